// Microfacet distributions D(alpha), alpha = angle between N and H, NoH = cos(alpha).
// All three are normalised like the Cook-Torrance Beckmann form of the lecture:
// the integral of D(alpha) cos(alpha) over the hemisphere of H is pi/4, so switching
// the distribution changes the shape of the highlight but not the light it reflects.

// Beckmann (1963) in the form used by Cook & Torrance (1982), m = RMS microfacet slope.
float D_beckmann(float NoH, float m) {
    float c2 = max(NoH * NoH, EPS);
    float m2 = m * m;
    return exp(-tan2_from_cos(NoH) / m2) / (4.0 * m2 * c2 * c2);
}

// Blinn (1977): cos^e(alpha) with e chosen so that D(beta) = D(0) / 2.
// Normalised: (e + 2) / 8 * cos^e(alpha), since the integral of cos^(e+1) over the
// hemisphere is 2 pi / (e + 2).
// cos(beta) by lab_cos_sin: a built-in cos off by 1e-4 (SwiftShader) moves e by 0.3 %.
float D_blinn(float NoH, float beta) {
    float e = log(2.0) / -log(lab_cos_sin(beta).x);
    return (e + 2.0) / 8.0 * pow(max(NoH, 0.0), e);
}

// Gaussian (Blinn 1977, Torrance-Sparrow): exp(-(c alpha)^2) with c = sqrt(ln 2) / beta,
// so that D(beta) = D(0) / 2. (The lecture slide writes c = sqrt(2) / beta, which puts the
// half-angle elsewhere; we keep the defining property D(beta) = 1/2.) Its hemisphere
// integral has no closed form, so the normaliser is Simpson's rule over [0, 6 beta], beyond
// which the shape is below 1e-10.
float D_gaussian_shape(float alpha, float beta) {
    return exp(-log(2.0) * sqr(alpha / beta));
}

float D_gaussian(float NoH, float beta) {
    const int STEPS = 48;  // even, for Simpson's rule
    float top = min(0.5 * PI, 6.0 * beta);
    float h = top / float(STEPS);
    float integral = 0.0;  // int_0^top shape(a) cos(a) sin(a) da
    for (int i = 0; i <= STEPS; ++i) {
        float a = float(i) * h;
        float weight = (i == 0 || i == STEPS) ? 1.0 : ((i - (i / 2) * 2) == 1 ? 4.0 : 2.0);
        vec2 cs = lab_cos_sin(a);
        integral += weight * D_gaussian_shape(a, beta) * cs.x * cs.y;
    }
    integral *= 2.0 * PI * h / 3.0;
    float alpha = angle_from_cos(NoH);
    return 0.25 * PI * D_gaussian_shape(alpha, beta) / integral;
}

// Trowbridge-Reitz / GGX (Walter et al. 2007), alpha = roughness; integrates to 1.
// d = cos^2 (a^2 - 1) + 1 = a^2 cos^2 + sin^2.
float D_ggx(float NoH, float alpha) {
    float a2 = alpha * alpha;
    float d = NoH * NoH * (a2 - 1.0) + 1.0;
    return a2 / (PI * d * d);
}

// The same D from sin^2 = |N x H|^2, which float32 keeps accurate near the peak (1 - cos^2
// there loses the digits that a sharp lobe, alpha = 0.01, depends on).
float D_ggx_sin2(float NoH, float sin2, float alpha) {
    float a2 = alpha * alpha;
    float d = a2 * NoH * NoH + sin2;
    return a2 / (PI * d * d);
}

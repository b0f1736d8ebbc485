// Exercise 06: microfacet distributions D(alpha), alpha = angle between N and H.
// This file stands in for shaders/terms/distributions.glsl: the library's Cook-Torrance
// model (shaders/brdfs/cook_torrance.glsl) calls these three functions.
// All three are normalised so that the integral of D(alpha) cos(alpha) over the
// hemisphere of H is pi/4 (the Cook-Torrance convention).

// Beckmann: exp(-tan^2(alpha) / m^2) / (4 m^2 cos^4(alpha)),  NoH = cos(alpha).
float D_beckmann(float NoH, float m) {
    float c2 = max(NoH * NoH, EPS);
    float m2 = m * m;
    return exp(-((1.0 - c2) / NoH) / m2) / (4.0 * m2 * c2 * c2);
}

// Blinn: (e + 2) / 8 * cos^e(alpha) with e = ln 2 / -ln(cos beta), so D(beta) = D(0) / 2.
float D_blinn(float NoH, float beta) {
    float e = log(2.0) / -log(cos(beta));
    return (e + 2.0) / 8.0 * pow(max(NoH, 0.0), e);
}

// Gaussian: g(alpha) = exp(-ln 2 (alpha / beta)^2), so g(beta) = 1/2, normalised as
// D = (pi / 4) g(alpha) / I with I = 2 pi * integral_0^{pi/2} g(a) cos(a) sin(a) da.
// g is below 1e-10 beyond 6 beta, so I is Simpson's rule in 48 steps over [0, min(pi/2, 6 beta)].
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
        integral += weight * D_gaussian_shape(a, beta) * cos(a) * sin(a);
    }
    integral *= 2.0 * PI * h / 3.0;
    float alpha = angle_from_cos(NoH);
    return 0.25 * PI * D_gaussian_shape(alpha, beta) / integral;
}

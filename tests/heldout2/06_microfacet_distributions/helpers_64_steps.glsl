// Exercise 06: microfacet distributions D(alpha), alpha = angle between N and H.
// This file stands in for shaders/terms/distributions.glsl: the library's Cook-Torrance
// model (shaders/brdfs/cook_torrance.glsl) calls these three functions.
// All three are normalised so that the integral of D(alpha) cos(alpha) over the
// hemisphere of H is pi/4 (the Cook-Torrance convention).

float cos4(float c) {
    float c2 = max(c * c, EPS);
    return c2 * c2;
}

// Beckmann: exp(-tan^2(alpha) / m^2) / (4 m^2 cos^4(alpha)),  NoH = cos(alpha).
float D_beckmann(float NoH, float m) {
    float t2 = tan2_from_cos(NoH);
    return exp(-t2 / sqr(m)) / (4.0 * sqr(m) * cos4(NoH));
}

// Blinn: (e + 2) / 8 * cos^e(alpha) with e = ln 2 / -ln(cos beta), so D(beta) = D(0) / 2.
float D_blinn(float NoH, float beta) {
    float e = log(0.5) / log(cos(beta));
    return (e + 2.0) * pow(max(NoH, 0.0), e) / 8.0;
}

// Gaussian: g(alpha) = exp(-ln 2 (alpha / beta)^2), so g(beta) = 1/2, normalised as
// D = (pi / 4) g(alpha) / I with I = 2 pi * integral_0^{pi/2} g(a) cos(a) sin(a) da,
// I computed numerically (see the handout: Simpson's rule over [0, min(pi/2, 6 beta)]).
float D_gaussian(float NoH, float beta) {
    float top = min(PI / 2.0, 6.0 * beta);
    const int n = 64;
    float h = top / float(n);
    float s = 0.0;
    for (int i = 0; i <= n; ++i) {
        float a = h * float(i);
        float f = exp(-log(2.0) * sqr(a / beta)) * sin(a) * cos(a);
        if (i == 0 || i == n) s += f;
        else if (i % 2 == 0) s += 2.0 * f;
        else s += 4.0 * f;
    }
    float I = 2.0 * PI * (h / 3.0) * s;
    float alpha = angle_from_cos(NoH);
    return PI * exp(-log(2.0) * sqr(alpha / beta)) / (4.0 * I);
}

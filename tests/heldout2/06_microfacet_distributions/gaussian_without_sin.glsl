// Exercise 06: microfacet distributions D(alpha), alpha = angle between N and H.
// This file stands in for shaders/terms/distributions.glsl: the library's Cook-Torrance
// model (shaders/brdfs/cook_torrance.glsl) calls these three functions.
// All three are normalised so that the integral of D(alpha) cos(alpha) over the
// hemisphere of H is pi/4 (the Cook-Torrance convention).

// Beckmann: exp(-tan^2(alpha) / m^2) / (4 m^2 cos^4(alpha)),  NoH = cos(alpha).
float D_beckmann(float NoH, float m) {
    float c2 = max(NoH * NoH, EPS);
    float m2 = m * m;
    return exp(-tan2_from_cos(NoH) / m2) / (4.0 * m2 * c2 * c2);
}

// Blinn: (e + 2) / 8 * cos^e(alpha) with e = ln 2 / -ln(cos beta), so D(beta) = D(0) / 2.
float D_blinn(float NoH, float beta) {
    float e = log(2.0) / -log(cos(beta));
    return (e + 2.0) / 8.0 * pow(max(NoH, 0.0), e);
}

// Gaussian: g(alpha) = exp(-ln 2 (alpha / beta)^2), so g(beta) = 1/2, normalised as
// D = (pi / 4) g(alpha) / I with I = 2 pi * integral_0^{pi/2} g(a) cos(a) sin(a) da,
// I computed numerically (see the handout: Simpson's rule over [0, min(pi/2, 6 beta)]).
float g_shape(float alpha, float beta) {
    float t = alpha / beta;
    return exp(-log(2.0) * t * t);
}

float D_gaussian(float NoH, float beta) {
    const int STEPS = 48;
    float top = min(0.5 * PI, 6.0 * beta);
    float dx = top / float(STEPS);
    float sum = g_shape(0.0, beta) + g_shape(top, beta) * cos(top);
    for (int i = 1; i < STEPS; ++i) {
        float a = float(i) * dx;
        float weight = (i % 2 == 1) ? 4.0 : 2.0;
        sum += weight * g_shape(a, beta) * cos(a);
    }
    float I = 2.0 * PI * sum * dx / 3.0;
    float alpha = angle_from_cos(NoH);
    return PI / 4.0 * g_shape(alpha, beta) / I;
}

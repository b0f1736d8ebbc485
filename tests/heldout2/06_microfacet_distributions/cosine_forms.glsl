// Exercise 06: microfacet distributions D(alpha), alpha = angle between N and H.
// This file stands in for shaders/terms/distributions.glsl: the library's Cook-Torrance
// model (shaders/brdfs/cook_torrance.glsl) calls these three functions.
// All three are normalised so that the integral of D(alpha) cos(alpha) over the
// hemisphere of H is pi/4 (the Cook-Torrance convention).

// Beckmann: exp(-tan^2(alpha) / m^2) / (4 m^2 cos^4(alpha)),  NoH = cos(alpha).
float D_beckmann(float NoH, float m) {
    float c2 = max(NoH * NoH, 1e-30);
    // -tan^2 = (c^2 - 1) / c^2
    float e = (c2 - 1.0) / (c2 * m * m);
    return 0.25 * exp(e) / (m * m * c2 * c2);
}

// Blinn: (e + 2) / 8 * cos^e(alpha) with e = ln 2 / -ln(cos beta), so D(beta) = D(0) / 2.
float D_blinn(float NoH, float beta) {
    float e = -1.0 / log2(cos(beta));   // ln 2 / -ln(cos beta)
    if (NoH <= 0.0) return 0.0;
    return 0.125 * (e + 2.0) * pow(NoH, e);
}

// Gaussian: g(alpha) = exp(-ln 2 (alpha / beta)^2), so g(beta) = 1/2, normalised as
// D = (pi / 4) g(alpha) / I with I = 2 pi * integral_0^{pi/2} g(a) cos(a) sin(a) da,
// I computed numerically (see the handout: Simpson's rule over [0, min(pi/2, 6 beta)]).
float shape(float a, float beta) {
    return exp(-0.69314718 * (a * a) / (beta * beta));
}

float D_gaussian(float NoH, float beta) {
    const int PAIRS = 24;
    float top = min(0.5 * PI, 6.0 * beta);
    float h = top / float(2 * PAIRS);
    float sum = 0.0;
    for (int k = 0; k < PAIRS; ++k) {
        float a0 = float(2 * k) * h;
        float a1 = a0 + h;
        float a2 = a1 + h;
        sum += shape(a0, beta) * cos(a0) * sin(a0)
             + 4.0 * shape(a1, beta) * cos(a1) * sin(a1)
             + shape(a2, beta) * cos(a2) * sin(a2);
    }
    float I = 2.0 * PI * sum * h / 3.0;
    return (PI / 4.0) * shape(angle_from_cos(NoH), beta) / I;
}

// Exercise 06: microfacet distributions D(alpha), alpha = angle between N and H.
// This file stands in for shaders/terms/distributions.glsl: the library's Cook-Torrance
// model (shaders/brdfs/cook_torrance.glsl) calls these three functions.
// All three are normalised so that the integral of D(alpha) cos(alpha) over the
// hemisphere of H is pi/4 (the Cook-Torrance convention).

// Beckmann: exp(-tan^2(alpha) / m^2) / (4 m^2 cos^4(alpha)),  NoH = cos(alpha).
float D_beckmann(float NoH, float m) {
    float cos2 = max(NoH * NoH, EPS);
    // tan^2 = sin^2 / cos^2 = (1 - cos^2) / cos^2
    float slope2 = (1.0 - cos2) / cos2;
    return exp(-slope2 / (m * m)) / (4.0 * m * m * cos2 * cos2);
}

// Blinn: (e + 2) / 8 * cos^e(alpha) with e = ln 2 / -ln(cos beta), so D(beta) = D(0) / 2.
float D_blinn(float NoH, float beta) {
    float n = -log(2.0) / log(cos(beta));
    return 0.125 * (n + 2.0) * exp(n * log(max(NoH, 1e-8)));
}

// Gaussian: g(alpha) = exp(-ln 2 (alpha / beta)^2), so g(beta) = 1/2, normalised as
// D = (pi / 4) g(alpha) / I with I = 2 pi * integral_0^{pi/2} g(a) cos(a) sin(a) da,
// I computed numerically (see the handout: Simpson's rule over [0, min(pi/2, 6 beta)]).
float D_gaussian(float NoH, float beta) {
    // trapezoid rule with many steps over [0, min(pi/2, 6 beta)]
    const int STEPS = 256;
    float b = min(0.5 * PI, 6.0 * beta);
    float h = b / float(STEPS);
    float sum = 0.5 * exp(-log(2.0) * sqr(b / beta)) * cos(b) * sin(b);
    for (int i = 1; i < STEPS; i++) {
        float a = h * float(i);
        sum += exp(-log(2.0) * sqr(a / beta)) * cos(a) * sin(a);
    }
    float norm = 2.0 * PI * h * sum;
    float alpha = atan(sqrt(max(1.0 - NoH * NoH, 0.0)), NoH);
    return 0.25 * PI * exp(-log(2.0) * sqr(alpha / beta)) / norm;
}

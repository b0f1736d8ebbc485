// Exercise 06: microfacet distributions D(alpha), alpha = angle between N and H.
// This file stands in for shaders/terms/distributions.glsl: the library's Cook-Torrance
// model (shaders/brdfs/cook_torrance.glsl) calls these three functions.
// All three are normalised so that the integral of D(alpha) cos(alpha) over the
// hemisphere of H is pi/4 (the Cook-Torrance convention).

// Beckmann: exp(-tan^2(alpha) / m^2) / (4 m^2 cos^4(alpha)),  NoH = cos(alpha).
float D_beckmann(float NoH, float m) {
    float cos2 = max(NoH * NoH, EPS);
    float tan2 = (1.0 - cos2) / cos2;
    float D = exp(tan2 / (m * m));
    return D / (4.0 * m * m * cos2 * cos2);
}

// Blinn: (e + 2) / 8 * cos^e(alpha) with e = ln 2 / -ln(cos beta), so D(beta) = D(0) / 2.
float D_blinn(float NoH, float beta) {
    float e = log(2.0) / -log(cos(beta));
    return (e + 2.0) / 8.0 * pow(max(NoH, 0.0), e);
}

// Gaussian: g(alpha) = exp(-ln 2 (alpha / beta)^2), so g(beta) = 1/2, normalised as
// D = (pi / 4) g(alpha) / I with I = 2 pi * integral_0^{pi/2} g(a) cos(a) sin(a) da,
// I computed numerically (see the handout: Simpson's rule over [0, min(pi/2, 6 beta)]).
float gauss_shape(float a, float beta) {
    return exp(-log(2.0) * sqr(a / beta));
}

float D_gaussian(float NoH, float beta) {
    const int N_STEPS = 48;
    float upper = min(0.5 * PI, 6.0 * beta);
    float h = upper / float(N_STEPS);
    float I = 0.0;
    for (int i = 0; i <= N_STEPS; i++) {
        float a = h * float(i);
        float w = 2.0;
        if (i == 0 || i == N_STEPS) w = 1.0;
        else if (i % 2 == 1) w = 4.0;
        I += w * gauss_shape(a, beta) * cos(a) * sin(a);
    }
    I *= 2.0 * PI * h / 3.0;
    return 0.25 * PI * gauss_shape(angle_from_cos(NoH), beta) / I;
}

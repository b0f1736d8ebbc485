// Exercise 06: microfacet distributions D(alpha), alpha = angle between N and H.
// This file stands in for shaders/terms/distributions.glsl: the library's Cook-Torrance
// model (shaders/brdfs/cook_torrance.glsl) calls these three functions.
// All three are normalised so that the integral of D(alpha) cos(alpha) over the
// hemisphere of H is pi/4 (the Cook-Torrance convention).

// Beckmann: exp(-tan^2(alpha) / m^2) / (4 m^2 cos^4(alpha)),  NoH = cos(alpha).
float D_beckmann(float NoH, float m) {
    // TODO: the Beckmann distribution (guard cos^4 against 0 with EPS).
    return 1.0;
}

// Blinn: (e + 2) / 8 * cos^e(alpha) with e = ln 2 / -ln(cos beta), so D(beta) = D(0) / 2.
float D_blinn(float NoH, float beta) {
    // TODO: the exponent e from the half-angle beta, then the normalised cosine power.
    return 1.0;
}

// Gaussian: g(alpha) = exp(-ln 2 (alpha / beta)^2), so g(beta) = 1/2, normalised as
// D = (pi / 4) g(alpha) / I with I = 2 pi * integral_0^{pi/2} g(a) cos(a) sin(a) da,
// I computed numerically (see the handout: Simpson's rule over [0, min(pi/2, 6 beta)]).
float D_gaussian(float NoH, float beta) {
    // TODO: alpha from NoH (angle_from_cos), the shape g, the integral I, then D.
    return 1.0;
}

// Exercise 06: microfacet distributions D(alpha), alpha = angle between N and H.
// This file stands in for shaders/terms/distributions.glsl: the library's Cook-Torrance
// model (shaders/brdfs/cook_torrance.glsl) calls these three functions.
// All three are normalised so that the integral of D(alpha) cos(alpha) over the
// hemisphere of H is pi/4 (the Cook-Torrance convention).

// Beckmann: exp(-tan^2(alpha) / m^2) / (4 m^2 cos^4(alpha)),  NoH = cos(alpha).
float D_beckmann(float NoH, float m) {
    float c2 = max(NoH * NoH, EPS);
    float m2 = m * m;
    // -tan^2 / m^2 = (cos^2 - 1) / (cos^2 m^2)
    float e = exp((c2 - 1.0) / (c2 * m2));
    return e / (4.0 * m2 * c2 * c2);
}

float D_blinn(float NoH, float beta) {
    float e = log(0.5) / log(cos(beta));
    float norm = 0.125 * (e + 2.0);
    return norm * pow(max(NoH, 0.0), e);
}

float gauss_g(float a, float beta) {
    float t = a / beta;
    return exp(-0.6931471805599453 * t * t);
}

float D_gaussian(float NoH, float beta) {
    // trapezoid rule with 256 steps of int_0^top g(a) cos(a) sin(a) da
    const int STEPS = 256;
    float top = min(0.5 * PI, 6.0 * beta);
    float h = top / float(STEPS);
    float sum = 0.5 * (gauss_g(0.0, beta) * 0.0 + gauss_g(top, beta) * cos(top) * sin(top));
    for (int i = 1; i < STEPS; ++i) {
        float a = h * float(i);
        sum += gauss_g(a, beta) * 0.5 * sin(2.0 * a);
    }
    float I = 2.0 * PI * h * sum;
    return PI / 4.0 * gauss_g(angle_from_cos(NoH), beta) / I;
}

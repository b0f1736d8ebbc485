// Correct rewrite of exercise 06: tan^2 from N.H inline, pow as exp(e log x), the
// Gaussian's integral by Simpson's rule in 64 steps of sin(2a) / 2 and acos for alpha.

float D_beckmann(float NoH, float m) {
    float c2 = max(NoH * NoH, EPS);
    float tan2 = max(1.0 - NoH * NoH, 0.0) / max(NoH * NoH, 1e-30);
    return exp(-tan2 / (m * m)) / (4.0 * m * m * c2 * c2);
}

float D_blinn(float NoH, float beta) {
    float e = -0.693147180559945 / log(cos(beta));
    float lobe = NoH > 0.0 ? exp(e * log(NoH)) : 0.0;
    return 0.125 * (e + 2.0) * lobe;
}

float gaussian_g(float a, float beta) {
    float r = a / beta;
    return exp(-0.693147180559945 * r * r);
}

float D_gaussian(float NoH, float beta) {
    float top = min(0.5 * PI, 6.0 * beta);
    float h = top / 64.0;
    float sum = 0.0;
    for (int i = 0; i <= 64; i++) {
        float a = h * float(i);
        float w = (i == 0 || i == 64) ? 1.0 : (i % 2 == 1 ? 4.0 : 2.0);
        sum += w * gaussian_g(a, beta) * 0.5 * sin(2.0 * a);
    }
    float integral = 2.0 * PI * sum * h / 3.0;
    float alpha = acos(clamp(NoH, -1.0, 1.0));
    return PI * gaussian_g(alpha, beta) / (4.0 * integral);
}

// Correct rewrite of exercise 06: Beckmann as exp((c^2 - 1) / (m^2 c^2)), Blinn's exponent
// from log base 2, the Gaussian's integral by the trapezoid rule in 400 steps.

float D_beckmann(float NoH, float m) {
    float c2 = max(NoH * NoH, EPS);
    float m2 = m * m;
    return exp((min(NoH * NoH, 1.0) - 1.0) / (m2 * max(NoH * NoH, 1e-30))) / (4.0 * m2 * c2 * c2);
}

float D_blinn(float NoH, float beta) {
    float e = -1.0 / log2(cos(beta));
    return (e + 2.0) / 8.0 * pow(max(NoH, 0.0), e);
}

float D_gaussian(float NoH, float beta) {
    const int N = 400;
    float top = min(0.5 * PI, 6.0 * beta);
    float h = top / float(N);
    float integral = 0.0;
    for (int i = 0; i <= N; ++i) {
        float a = float(i) * h;
        float f = exp(-log(2.0) * (a / beta) * (a / beta)) * cos(a) * sin(a);
        integral += (i == 0 || i == N) ? 0.5 * f : f;
    }
    integral *= 2.0 * PI * h;
    float alpha = angle_from_cos(NoH);
    return 0.25 * PI * exp(-log(2.0) * (alpha / beta) * (alpha / beta)) / integral;
}

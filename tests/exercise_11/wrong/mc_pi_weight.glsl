// WRONG: stratified uniform hemisphere sampling weighted by pi / N where 2 pi / N belongs
// HINT: 2π
// (a student's Monte Carlo version: the pdf of uniform directions is 1 / (2 pi)).

const int STRATA = 128;

float directional_albedo(vec3 V, vec3 N, vec3 X, vec3 Y) {
    vec3 sum = vec3(0.0);
    for (int i = 0; i < STRATA; ++i) {
        for (int j = 0; j < STRATA; ++j) {
            float u1 = (float(i) + 0.5) / float(STRATA);
            float u2 = (float(j) + 0.5) / float(STRATA);
            float c = u1;
            float s = sqrt(1.0 - c * c);
            float phi = 2.0 * PI * u2;
            vec3 L = s * cos(phi) * X + s * sin(phi) * Y + c * N;
            sum += BRDF(L, V, N, X, Y) * c;
        }
    }
    vec3 albedo = sum * PI / float(STRATA * STRATA);
    return max(albedo.r, max(albedo.g, albedo.b));
}

float reciprocity_error(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {
    vec3 a = BRDF(L, V, N, X, Y);
    vec3 b = BRDF(V, L, N, X, Y);
    vec3 d = abs(a - b) / max(max(a, b), vec3(EPS));
    return max(d.r, max(d.g, d.b));
}

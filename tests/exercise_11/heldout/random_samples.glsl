// WRONG: plain (unstratified) uniform hemisphere Monte Carlo with 16,384 samples from a hash:
// unbiased, but its noise at grazing views is far above the tolerance the README states
// HINT: noise
// @include terms/brdf_stand_in.glsl

float hash01(uint x) {
    x ^= x >> 16; x *= 0x7feb352du; x ^= x >> 15; x *= 0x846ca68bu; x ^= x >> 16;
    return float(x) / 4294967296.0;
}

float directional_albedo(vec3 V, vec3 N, vec3 X, vec3 Y) {
    const int COUNT = 16384;
    vec3 sum = vec3(0.0);
    for (int k = 0; k < COUNT; ++k) {
        float c = hash01(uint(2 * k + 1));
        float phi = 2.0 * PI * hash01(uint(2 * k + 2) * 7919u);
        float s = sqrt(max(1.0 - c * c, 0.0));
        vec3 L = s * cos(phi) * X + s * sin(phi) * Y + c * N;
        sum += BRDF(L, V, N, X, Y) * c;
    }
    vec3 albedo = sum * (2.0 * PI / float(COUNT));
    return max(albedo.r, max(albedo.g, albedo.b));
}

float reciprocity_error(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {
    vec3 a = BRDF(L, V, N, X, Y);
    vec3 b = BRDF(V, L, N, X, Y);
    vec3 d = abs(a - b) / max(max(a, b), vec3(EPS));
    return max(d.r, max(d.g, d.b));
}

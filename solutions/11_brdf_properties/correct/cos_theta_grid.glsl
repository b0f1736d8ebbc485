// Correct: the midpoint rule in (cos theta, phi) instead of (theta, phi). With u = cos theta
// the solid angle is du dphi, so no sin(theta) appears; the integrand is f(L, V) u.
// @include terms/brdf_stand_in.glsl

const int N_U = 64;
const int N_PHI = 256;

float directional_albedo(vec3 V, vec3 N, vec3 X, vec3 Y) {
    float du = 1.0 / float(N_U);
    float dphi = 2.0 * PI / float(N_PHI);
    vec3 total = vec3(0.0);
    for (int i = 0; i < N_U; ++i) {
        float u = (float(i) + 0.5) * du;
        float s = sqrt(1.0 - u * u);
        for (int j = 0; j < N_PHI; ++j) {
            float phi = (float(j) + 0.5) * dphi;
            vec3 L = normalize(s * cos(phi) * X + s * sin(phi) * Y + u * N);
            total += BRDF(L, V, N, X, Y) * u;
        }
    }
    total *= du * dphi;
    return max(max(total.x, total.y), total.z);
}

float reciprocity_error(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {
    vec3 forward = BRDF(L, V, N, X, Y);
    vec3 backward = BRDF(V, L, N, X, Y);
    float worst = 0.0;
    for (int c = 0; c < 3; ++c) {
        float top = max(max(forward[c], backward[c]), EPS);
        worst = max(worst, abs(forward[c] - backward[c]) / top);
    }
    return worst;
}

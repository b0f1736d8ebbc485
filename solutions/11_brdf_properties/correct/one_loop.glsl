// Correct: the handout's midpoint rule in one loop over all cells, with the cell's weight
// in a helper and the per-channel maximum written out.
// @include terms/brdf_stand_in.glsl

const int N_THETA = 64;
const int N_PHI = 256;

vec3 cell_direction(float theta, float phi, vec3 N, vec3 X, vec3 Y) {
    return sin(theta) * (cos(phi) * X + sin(phi) * Y) + cos(theta) * N;
}

float largest(vec3 v) {
    return max(v.r, max(v.g, v.b));
}

float directional_albedo(vec3 V, vec3 N, vec3 X, vec3 Y) {
    float dtheta = (PI / 2.0) / float(N_THETA);
    float dphi = (2.0 * PI) / float(N_PHI);
    vec3 sum = vec3(0.0);
    for (int k = 0; k < N_THETA * N_PHI; ++k) {
        float theta = (float(k / N_PHI) + 0.5) * dtheta;
        float phi = (float(k - (k / N_PHI) * N_PHI) + 0.5) * dphi;
        vec3 L = cell_direction(theta, phi, N, X, Y);
        sum += BRDF(L, V, N, X, Y) * cos(theta) * sin(theta);
    }
    return largest(sum * dtheta * dphi);
}

float reciprocity_error(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {
    vec3 f_lv = BRDF(L, V, N, X, Y);
    vec3 f_vl = BRDF(V, L, N, X, Y);
    return largest(abs(f_lv - f_vl) / max(max(f_lv, f_vl), vec3(EPS)));
}

// Exercise 11: BRDF properties as code. Two tests of whatever BRDF(L, V, N, X, Y) the
// grader links in (a library model, or one broken on purpose), which this file calls but
// does not define. Directions are unit vectors in the frame X, Y, N the grader passes.
// @include terms/brdf_stand_in.glsl

const int N_THETA = 64;   // the midpoint rule's steps in theta over [0, pi/2]
const int N_PHI = 256;    // and in phi over [0, 2 pi)

float directional_albedo(vec3 V, vec3 N, vec3 X, vec3 Y) {
    const float DT = 0.5 * PI / float(N_THETA);
    const float DP = 2.0 * PI / float(N_PHI);
    vec3 sum = vec3(0.0);
    for (int j = 0; j < N_PHI; j++) {
        float phi = DP * (float(j) + 0.5);
        vec3 T = cos(phi) * X + sin(phi) * Y;  // the azimuth's direction in the tangent plane
        for (int i = 0; i < N_THETA; i++) {
            float theta = DT * (float(i) + 0.5);
            vec3 L = sin(theta) * T + cos(theta) * N;
            sum += BRDF(L, V, N, X, Y) * (0.5 * sin(2.0 * theta));  // cos * sin
        }
    }
    sum *= DT * DP;
    return max(sum.r, max(sum.g, sum.b));
}

float reciprocity_error(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {
    vec3 forward = BRDF(L, V, N, X, Y);
    vec3 backward = BRDF(V, L, N, X, Y);
    vec3 denom = max(forward, backward);
    denom = max(denom, vec3(EPS));
    vec3 rel = abs(forward - backward) / denom;
    return max(max(rel.r, rel.g), rel.b);
}

// Exercise 11: BRDF properties as code. Two tests of whatever BRDF(L, V, N, X, Y) the
// grader links in (a library model, or one broken on purpose), which this file calls but
// does not define. Directions are unit vectors in the frame X, Y, N the grader passes.
// @include terms/brdf_stand_in.glsl

const int N_THETA = 64;   // the midpoint rule's steps in theta over [0, pi/2]
const int N_PHI = 256;    // and in phi over [0, 2 pi)

// a(V) by the midpoint rule in (cos theta, phi): dw = d(cos theta) dphi, weight cos theta.
float directional_albedo(vec3 V, vec3 N, vec3 X, vec3 Y) {
    float dmu = 1.0 / float(N_THETA);
    float dphi = 2.0 * PI / float(N_PHI);
    vec3 total = vec3(0.0);
    for (int i = 0; i < N_THETA; ++i) {
        float mu = (float(i) + 0.5) * dmu;
        float s = sqrt(max(1.0 - mu * mu, 0.0));
        for (int j = 0; j < N_PHI; ++j) {
            float phi = (float(j) + 0.5) * dphi;
            vec3 L = mu * N + s * (cos(phi) * X + sin(phi) * Y);
            total += mu * BRDF(L, V, N, X, Y);
        }
    }
    total *= dmu * dphi;
    return max(max(total.x, total.y), total.z);
}

float reciprocity_error(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {
    vec3 f1 = BRDF(L, V, N, X, Y);
    vec3 f2 = BRDF(V, L, N, X, Y);
    float worst = 0.0;
    for (int k = 0; k < 3; ++k) {
        float big = max(max(f1[k], f2[k]), EPS);
        worst = max(worst, abs(f1[k] - f2[k]) / big);
    }
    return worst;
}

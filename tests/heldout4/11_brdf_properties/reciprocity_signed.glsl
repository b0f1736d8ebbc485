// Exercise 11: BRDF properties as code. Two tests of whatever BRDF(L, V, N, X, Y) the
// grader links in (a library model, or one broken on purpose), which this file calls but
// does not define. Directions are unit vectors in the frame X, Y, N the grader passes.
// @include terms/brdf_stand_in.glsl

const int N_THETA = 64;   // the midpoint rule's steps in theta over [0, pi/2]
const int N_PHI = 256;    // and in phi over [0, 2 pi)

// The directional albedo of the BRDF for the view V: the integral over the upper hemisphere
// of f(L, V) cos(theta_L) dw_L, per colour channel; the largest channel is returned (a
// model conserves energy when it is at most 1 for every V). In (theta, phi) the solid angle
// is dw = sin(theta) dtheta dphi, so each cell of the midpoint rule weighs
// f cos(theta) sin(theta) dtheta dphi.
float directional_albedo(vec3 V, vec3 N, vec3 X, vec3 Y) {
    float dtheta = 0.5 * PI / float(N_THETA);
    float dphi = 2.0 * PI / float(N_PHI);
    vec3 total = vec3(0.0);
    for (int i = 0; i < N_THETA; ++i) {
        float theta = (float(i) + 0.5) * dtheta;
        float c = cos(theta);
        float s = sin(theta);
        vec3 ring = vec3(0.0);
        for (int j = 0; j < N_PHI; ++j) {
            float phi = (float(j) + 0.5) * dphi;
            vec3 L = s * cos(phi) * X + s * sin(phi) * Y + c * N;
            ring += BRDF(L, V, N, X, Y);
        }
        total += ring * (c * s * dtheta * dphi);
    }
    return max(total.r, max(total.g, total.b));
}

// Helmholtz reciprocity says f(L, V) = f(V, L). The error is the largest relative difference
// over the colour channels, relative to the larger of the two values (EPS keeps 0 / 0 at 0).
float reciprocity_error(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {
    vec3 a = BRDF(L, V, N, X, Y);
    vec3 b = BRDF(V, L, N, X, Y);
    vec3 error = (a - b) / max(max(a, b), vec3(EPS));
    return max(error.r, max(error.g, error.b));
}

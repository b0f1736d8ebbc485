// @title Exercise 14: the reflection equation under an environment
// @formula L_o(V) = integral of f_r(L, V) L_i(L) cos(theta_L) dL  ~  (1/n) sum f_r L_i cos / p(L_k)
// @source J. T. Kajiya, "The Rendering Equation", SIGGRAPH 1986.
// @source M. Pharr, W. Jakob and G. Humphreys, "Physically Based Rendering", 3rd ed., 13.2 and 13.6.
// The model is the library's blinn_phong: call BRDF(L, V, N, X, Y) for f_r.
// Given: PI, INV_PI, to_world(v, X, Y, N), BRDF(L, V, N, X, Y), environment(L) (the map's
// radiance L_i arriving from direction L) and random2() (two new uniform numbers in [0, 1)).

// One sample's contribution f_r(L, V) L_i(L) cos(theta_L) / p(L), for one direction L drawn
// from the unit numbers u with a density p of your choice (here: uniform over the hemisphere).
vec3 radiance_sample(vec2 u, vec3 V, vec3 N, vec3 X, vec3 Y) {
    // uniform over the whole sphere, p = 1 / (4 pi); the lower half contributes 0
    float z = 1.0 - 2.0 * u.x;
    float r = sqrt(max(1.0 - z * z, 0.0));
    float phi = 2.0 * PI * u.y;
    vec3 L = to_world(vec3(r * cos(phi), r * sin(phi), z), X, Y, N);
    float NoL = dot(N, L);
    if (NoL <= 0.0) return vec3(0.0);
    return 4.0 * PI * BRDF(L, V, N, X, Y) * environment(L) * NoL;
}

// The estimate of L_o(V): the mean of n samples, each from two new random numbers.
vec3 estimate_radiance(int n, vec3 V, vec3 N, vec3 X, vec3 Y) {
    vec3 sum = vec3(0.0);
    for (int i = 0; i < n; ++i) {
        sum += radiance_sample(random2(), V, N, X, Y);
    }
    return sum / float(n);
}

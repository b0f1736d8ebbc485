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
    // Uniform over the hemisphere: cos(theta) = u.x, phi = 2 pi u.y, p = 1 / (2 pi).
    float cos_t = u.x;
    float sin_t = sqrt(max(1.0 - cos_t * cos_t, 0.0));
    float phi = 2.0 * PI * u.y;
    vec3 L = to_world(vec3(sin_t * cos(phi), sin_t * sin(phi), cos_t), X, Y, N);
    float NoL = dot(N, L);
    if (NoL <= 0.0) return vec3(0.0);
    float pdf = 0.5 * INV_PI;
    return BRDF(L, V, N, X, Y) * environment(L) * NoL / pdf;
}

// The estimate of L_o(V): the mean of n samples, each from two new random numbers.
vec3 estimate_radiance(int n, vec3 V, vec3 N, vec3 X, vec3 Y) {
    vec3 sum = vec3(0.0);
    for (int i = 0; i < n; ++i) {
        sum += radiance_sample(random2(), V, N, X, Y);
    }
    return sum;
}

// WRONG: samples over the whole sphere weighted by the hemisphere's pdf 1/(2 pi)
// HINT: 4π
// @title Exercise 14: the reflection equation under an environment
// @formula L_o(V) = integral of f_r(L, V) L_i(L) cos(theta_L) dL  ~  (1/n) sum f_r L_i cos / p(L_k)
// @source J. T. Kajiya, "The Rendering Equation", SIGGRAPH 1986.
// @source M. Pharr, W. Jakob and G. Humphreys, "Physically Based Rendering", 3rd ed., 13.2 and 13.6.
// The model is the library's blinn_phong: call BRDF(L, V, N, X, Y) for f_r.
// Given: PI, INV_PI, to_world(v, X, Y, N), BRDF(L, V, N, X, Y), environment(L) (the map's
// radiance L_i arriving from direction L) and random2() (two new uniform numbers in [0, 1)).

// One sample's contribution f_r(L, V) L_i(L) cos(theta_L) / p(L), for one direction L drawn
// from the unit numbers u with a density p of your choice (here: uniform over the whole sphere).
vec3 radiance_sample(vec2 u, vec3 V, vec3 N, vec3 X, vec3 Y) {
    // Uniform over the whole sphere, p = 1 / (4 pi): half the directions lie below the
    // surface and add nothing, but the mean is right.
    float c = 1.0 - 2.0 * u.x;
    float s = sqrt(max(1.0 - c * c, 0.0));
    float phi = 2.0 * PI * u.y;
    vec3 L = to_world(vec3(s * cos(phi), s * sin(phi), c), X, Y, N);
    float NoL = max(dot(N, L), 0.0);
    return BRDF(L, V, N, X, Y) * environment(L) * NoL * 2.0 * PI;
}

// The estimate of L_o(V): the mean of n samples, each from two new random numbers.
vec3 estimate_radiance(int n, vec3 V, vec3 N, vec3 X, vec3 Y) {
    vec3 sum = vec3(0.0);
    for (int i = 0; i < n; ++i) {
        sum += radiance_sample(random2(), V, N, X, Y);
    }
    return sum / float(n);
}

// @title Exercise 14: the reflection equation under an environment
// @formula L_o(V) = integral of f_r(L, V) L_i(L) cos(theta_L) dL  ~  (1/n) sum f_r L_i cos / p(L_k)
// @source J. T. Kajiya, "The Rendering Equation", SIGGRAPH 1986.
// @source M. Pharr, W. Jakob and G. Humphreys, "Physically Based Rendering", 3rd ed., 13.2 and 13.6.
// The model is the library's blinn_phong: call BRDF(L, V, N, X, Y) for f_r.
// Given: PI, INV_PI, to_world(v, X, Y, N), BRDF(L, V, N, X, Y), environment(L) (the map's
// radiance L_i arriving from direction L) and random2() (two new uniform numbers in [0, 1)).

// One sample's contribution f_r(L, V) L_i(L) cos(theta_L) / p(L), for one direction L drawn
// from the unit numbers u with a density p of your choice.
vec3 radiance_sample(vec2 u, vec3 V, vec3 N, vec3 X, vec3 Y) {
    // TODO: a direction L from u, drawn with a density p of your choice over the hemisphere
    //       around N (uniform: cos = u.x; cosine-weighted: r = sqrt(u.x)), carried into the
    //       shading frame with to_world (the frame is not the coordinate axes on a sphere).
    // TODO: p(L), the density of that choice over solid angle.
    // TODO: f_r L_i cos(theta_L) / p(L), and zero where L lies below the surface (N.L <= 0).
    return vec3(0.0);
}

// The estimate of L_o(V): the mean of n samples, each from two new random numbers.
vec3 estimate_radiance(int n, vec3 V, vec3 N, vec3 X, vec3 Y) {
    // TODO: add n samples, each from its own random2(), and return their mean.
    return vec3(0.0);
}

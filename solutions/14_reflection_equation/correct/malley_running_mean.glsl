// @title Exercise 14: the reflection equation under an environment
// @formula L_o(V) = integral of f_r(L, V) L_i(L) cos(theta_L) dL  ~  (1/n) sum f_r L_i cos / p(L_k)
// @source J. T. Kajiya, "The Rendering Equation", SIGGRAPH 1986.
// @source M. Pharr, W. Jakob and G. Humphreys, "Physically Based Rendering", 3rd ed., 13.2 and 13.6.
// The model is the library's blinn_phong: call BRDF(L, V, N, X, Y) for f_r.
// Given: PI, INV_PI, to_world(v, X, Y, N), BRDF(L, V, N, X, Y), environment(L) (the map's
// radiance L_i arriving from direction L) and random2() (two new uniform numbers in [0, 1)).

// One sample's contribution f_r(L, V) L_i(L) cos(theta_L) / p(L), for one direction L drawn
// from the unit numbers u with a density p of your choice (here: cosine-weighted).
vec3 radiance_sample(vec2 u, vec3 V, vec3 N, vec3 X, vec3 Y) {
    // Cosine-weighted by Malley's method: a point on the unit disk, lifted to the hemisphere.
    float angle = 2.0 * PI * u.x;
    float radius = sqrt(u.y);
    vec2 disk = radius * vec2(cos(angle), sin(angle));
    float z = sqrt(max(0.0, 1.0 - dot(disk, disk)));
    vec3 L = normalize(disk.x * X + disk.y * Y + z * N);
    float pdf = max(dot(N, L), 0.0) / PI;
    return pdf > 0.0 ? BRDF(L, V, N, X, Y) * environment(L) * dot(N, L) / pdf : vec3(0.0);
}

vec3 estimate_radiance(int n, vec3 V, vec3 N, vec3 X, vec3 Y) {
    vec3 mean = vec3(0.0);
    for (int k = 1; k <= n; k++) {
        mean += (radiance_sample(random2(), V, N, X, Y) - mean) / float(k);  // running mean
    }
    return mean;
}

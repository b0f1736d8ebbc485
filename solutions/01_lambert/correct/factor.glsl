// @model lambert
// @title Exercise 01: Lambert, ideal diffuse reflection
// @formula f_r = albedo / pi   (0 when L or V is below the surface)
// @source J. H. Lambert, Photometria, 1760.
// @param albedo color 0.8 0.8 0.8 | fraction of incident light reflected (diffuse albedo)

// Correct rewrite: a helper function and a 0/1 factor instead of an early return.
float above(vec3 N, vec3 D) {
    return dot(D, N) > 0.0 ? 1.0 : 0.0;
}

vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {
    float lit = above(N, L) * above(N, V);
    return lit * (albedo / PI);
}

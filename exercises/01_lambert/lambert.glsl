// @model lambert
// @title Exercise 01: Lambert, ideal diffuse reflection
// @formula f_r = albedo / pi   (0 when L or V is below the surface)
// @source J. H. Lambert, Photometria, 1760.
// @param albedo color 0.8 0.8 0.8 | fraction of incident light reflected (diffuse albedo)

vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {
    // TODO: return 0 when the light or the viewer is below the surface (N.L <= 0 or N.V <= 0).
    // TODO: a perfectly diffuse surface reflects the same radiance in every direction;
    //       return the constant that makes its albedo equal to `albedo`.
    return vec3(1.0, 0.0, 1.0);
}

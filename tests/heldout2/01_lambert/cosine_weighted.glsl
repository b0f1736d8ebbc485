// @model lambert
// @title Exercise 01: Lambert, ideal diffuse reflection
// @formula f_r = albedo / pi   (0 when L or V is below the surface)
// @source J. H. Lambert, Photometria, 1760.
// @param albedo color 0.8 0.8 0.8 | fraction of incident light reflected (diffuse albedo)

vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {
    float cosL = dot(N, L);
    float cosV = dot(N, V);
    // below the surface: nothing is reflected
    if (cosL <= 0.0 || cosV <= 0.0) {
        return vec3(0.0);
    }
    // diffuse: albedo / pi, weighted by the cosine of the light
    return albedo / PI * cosL;
}

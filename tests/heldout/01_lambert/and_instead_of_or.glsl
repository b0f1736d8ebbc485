// @model lambert
// @title Exercise 01: Lambert, ideal diffuse reflection
// @formula f_r = albedo / pi   (0 when L or V is below the surface)
// @source J. H. Lambert, Photometria, 1760.
// @param albedo color 0.8 0.8 0.8 | fraction of incident light reflected (diffuse albedo)

vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {
    float cos_in = dot(N, L);
    float cos_out = dot(N, V);
    // nothing is reflected when we are under the surface
    if (cos_in <= 0.0 && cos_out <= 0.0) {
        return vec3(0.0);
    }
    // integrating c * cos over the hemisphere gives c * pi, so c = albedo / pi
    return albedo / PI;
}

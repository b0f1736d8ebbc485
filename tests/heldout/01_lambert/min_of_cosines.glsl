// @model lambert
// @title Exercise 01: Lambert, ideal diffuse reflection
// @formula f_r = albedo / pi   (0 when L or V is below the surface)
// @source J. H. Lambert, Photometria, 1760.
// @param albedo color 0.8 0.8 0.8 | fraction of incident light reflected (diffuse albedo)

vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {
    // both directions must be in the upper hemisphere
    float lowest = min(dot(N, L), dot(N, V));
    if (lowest <= 0.0) {
        return vec3(0.0);
    }
    const float one_over_pi = 1.0 / 3.14159265358979;
    return one_over_pi * albedo;
}

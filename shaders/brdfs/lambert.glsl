// @model lambert
// @title Lambert: ideal diffuse reflection
// @property reciprocal isotropic energy-conserving
// @formula f_r = albedo / pi
// @source J. H. Lambert, Photometria, 1760.
// @param albedo color 0.8 0.8 0.8 | fraction of incident light reflected (diffuse albedo)

vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {
    if (dot(N, L) <= 0.0 || dot(N, V) <= 0.0) return vec3(0.0);
    return albedo * INV_PI;
}

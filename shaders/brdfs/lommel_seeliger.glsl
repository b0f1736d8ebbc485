// @model lommel_seeliger
// @title Lommel-Seeliger: single scattering in a dusty layer (the full moon)
// @property reciprocal isotropic energy-conserving
// @formula f_r = albedo / (4 pi (N.L + N.V))
// @source E. Lommel (1887), H. von Seeliger (1888); see Hapke, Theory of Reflectance Spectroscopy, 2012.
// @param albedo color 0.8 0.8 0.8 | single-scattering albedo of the dust

vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {
    float NoL = dot(N, L);
    float NoV = dot(N, V);
    if (NoL <= 0.0 || NoV <= 0.0) return vec3(0.0);
    return albedo / (4.0 * PI * (NoL + NoV));
}

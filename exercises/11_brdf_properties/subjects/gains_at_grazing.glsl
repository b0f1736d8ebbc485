// @model gains_at_grazing
// @title A microfacet BRDF that forgot its shadowing-masking term G (broken on purpose)
// @formula f_r = kd / pi + ks D / (4 (N.L)(N.V)): without G, the microfacets' projected area
// @formula outgrows the surface's, N.V, at grazing views and the albedo passes 1
// @source exercise 11 of brdf-lab: a model for the students' energy test to catch.
// @include terms/distributions.glsl
// @param kd color 0.05 0.05 0.05 | diffuse albedo
// @param ks color 0.8 0.8 0.8 | specular weight
// @param alpha float 0.05 1 0.4 log | GGX roughness

vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {
    float NoL = dot(N, L);
    float NoV = dot(N, V);
    if (NoL <= 0.0 || NoV <= 0.0) return vec3(0.0);
    vec3 H = normalize(L + V);
    float D = D_ggx(dot(N, H), alpha);
    return kd * INV_PI + ks * D / (4.0 * NoL * NoV);
}

// @model phong_illumination
// @title Phong illumination model of the lecture (heuristic, not a physical BRDF)
// @property isotropic
// @formula L_r = ka L_a + sum_l L_l (kd (N.L_l) + ks (R(L_l).V)^ke)   (the slide; specular without the cosine)
// @formula as a BRDF: f_r = kd + ks (R.V)^ke / (N.L), which is not reciprocal: f(L, V) != f(V, L)
// @source B. T. Phong, "Illumination for Computer Generated Pictures", CACM 18(6), 1975.
// @ambient ka
// @param ka color 0.1 0.1 0.1 | ambient coefficient: the share of the ambient light L_a reflected
// @param kd color 0.3 0.3 0.3 | diffuse coefficient (the slide's kd: kd (N.L) per light; albedo = pi kd)
// @param ks color 0.5 0.5 0.5 | specular coefficient
// @param ke float 1 1000 50 log | specular exponent

// The scene view adds ka L_a (through @ambient) and sums over the lights the per-light part
// below times N.L; dividing the specular term by N.L cancels that cosine, so the rendered
// specular is ks (R.V)^ke, exactly the slide's form.
vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {
    float NoL = dot(N, L);
    float NoV = dot(N, V);
    if (NoL <= 0.0 || NoV <= 0.0) return vec3(0.0);
    vec3 R = 2.0 * NoL * N - L;
    float RoV = max(dot(R, V), 0.0);
    return kd + ks * pow(RoV, ke) / NoL;
}

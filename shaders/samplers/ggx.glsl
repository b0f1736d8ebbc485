// Sampler for ggx: visible normals (Heitz 2018), mixed with the cosine lobe for kd.
const bool HAS_SAMPLER = true;
float ggx_share() { return specular_share(lab_luma(kd), lab_luma(ks) * max(lab_luma(f0), 0.25)); }
vec3 SAMPLE_BRDF(vec3 V, vec3 N, vec3 X, vec3 Y, vec3 u) {
    if (u.z < ggx_share()) return reflect_about(V, sample_ggx_visible(u.xy, V, N, X, Y, alpha));
    return sample_cosine(u.xy, N, X, Y);
}
float PDF_BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {
    float s = ggx_share();
    return s * pdf_ggx_visible_light(L, V, N, alpha) + (1.0 - s) * pdf_cosine(L, N);
}

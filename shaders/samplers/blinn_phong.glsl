// Sampler for blinn_phong: cos^ke half vectors around N, reflected (Walter et al. 2007),
// mixed with the cosine lobe for kd.
const bool HAS_SAMPLER = true;
float blinn_share() { return specular_share(lab_luma(kd), lab_luma(ks) * 8.0 * PI / (ke + 2.0)); }
vec3 SAMPLE_BRDF(vec3 V, vec3 N, vec3 X, vec3 Y, vec3 u) {
    if (u.z < blinn_share()) return reflect_about(V, sample_power_cosine(u.xy, N, ke));
    return sample_cosine(u.xy, N, X, Y);
}
float PDF_BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {
    vec3 H = normalize(L + V);
    float spec = half_to_light_pdf(pdf_power_cosine(H, N, ke), V, H);
    float s = blinn_share();
    return s * spec + (1.0 - s) * pdf_cosine(L, N);
}

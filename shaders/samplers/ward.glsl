// Sampler for ward: anisotropic Gaussian half-vector slopes (Walter 2005, "Notes on the
// Ward BRDF"), mixed with the cosine lobe for kd.
const bool HAS_SAMPLER = true;
float ward_share() { return specular_share(lab_luma(kd), lab_luma(ks)); }
vec3 SAMPLE_BRDF(vec3 V, vec3 N, vec3 X, vec3 Y, vec3 u) {
    if (u.z < ward_share()) {
        return reflect_about(V, sample_gaussian_slopes(u.xy, N, X, Y, alpha_x, alpha_y));
    }
    return sample_cosine(u.xy, N, X, Y);
}
float PDF_BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {
    vec3 H = normalize(L + V);
    float spec = half_to_light_pdf(pdf_gaussian_slopes(H, N, X, Y, alpha_x, alpha_y), V, H);
    float s = ward_share();
    return s * spec + (1.0 - s) * pdf_cosine(L, N);
}

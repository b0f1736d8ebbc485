// Sampler for cook_torrance: Beckmann half vectors (slopes normal with deviation m/sqrt(2);
// Walter et al. 2007), mixed with the cosine lobe for kd. With the Blinn or Gaussian
// distribution the Beckmann lobe of the same m still covers the highlight: the estimate
// stays unbiased, only less efficient.
const bool HAS_SAMPLER = true;
float ct_share() {
    float f = fresnel == FRESNEL_NONE ? 1.0 : max(lab_luma(f0), 0.25);
    return specular_share(lab_luma(kd), lab_luma(ks) * f);
}
vec3 SAMPLE_BRDF(vec3 V, vec3 N, vec3 X, vec3 Y, vec3 u) {
    if (u.z < ct_share()) return reflect_about(V, sample_gaussian_slopes(u.xy, N, X, Y, m, m));
    return sample_cosine(u.xy, N, X, Y);
}
float PDF_BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {
    vec3 H = normalize(L + V);
    float spec = half_to_light_pdf(pdf_gaussian_slopes(H, N, X, Y, m, m), V, H);
    float s = ct_share();
    return s * spec + (1.0 - s) * pdf_cosine(L, N);
}

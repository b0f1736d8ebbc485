// Sampler for phong: a mixture of the cosine lobe (kd) and cos^ke around the mirror
// direction of V (ks), since (R.V) = (L.R_V) (Lafortune & Willems 1994).
const bool HAS_SAMPLER = true;
float phong_share() { return specular_share(lab_luma(kd), lab_luma(ks) * 2.0 * PI / (ke + 1.0)); }
vec3 SAMPLE_BRDF(vec3 V, vec3 N, vec3 X, vec3 Y, vec3 u) {
    if (u.z < phong_share()) return sample_power_cosine(u.xy, reflect(-V, N), ke);
    return sample_cosine(u.xy, N, X, Y);
}
float PDF_BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {
    float s = phong_share();
    return s * pdf_power_cosine(L, reflect(-V, N), ke) + (1.0 - s) * pdf_cosine(L, N);
}

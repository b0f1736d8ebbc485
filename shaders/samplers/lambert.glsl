// Sampler for lambert: cosine-weighted directions (f_r cos / pdf = albedo, no variance
// under a white furnace).
const bool HAS_SAMPLER = true;
vec3 SAMPLE_BRDF(vec3 V, vec3 N, vec3 X, vec3 Y, vec3 u) { return sample_cosine(u.xy, N, X, Y); }
float PDF_BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) { return pdf_cosine(L, N); }

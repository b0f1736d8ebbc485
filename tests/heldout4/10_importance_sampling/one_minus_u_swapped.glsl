// @title Exercise 10: importance sampling the Blinn-Phong lobe
// @formula p_h(H) = (ke + 1) / (2 pi) (N.H)^ke,  L = reflect(-V, H),  p(L) = p_h(H) / (4 V.H)
// @source B. Walter et al., "Microfacet Models for Refraction through Rough Surfaces", EGSR 2007, eq. 14 to 17.
// @source M. Pharr and G. Humphreys, "Physically Based Rendering", 2nd ed., section 14.5.1.
// The lobe is that of shaders/brdfs/blinn_phong.glsl, ks (N.H)^ke; ke is its exponent.
// Given (shaders/terms/sampling.glsl): PI, INV_PI, to_world(v, X, Y, N).

vec3 sample_half_vector(vec2 u, vec3 N, vec3 X, vec3 Y) {
    // 1 - u is uniform too; the two numbers swapped
    float cos_t = pow(max(1.0 - u.y, 1e-30), 1.0 / (ke + 1.0));
    float sin_t = sqrt(max(1.0 - cos_t * cos_t, 0.0));
    float phi = 2.0 * PI * u.x;
    return to_world(vec3(cos(phi) * sin_t, sin(phi) * sin_t, cos_t), X, Y, N);
}

float pdf_half_vector(vec3 H, vec3 N) {
    float c = dot(H, N);
    return c > 0.0 ? (ke + 1.0) / (2.0 * PI) * pow(c, ke) : 0.0;
}

vec3 sample_lobe(vec2 u, vec3 V, vec3 N, vec3 X, vec3 Y) {
    vec3 H = sample_half_vector(u, N, X, Y);
    return 2.0 * dot(V, H) * H - V;
}

float pdf_lobe(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {
    vec3 H = normalize(V + L);
    float VoH = dot(H, V);
    if (VoH <= 0.0) {
        return 0.0;
    }
    return pdf_half_vector(H, N) * 0.25 / VoH;
}

// @title Exercise 10: importance sampling the Blinn-Phong lobe
// @formula p_h(H) = (ke + 1) / (2 pi) (N.H)^ke,  L = reflect(-V, H),  p(L) = p_h(H) / (4 V.H)
// @source B. Walter et al., "Microfacet Models for Refraction through Rough Surfaces", EGSR 2007, eq. 14 to 17.
// @source M. Pharr and G. Humphreys, "Physically Based Rendering", 2nd ed., section 14.5.1.
// The lobe is that of shaders/brdfs/blinn_phong.glsl, ks (N.H)^ke; ke is its exponent.
// Given (shaders/terms/sampling.glsl): PI, INV_PI, to_world(v, X, Y, N).

// A half vector H around N with density p_h(H) = (ke + 1) / (2 pi) (N.H)^ke over solid
// angle: cos(theta_h) = u.x^(1 / (ke + 1)), phi_h = 2 pi u.y, in the frame (X, Y, N).
vec3 sample_half_vector(vec2 u, vec3 N, vec3 X, vec3 Y) {
    float cos_t = pow(max(u.x, 1e-30), 1.0 / ke);
    float sin_t = sqrt(max(1.0 - cos_t * cos_t, 0.0));
    float phi = 2.0 * PI * u.y;
    vec3 h = vec3(sin_t * cos(phi), sin_t * sin(phi), cos_t);
    return h.x * X + h.y * Y + h.z * N;
}

// The density of sample_half_vector over solid angle.
float pdf_half_vector(vec3 H, vec3 N) {
    float NoH = dot(N, H);
    if (NoH <= 0.0) return 0.0;
    return (ke + 1.0) * 0.5 * INV_PI * pow(NoH, ke);
}

// One direction L from the lobe: a half vector, and V reflected about it.
vec3 sample_lobe(vec2 u, vec3 V, vec3 N, vec3 X, vec3 Y) {
    vec3 H = sample_half_vector(u, N, X, Y);
    return reflect(-V, H);
}

// The density of sample_lobe over solid angle: p_h(H) times the Jacobian 1 / (4 V.H) of
// the reflection H -> L (0 where no half vector facing V gives L).
float pdf_lobe(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {
    vec3 H = normalize(L + V);
    float VoH = dot(V, H);
    if (VoH <= 0.0) return 0.0;
    return pdf_half_vector(H, N) / (4.0 * VoH);
}

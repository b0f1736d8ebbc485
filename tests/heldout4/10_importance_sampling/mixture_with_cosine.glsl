// @title Exercise 10: importance sampling the Blinn-Phong lobe
// @formula p_h(H) = (ke + 1) / (2 pi) (N.H)^ke,  L = reflect(-V, H),  p(L) = p_h(H) / (4 V.H)
// @source B. Walter et al., "Microfacet Models for Refraction through Rough Surfaces", EGSR 2007, eq. 14 to 17.
// @source M. Pharr and G. Humphreys, "Physically Based Rendering", 2nd ed., section 14.5.1.
// The lobe is that of shaders/brdfs/blinn_phong.glsl, ks (N.H)^ke; ke is its exponent.
// Given (shaders/terms/sampling.glsl): PI, INV_PI, to_world(v, X, Y, N).

vec3 sample_half_vector(vec2 u, vec3 N, vec3 X, vec3 Y) {
    float cos_t = pow(max(u.x, 1e-30), 1.0 / (ke + 1.0));
    float sin_t = sqrt(max(1.0 - cos_t * cos_t, 0.0));
    float phi = 2.0 * PI * u.y;
    return to_world(vec3(sin_t * cos(phi), sin_t * sin(phi), cos_t), X, Y, N);
}

float pdf_half_vector(vec3 H, vec3 N) {
    float NoH = dot(N, H);
    if (NoH <= 0.0) return 0.0;
    return (ke + 1.0) * 0.5 * INV_PI * pow(NoH, ke);
}

// A mixture: half the samples from the lobe, half cosine-weighted over the hemisphere.
vec3 sample_lobe(vec2 u, vec3 V, vec3 N, vec3 X, vec3 Y) {
    if (u.x < 0.5) {
        vec3 H = sample_half_vector(vec2(2.0 * u.x, u.y), N, X, Y);
        return reflect(-V, H);
    }
    float r = sqrt(2.0 * u.x - 1.0);
    float phi = 2.0 * PI * u.y;
    return to_world(vec3(r * cos(phi), r * sin(phi), sqrt(max(1.0 - r * r, 0.0))), X, Y, N);
}

// The mixture's density: the mean of the two densities.
float pdf_lobe(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {
    vec3 H = normalize(L + V);
    float VoH = dot(V, H);
    float lobe = VoH > 0.0 ? pdf_half_vector(H, N) / (4.0 * VoH) : 0.0;
    float NoL = dot(N, L);
    float cosine = NoL > 0.0 ? NoL * INV_PI : 0.0;
    return 0.5 * lobe + 0.5 * cosine;
}

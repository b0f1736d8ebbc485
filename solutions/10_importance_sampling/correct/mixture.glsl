// @title Exercise 10: importance sampling the Blinn-Phong lobe
// A correct variant: a one-sample mixture of cosine-weighted and lobe sampling. Half the
// samples come from each; the pdf of the mixture is the mixture of the pdfs,
// p(L) = 1/2 cos(theta_L) / pi + 1/2 p_h(H) / (4 V.H). It is unbiased and, with half its
// samples in the lobe, a little noisier than lobe sampling alone.

vec3 sample_half_vector(vec2 u, vec3 N, vec3 X, vec3 Y) {
    float cos_t = pow(max(u.x, 1e-30), 1.0 / (ke + 1.0));
    float sin_t = sqrt(max(1.0 - cos_t * cos_t, 0.0));
    float phi = 2.0 * PI * u.y;
    return to_world(vec3(sin_t * cos(phi), sin_t * sin(phi), cos_t), X, Y, N);
}

float pdf_half_vector(vec3 H, vec3 N) {
    float NoH = dot(N, H);
    return NoH > 0.0 ? (ke + 1.0) * 0.5 * INV_PI * pow(NoH, ke) : 0.0;
}

vec3 sample_lobe(vec2 u, vec3 V, vec3 N, vec3 X, vec3 Y) {
    if (u.x < 0.5) {
        // Cosine-weighted, with u.x stretched back to [0, 1).
        float r = sqrt(2.0 * u.x);
        float phi = 2.0 * PI * u.y;
        return to_world(vec3(r * cos(phi), r * sin(phi), sqrt(max(1.0 - r * r, 0.0))), X, Y, N);
    }
    vec3 H = sample_half_vector(vec2(2.0 * u.x - 1.0, u.y), N, X, Y);
    return reflect(-V, H);
}

float pdf_lobe(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {
    float cosine = max(dot(N, L), 0.0) * INV_PI;
    vec3 H = normalize(L + V);
    float VoH = dot(V, H);
    float lobe = VoH > 0.0 ? pdf_half_vector(H, N) / (4.0 * VoH) : 0.0;
    return 0.5 * cosine + 0.5 * lobe;
}

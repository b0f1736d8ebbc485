// @title Exercise 10: importance sampling the Blinn-Phong lobe
// Not importance sampling: L uniform over the hemisphere, with its exact pdf 1 / (2 pi).
// Unbiased, but most samples miss the lobe: it must lose the ibl_render points.

vec3 sample_half_vector(vec2 u, vec3 N, vec3 X, vec3 Y) { return N; }

float pdf_half_vector(vec3 H, vec3 N) { return 0.0; }

vec3 sample_lobe(vec2 u, vec3 V, vec3 N, vec3 X, vec3 Y) {
    float z = u.x;
    float r = sqrt(max(1.0 - z * z, 0.0));
    float phi = 2.0 * PI * u.y;
    return to_world(vec3(r * cos(phi), r * sin(phi), z), X, Y, N);
}

float pdf_lobe(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {
    return dot(N, L) > 0.0 ? 0.5 * INV_PI : 0.0;
}

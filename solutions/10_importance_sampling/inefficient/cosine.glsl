// @title Exercise 10: importance sampling the Blinn-Phong lobe
// Not importance sampling of the lobe: L cosine-weighted, with its exact pdf cos / pi.
// Unbiased, but blind to the lobe: it must lose the ibl_render points.

vec3 sample_half_vector(vec2 u, vec3 N, vec3 X, vec3 Y) { return N; }

float pdf_half_vector(vec3 H, vec3 N) { return 0.0; }

vec3 sample_lobe(vec2 u, vec3 V, vec3 N, vec3 X, vec3 Y) {
    float r = sqrt(u.x);
    float phi = 2.0 * PI * u.y;
    return to_world(vec3(r * cos(phi), r * sin(phi), sqrt(max(1.0 - u.x, 0.0))), X, Y, N);
}

float pdf_lobe(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {
    return max(dot(N, L), 0.0) * INV_PI;
}

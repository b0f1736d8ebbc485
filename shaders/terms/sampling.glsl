// Random numbers and lobe samplers for Monte Carlo integration (the IBL view and its tests).
// Every sampler returns a unit direction; every pdf is a density over solid angle on the
// whole sphere (directions below the horizon may be drawn: they carry zero radiance).

// PCG hash (Jarzynski & Olano 2020, "Hash Functions for GPU Rendering").
uint lab_pcg(uint v) {
    uint state = v * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

uint lab_rng_state;

void lab_seed(uint pixel, uint frame) { lab_rng_state = lab_pcg(pixel ^ lab_pcg(frame + 0x9e3779b9u)); }

// A uniform number in [0, 1) with 24 random bits.
float lab_random() {
    lab_rng_state = lab_pcg(lab_rng_state);
    return float(lab_rng_state >> 8u) * (1.0 / 16777216.0);
}

vec3 lab_random3() { return vec3(lab_random(), lab_random(), lab_random()); }

float lab_luma(vec3 c) { return dot(c, LAB_LUMA); }

// Local (x, y, z) in the frame (X, Y, N).
vec3 to_world(vec3 v, vec3 X, vec3 Y, vec3 N) { return v.x * X + v.y * Y + v.z * N; }

// Any orthonormal frame around the unit axis A (Duff et al. 2017).
void frame_around(vec3 A, out vec3 T, out vec3 B) {
    float s = A.z >= 0.0 ? 1.0 : -1.0;
    float a = -1.0 / (s + A.z);
    float b = A.x * A.y * a;
    T = vec3(1.0 + s * A.x * A.x * a, s * b, -s * A.x);
    B = vec3(b, s + A.y * A.y * a, -A.y);
}

// Uniform over the hemisphere around N: pdf 1 / (2 pi).
vec3 sample_uniform_hemisphere(vec2 u, vec3 N, vec3 X, vec3 Y) {
    float z = u.x;
    float r = sqrt(max(1.0 - z * z, 0.0));
    float phi = 2.0 * PI * u.y;
    return to_world(vec3(r * cos(phi), r * sin(phi), z), X, Y, N);
}
float pdf_uniform_hemisphere(vec3 L, vec3 N) { return dot(N, L) > 0.0 ? 0.5 * INV_PI : 0.0; }

// Cosine-weighted (Malley's method): pdf cos(theta) / pi.
vec3 sample_cosine(vec2 u, vec3 N, vec3 X, vec3 Y) {
    float r = sqrt(u.x);
    float phi = 2.0 * PI * u.y;
    return to_world(vec3(r * cos(phi), r * sin(phi), sqrt(max(1.0 - u.x, 0.0))), X, Y, N);
}
float pdf_cosine(vec3 L, vec3 N) { return max(dot(N, L), 0.0) * INV_PI; }

// cos^n around the axis A (Phong lobe): pdf (n + 1) / (2 pi) cos^n(angle to A).
vec3 sample_power_cosine(vec2 u, vec3 A, float n) {
    float c = pow(max(u.x, 1e-30), 1.0 / (n + 1.0));
    float s = sqrt(max(1.0 - c * c, 0.0));
    float phi = 2.0 * PI * u.y;
    vec3 T, B;
    frame_around(A, T, B);
    return s * cos(phi) * T + s * sin(phi) * B + c * A;
}
float pdf_power_cosine(vec3 L, vec3 A, float n) {
    float c = dot(L, A);
    return c > 0.0 ? (n + 1.0) * 0.5 * INV_PI * pow(c, n) : 0.0;
}

// A half vector H drawn with density p_h turns into L = reflect(-V, H) with density
// p_h / (4 V.H) (Walter et al. 2007, eq. 14).
vec3 reflect_about(vec3 V, vec3 H) { return 2.0 * dot(V, H) * H - V; }
float half_to_light_pdf(float pdf_h, vec3 V, vec3 H) {
    float VoH = dot(V, H);
    return VoH > 0.0 ? pdf_h / (4.0 * VoH) : 0.0;
}

// Anisotropic Gaussian slopes (Ward 1992; Beckmann when ax = ay): the slopes of H are
// normal with deviations ax / sqrt(2), ay / sqrt(2) (Box-Muller), so
// p_h(H) = exp(-(sx^2 / ax^2 + sy^2 / ay^2)) / (pi ax ay cos^3 theta_h).
vec3 sample_gaussian_slopes(vec2 u, vec3 N, vec3 X, vec3 Y, float ax, float ay) {
    float r = sqrt(-log(max(1.0 - u.x, 1e-30)));
    float phi = 2.0 * PI * u.y;
    return normalize(to_world(vec3(ax * r * cos(phi), ay * r * sin(phi), 1.0), X, Y, N));
}
float pdf_gaussian_slopes(vec3 H, vec3 N, vec3 X, vec3 Y, float ax, float ay) {
    float c = dot(H, N);
    if (c <= 0.0) return 0.0;
    float sx = dot(H, X) / c;
    float sy = dot(H, Y) / c;
    return exp(-(sx * sx / (ax * ax) + sy * sy / (ay * ay))) / (PI * ax * ay * c * c * c);
}

// GGX visible normals (Heitz 2018, "Sampling the GGX Distribution of Visible Normals"):
// p_h(H) = G1(V) max(V.H, 0) D(H) / (N.V), so p(L) = G1(V) D(H) / (4 N.V).
float ggx_D(float NoH, float alpha) {
    float a2 = alpha * alpha;
    float d = NoH * NoH * (a2 - 1.0) + 1.0;
    return NoH > 0.0 ? a2 / (PI * d * d) : 0.0;
}
float ggx_G1(float NoV, float alpha) {
    float a2 = alpha * alpha;
    return 2.0 * NoV / (NoV + sqrt(a2 + (1.0 - a2) * NoV * NoV));
}
vec3 sample_ggx_visible(vec2 u, vec3 V, vec3 N, vec3 X, vec3 Y, float alpha) {
    vec3 v = vec3(dot(V, X), dot(V, Y), dot(V, N));
    vec3 vh = normalize(vec3(alpha * v.x, alpha * v.y, max(v.z, 1e-6)));
    float len2 = vh.x * vh.x + vh.y * vh.y;
    vec3 t1 = len2 > 0.0 ? vec3(-vh.y, vh.x, 0.0) / sqrt(len2) : vec3(1.0, 0.0, 0.0);
    vec3 t2 = cross(vh, t1);
    float r = sqrt(u.x);
    float phi = 2.0 * PI * u.y;
    float p1 = r * cos(phi);
    float p2 = r * sin(phi);
    float s = 0.5 * (1.0 + vh.z);
    p2 = (1.0 - s) * sqrt(max(1.0 - p1 * p1, 0.0)) + s * p2;
    vec3 nh = p1 * t1 + p2 * t2 + sqrt(max(1.0 - p1 * p1 - p2 * p2, 0.0)) * vh;
    vec3 h = normalize(vec3(alpha * nh.x, alpha * nh.y, max(nh.z, 1e-6)));
    return to_world(h, X, Y, N);
}
float pdf_ggx_visible_light(vec3 L, vec3 V, vec3 N, float alpha) {
    float NoV = dot(N, V);
    vec3 H = normalize(L + V);
    if (NoV <= 0.0 || dot(V, H) <= 0.0) return 0.0;
    return ggx_G1(NoV, alpha) * ggx_D(dot(N, H), alpha) / (4.0 * NoV);
}

// The share of samples a mixture gives its specular lobe: by the lobes' rough energies,
// kept between 10% and 90% while both lobes are present.
float specular_share(float diffuse, float specular) {
    if (specular <= 0.0) return 0.0;
    if (diffuse <= 0.0) return 1.0;
    return clamp(specular / (diffuse + specular), 0.1, 0.9);
}

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

// Low-discrepancy samples: Owen-scrambled Sobol' points (lab/ibl/sobol.py is the numpy
// twin). Dimension 0 is bit reversal, 1 and 2 use the direction numbers below (Joe and
// Kuo 2008: x + 1 with m = 1; x^2 + x + 1 with m = 1, 3). Each pixel shuffles the index
// and scrambles every dimension with its own hash (Burley 2020, "Practical Hash-based Owen
// Scrambling"): a shuffle maps each aligned block of 2^m indices onto another such block,
// so every power-of-two prefix stays a scrambled (0, m, 2)-net, and pixels are independent.
const uint LAB_SOBOL_V[64] = uint[64](
    0x80000000u, 0xc0000000u, 0xa0000000u, 0xf0000000u, 0x88000000u, 0xcc000000u, 0xaa000000u, 0xff000000u,
    0x80800000u, 0xc0c00000u, 0xa0a00000u, 0xf0f00000u, 0x88880000u, 0xcccc0000u, 0xaaaa0000u, 0xffff0000u,
    0x80008000u, 0xc000c000u, 0xa000a000u, 0xf000f000u, 0x88008800u, 0xcc00cc00u, 0xaa00aa00u, 0xff00ff00u,
    0x80808080u, 0xc0c0c0c0u, 0xa0a0a0a0u, 0xf0f0f0f0u, 0x88888888u, 0xccccccccu, 0xaaaaaaaau, 0xffffffffu,
    0x80000000u, 0xc0000000u, 0x60000000u, 0x90000000u, 0xe8000000u, 0x5c000000u, 0x8e000000u, 0xc5000000u,
    0x68800000u, 0x9cc00000u, 0xee600000u, 0x55900000u, 0x80680000u, 0xc09c0000u, 0x60ee0000u, 0x90550000u,
    0xe8808000u, 0x5cc0c000u, 0x8e606000u, 0xc5909000u, 0x6868e800u, 0x9c9c5c00u, 0xeeee8e00u, 0x5555c500u,
    0x8000e880u, 0xc0005cc0u, 0x60008e60u, 0x9000c590u, 0xe8006868u, 0x5c009c9cu, 0x8e00eeeeu, 0xc5005555u);

uint lab_reverse_bits(uint x) {  // bitfieldReverse needs GLSL 4.0; this runs in 3.3 / ES 3.0
    x = ((x >> 1u) & 0x55555555u) | ((x & 0x55555555u) << 1u);
    x = ((x >> 2u) & 0x33333333u) | ((x & 0x33333333u) << 2u);
    x = ((x >> 4u) & 0x0f0f0f0fu) | ((x & 0x0f0f0f0fu) << 4u);
    x = ((x >> 8u) & 0x00ff00ffu) | ((x & 0x00ff00ffu) << 8u);
    return (x >> 16u) | (x << 16u);
}

// Nested uniform scrambling of the bits of x, from the top: reversed, each bit flips by a
// function of the bits below it only (additions and products with even constants never
// carry downwards: a Laine-Karras style permutation), then reversed back.
uint lab_owen(uint x, uint seed) {
    x = lab_reverse_bits(x) + seed;
    x ^= x * 0x6c50b47cu;
    x ^= x * 0xb82f1e52u;
    x ^= x * 0xc7afe638u;
    x ^= x * 0x8d22f6e6u;
    return lab_reverse_bits(x);
}

// The Sobol' integers of `index` in dimensions 1 and 2 (dimension 0 is lab_reverse_bits).
uvec2 lab_sobol12(uint index) {
    uvec2 x = uvec2(0u);
    for (int k = 0; k < 32; ++k) {
        if (index == 0u) break;
        if ((index & 1u) != 0u) x ^= uvec2(LAB_SOBOL_V[k], LAB_SOBOL_V[32 + k]);
        index >>= 1u;
    }
    return x;
}

float lab_unit(uint x) { return float(x >> 8u) * (1.0 / 16777216.0); }

// Four scrambling keys from one seed: the index shuffle's and one per dimension.
uvec4 lab_sobol_keys(uint seed) {
    uint h = lab_pcg(seed);
    return uvec4(h, lab_pcg(h ^ 0x68bc21ebu), lab_pcg(h ^ 0x02e5be93u), lab_pcg(h ^ 0x967a889bu));
}

// Point `index` of a scrambled 3D Sobol' sequence. With `shuffle` the index is first
// permuted (keys.x; kept to 16 bits, so the Sobol' loop stays short: prefixes up to
// 65536 samples stay nets): that pads a second sequence, independent of the first.
vec3 lab_sobol3(uint index, uvec4 keys, bool shuffle) {
    uint i = shuffle ? lab_owen(index, keys.x) & 0xffffu : index;
    uvec2 s = lab_sobol12(i);
    return vec3(lab_unit(lab_owen(lab_reverse_bits(i), keys.y)),
                lab_unit(lab_owen(s.x, keys.z)), lab_unit(lab_owen(s.y, keys.w)));
}

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

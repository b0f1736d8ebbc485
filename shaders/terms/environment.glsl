// The environment map and the Monte Carlo estimate of the reflection equation
// L_o(V) = integral of f_r(L, V) L_i(L) cos(theta_L) dL, shared by the IBL views
// (views/ibl.glsl: the sphere; views/ibl_object.glsl: the lab's object). The hosts put it
// after the model, terms/sampling.glsl and the model's sampler (SAMPLE_BRDF, PDF_BRDF).
// The environment is equirectangular (row 0 the zenith, +y up), rotated by u_rotation
// around +y; u_marginal / u_conditional hold its CDFs, u_density its pdf over (u, v).
uniform sampler2D u_env;
uniform sampler2D u_density;
uniform sampler2D u_marginal;
uniform sampler2D u_conditional;
uniform vec2 u_env_size;
uniform float u_rotation;
uniform int u_strategy;  // 0 uniform, 1 cosine, 2 environment, 3 BRDF, 4 MIS balance, 5 MIS power

vec2 env_uv(vec3 d) {
    float u = 0.5 + atan(d.x, -d.z) * (0.5 * INV_PI) + u_rotation * (0.5 * INV_PI);
    return vec2(fract(u), acos(clamp(d.y, -1.0, 1.0)) * INV_PI);
}

vec3 env_direction(vec2 uv) {
    float phi = (uv.x - 0.5) * 2.0 * PI - u_rotation;
    float theta = uv.y * PI;
    return vec3(sin(theta) * sin(phi), cos(theta), -sin(theta) * cos(phi));
}

ivec2 env_texel(vec2 uv) {
    ivec2 size = ivec2(u_env_size);
    return clamp(ivec2(uv * u_env_size), ivec2(0), size - 1);
}

vec3 environment(vec3 d) { return texelFetch(u_env, env_texel(env_uv(d)), 0).rgb; }

// Solid-angle pdf of sample_environment for direction d.
float pdf_environment(vec3 d) {
    vec2 uv = env_uv(d);
    float s = sin(uv.y * PI);
    if (s <= 0.0) return 0.0;
    return texelFetch(u_density, env_texel(uv), 0).r / (2.0 * PI * PI * s);
}

// The first index i in [0, n) with cdf[i + 1] > x (the CDF has n + 1 entries).
int find_interval(sampler2D cdf, int row, int n, float x) {
    int lo = 0;
    int hi = n - 1;
    for (int step = 0; step < 16; ++step) {
        if (lo >= hi) break;
        int mid = (lo + hi) / 2;
        if (texelFetch(cdf, ivec2(mid + 1, row), 0).r <= x) lo = mid + 1;
        else hi = mid;
    }
    return lo;
}

vec3 sample_environment(vec2 u) {
    int w = int(u_env_size.x);
    int h = int(u_env_size.y);
    int row = find_interval(u_marginal, 0, h, u.x);
    float c0 = texelFetch(u_marginal, ivec2(row, 0), 0).r;
    float c1 = texelFetch(u_marginal, ivec2(row + 1, 0), 0).r;
    float v = (float(row) + clamp((u.x - c0) / max(c1 - c0, 1e-20), 0.0, 1.0)) / float(h);
    int col = find_interval(u_conditional, row, w, u.y);
    float d0 = texelFetch(u_conditional, ivec2(col, row), 0).r;
    float d1 = texelFetch(u_conditional, ivec2(col + 1, row), 0).r;
    float x = (float(col) + clamp((u.y - d0) / max(d1 - d0, 1e-20), 0.0, 1.0)) / float(w);
    return env_direction(vec2(x, v));
}

float mis_weight(float a, float b) {
    if (u_strategy == 5) {
        a *= a;
        b *= b;
    }
    return a + b > 0.0 ? a / (a + b) : 0.0;
}

// f_r L_i cos / pdf for one direction, zero below the horizon.
vec3 contribution(vec3 L, float pdf, vec3 V, vec3 N, vec3 X, vec3 Y) {
    float NoL = dot(N, L);
    if (NoL <= 0.0 || pdf <= 0.0) return vec3(0.0);
    return BRDF(L, V, N, X, Y) * environment(L) * (NoL / pdf);
}

vec3 one_sample(vec3 V, vec3 N, vec3 X, vec3 Y) {
    vec3 u = lab_random3();
    if (u_strategy == 0) {
        return contribution(sample_uniform_hemisphere(u.xy, N, X, Y), 0.5 * INV_PI, V, N, X, Y);
    }
    if (u_strategy == 1 || (u_strategy == 3 && !HAS_SAMPLER)) {
        vec3 L = sample_cosine(u.xy, N, X, Y);
        return contribution(L, pdf_cosine(L, N), V, N, X, Y);
    }
    if (u_strategy == 2) {
        vec3 L = sample_environment(u.xy);
        return contribution(L, pdf_environment(L), V, N, X, Y);
    }
    // The BRDF's own sampler (cosine-weighted when the model has none).
    vec3 Lb = HAS_SAMPLER ? SAMPLE_BRDF(V, N, X, Y, u) : sample_cosine(u.xy, N, X, Y);
    float pb = HAS_SAMPLER ? PDF_BRDF(Lb, V, N, X, Y) : pdf_cosine(Lb, N);
    if (u_strategy == 3) return contribution(Lb, pb, V, N, X, Y);
    // Multiple importance sampling: one BRDF and one environment direction (Veach 1997).
    vec3 Le = sample_environment(lab_random3().xy);
    float pe = pdf_environment(Le);
    float pb_e = HAS_SAMPLER ? PDF_BRDF(Le, V, N, X, Y) : pdf_cosine(Le, N);
    float pe_b = pdf_environment(Lb);
    return mis_weight(pb, pe_b) * contribution(Lb, pb, V, N, X, Y)
         + mis_weight(pe, pb_e) * contribution(Le, pe, V, N, X, Y);
}

// What an IBL view adds to a pixel in one pass: the sum of `spp` samples (seeded by the
// pixel, the pass and the seed) and, for a delta model, `spp` times its mirror image of
// the environment.
vec3 pass_sum(vec3 V, vec3 N, vec3 X, vec3 Y, int spp, int frame, int seed) {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    lab_seed(uint(pixel.y * 8192 + pixel.x), uint(frame) * 7919u + uint(seed));
    vec3 total = vec3(0.0);
    for (int i = 0; i < 1024; ++i) {
        if (i >= spp) break;
        total += one_sample(V, N, X, Y);
    }
    if (IS_DELTA) {
        vec3 R = reflect(-V, N);
        total += DELTA_REFLECTANCE(R, N, X, Y) * environment(R) * float(spp);
    }
    return total;
}

// The environment map and the Monte Carlo estimate of the reflection equation
// L_o(V) = integral of f_r(L, V) L_i(L) cos(theta_L) dL, shared by the IBL views
// (views/ibl.glsl: the sphere; views/ibl_object.glsl: the lab's object). The hosts put it
// after the model, terms/sampling.glsl and the model's sampler (SAMPLE_BRDF, PDF_BRDF).
// The environment is equirectangular (row 0 the zenith, +y up), rotated by u_rotation
// around +y; u_marginal / u_conditional hold its CDFs, u_density its pdf over (u, v).
// The desktop host compiles one program per strategy (LAB_STRATEGY) and sample sequence
// (LAB_SOBOL: Owen-scrambled Sobol' points instead of PCG random numbers), so a pass
// carries no branch on either; the page sets u_strategy.
uniform sampler2D u_env;
uniform sampler2D u_density;
uniform sampler2D u_marginal;
uniform sampler2D u_conditional;
uniform vec2 u_env_size;
uniform float u_rotation;
#ifdef LAB_STRATEGY
#define STRATEGY LAB_STRATEGY
#else
// 0 uniform, 1 cosine, 2 environment, 3 BRDF, 4 MIS balance, 5 MIS power
uniform int u_strategy;
#define STRATEGY u_strategy
#endif
uniform int u_sample0;  // samples per pixel before this pass: the Sobol' index of the first

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

// Radiance (rgb) and the solid-angle pdf of sample_environment (a) at a place on the map.
vec4 env_lookup(vec2 uv) {
    ivec2 texel = env_texel(uv);
    float s = sin(uv.y * PI);
    float pdf = s > 0.0 ? texelFetch(u_density, texel, 0).r / (2.0 * PI * PI * s) : 0.0;
    return vec4(texelFetch(u_env, texel, 0).rgb, pdf);
}

// Solid-angle pdf of sample_environment for direction d.
float pdf_environment(vec3 d) { return env_lookup(env_uv(d)).a; }

// The largest index i in [0, n) with cdf[i] <= x (the CDF has n + 1 entries, cdf[0] = 0):
// the cell x falls in, never an empty one. The steps halve from the largest power of two
// below n, the same count in every pixel (a loop that ends pixel by pixel costs a
// software rasterizer the longest pixel's count anyway, and its branches).
int find_interval(sampler2D cdf, int row, int n, float x) {
    int lo = 0;
    for (int step = 1 << int(log2(float(n)) + 1e-3); step > 0; step >>= 1) {
        int i = lo + step;
        if (i < n && texelFetch(cdf, ivec2(i, row), 0).r <= x) lo = i;
    }
    return lo;
}

// A direction drawn from the map; `uv` is its place on the map (no trigonometry to find it).
vec3 sample_environment(vec2 u, out vec2 uv) {
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
    uv = vec2(x, v);
    return env_direction(uv);
}
vec3 sample_environment(vec2 u) {
    vec2 uv;
    return sample_environment(u, uv);
}

float mis_weight(float a, float b) {
    if (STRATEGY == 5) {
        a *= a;
        b *= b;
    }
    return a + b > 0.0 ? a / (a + b) : 0.0;
}

// f_r cos for one direction, zero below the horizon.
vec3 reflected(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {
    float NoL = dot(N, L);
    return NoL > 0.0 ? BRDF(L, V, N, X, Y) * NoL : vec3(0.0);
}

// f_r L_i cos / pdf for one direction, zero below the horizon.
vec3 contribution(vec3 L, float pdf, vec3 V, vec3 N, vec3 X, vec3 Y) {
    if (pdf <= 0.0) return vec3(0.0);
    return reflected(L, V, N, X, Y) * environment(L) / pdf;
}

float brdf_pdf(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {
    return HAS_SAMPLER ? PDF_BRDF(L, V, N, X, Y) : pdf_cosine(L, N);
}

// One estimate from the unit numbers u (the BRDF's or the strategy's direction) and, for
// MIS, ue (the environment's direction in xy).
vec3 one_sample(vec3 V, vec3 N, vec3 X, vec3 Y, vec3 u, vec3 ue) {
    if (STRATEGY == 0) {
        return contribution(sample_uniform_hemisphere(u.xy, N, X, Y), 0.5 * INV_PI, V, N, X, Y);
    }
    if (STRATEGY == 1 || (STRATEGY == 3 && !HAS_SAMPLER)) {
        vec3 L = sample_cosine(u.xy, N, X, Y);
        return contribution(L, pdf_cosine(L, N), V, N, X, Y);
    }
    if (STRATEGY == 2) {
        vec2 uv;
        vec3 L = sample_environment(u.xy, uv);
        vec4 e = env_lookup(uv);
        return e.a > 0.0 ? reflected(L, V, N, X, Y) * e.rgb / e.a : vec3(0.0);
    }
    // The BRDF's own sampler (cosine-weighted when the model has none).
    vec3 Lb = HAS_SAMPLER ? SAMPLE_BRDF(V, N, X, Y, u) : sample_cosine(u.xy, N, X, Y);
    float pb = brdf_pdf(Lb, V, N, X, Y);
    if (STRATEGY == 3) return contribution(Lb, pb, V, N, X, Y);
    // Multiple importance sampling: one BRDF and one environment direction (Veach 1997).
    vec4 eb = env_lookup(env_uv(Lb));
    vec2 uv;
    vec3 Le = sample_environment(ue.xy, uv);
    vec4 ee = env_lookup(uv);
    float pb_e = brdf_pdf(Le, V, N, X, Y);
    vec3 sum = vec3(0.0);
    if (pb > 0.0) sum += mis_weight(pb, eb.a) / pb * reflected(Lb, V, N, X, Y) * eb.rgb;
    if (ee.a > 0.0) sum += mis_weight(ee.a, pb_e) / ee.a * reflected(Le, V, N, X, Y) * ee.rgb;
    return sum;
}

// What an IBL view adds to a pixel in one pass: the sum of `spp` samples (seeded by the
// pixel, the pass and the seed; with LAB_SOBOL, samples u_sample0 on of the pixel's own
// scrambled sequences) and, for a delta model, `spp` times its mirror image of the
// environment.
vec3 pass_sum(vec3 V, vec3 N, vec3 X, vec3 Y, int spp, int frame, int seed) {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    uint id = uint(pixel.y * 8192 + pixel.x);
#ifdef LAB_ESTIMATOR  // an exercise's own estimator: the mean of spp samples, its own loop
    lab_seed(id, uint(frame) * 7919u + uint(seed));
    return LAB_ESTIMATOR(spp, V, N, X, Y) * float(spp);
#endif
#ifdef LAB_SOBOL
    uvec4 keys = lab_sobol_keys(id ^ lab_pcg(uint(seed) + 0x9e3779b9u));
    uvec4 pad = lab_sobol_keys(keys.x ^ 0x5bd1e995u);  // the environment's own sequence
#else
    lab_seed(id, uint(frame) * 7919u + uint(seed));
#endif
    bool two = STRATEGY >= 4;  // strategies that draw an environment direction too
    vec3 total = vec3(0.0);
    for (int i = 0; i < 1024; ++i) {
        if (i >= spp) break;
#ifdef LAB_SOBOL
        uint index = uint(u_sample0 + i);
        vec3 u = lab_sobol3(index, keys, false);
        vec3 ue = two ? lab_sobol3(index, pad, true) : vec3(0.0);
#else
        vec3 u = lab_random3();
        vec3 ue = two ? lab_random3() : vec3(0.0);
#endif
        total += one_sample(V, N, X, Y, u, ue);
    }
    if (IS_DELTA) {
        vec3 R = reflect(-V, N);
        total += DELTA_REFLECTANCE(R, N, X, Y) * environment(R) * float(spp);
    }
    return total;
}

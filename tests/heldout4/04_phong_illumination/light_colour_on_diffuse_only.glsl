// @model phong_illumination
// @title Exercise 04: the Phong illumination model (ambient term and several lights)
// @formula L_r = ka La + sum_l L_l (kd (N.L_l) + ks max(0, R(L_l).V)^ke)
// @source B. T. Phong, "Illumination for Computer Generated Pictures", CACM 18(6), 1975.
// @param ka color 0.2 0.2 0.2 | ambient coefficient
// @param kd color 0.5 0.5 0.5 | diffuse coefficient (the slide's kd, no 1/pi)
// @param ks color 0.5 0.5 0.5 | specular coefficient
// @param ke float 1 1000 30 log | specular exponent

// Reflected radiance towards V at a point with normal N, lit by the ambient light
// `ambient` (L_a) and by `count` directional lights: light_dir[l] points to light l,
// light_rgb[l] is its radiance L_l. Only the first `count` entries are lights.
vec3 phong_illumination(vec3 N, vec3 V, vec3 ambient, vec3 light_dir[8], vec3 light_rgb[8],
                        int count) {
    vec3 color = ka * ambient;
    for (int l = 0; l < 8; ++l) {
        if (l >= count) break;
        vec3 L = light_dir[l];
        float NoL = dot(N, L);
        if (NoL <= 0.0) continue;
        vec3 R = 2.0 * NoL * N - L;
        float RoV = max(dot(R, V), 0.0);
        color += light_rgb[l] * kd * NoL + ks * pow(RoV, ke);
    }
    return color;
}

// Given (do not change): the same model as a BRDF, so every view of the lab can show it.
// One white light, no ambient light, and the view's cosine factor divided out.
vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {
    float NoL = dot(N, L);
    if (NoL <= 0.0 || dot(N, V) <= 0.0) return vec3(0.0);
    vec3 dirs[8];
    vec3 rgbs[8];
    for (int l = 0; l < 8; ++l) {
        dirs[l] = N;
        rgbs[l] = vec3(0.0);
    }
    dirs[0] = L;
    rgbs[0] = vec3(1.0);
    return phong_illumination(N, V, vec3(0.0), dirs, rgbs, 1) / NoL;
}

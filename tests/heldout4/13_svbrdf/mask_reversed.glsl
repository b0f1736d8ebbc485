// @title Exercise 13: a spatially varying BRDF (painted tiles and brushed metal)
// @formula f_r(uv) = (1 - m) albedo / pi + m f_ward(ks = albedo, alpha_x = r, alpha_y = r a)
// @formula albedo, r, m: the albedo, roughness and mask textures at uv; a: anisotropy
// @source G. J. Ward, "Measuring and Modeling Anisotropic Reflection", SIGGRAPH 1992, eq. 5a.
// @param anisotropy float 1 6 3 linear | the metal's alpha_y / alpha_x: its highlight stretches along Y

// The textures the grader binds (linear values, filtered, repeating in u and v).
uniform sampler2D albedo_map;     // RGB: the paint's colour, and the metal's specular colour
uniform sampler2D roughness_map;  // R: the metal's RMS slope alpha_x along the tangent X
uniform sampler2D mask_map;       // R: 0 paint, 1 metal, in between a blend of the two

// The paint: Lambert.
vec3 paint(vec3 albedo) {
    return albedo * INV_PI;
}

// The brushed metal: Ward's anisotropic lobe without its diffuse part; X and Y are the
// surface's tangent and bitangent, so the lobe follows the object's u and v directions.
vec3 metal(vec3 ks, float alpha_x, float alpha_y, vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {
    float NoL = dot(N, L);
    float NoV = dot(N, V);
    if (NoL <= 0.0 || NoV <= 0.0) return vec3(0.0);
    vec3 H = normalize(L + V);
    float NoH = max(dot(N, H), EPS);
    float exponent = -(sqr(dot(H, X) / alpha_x) + sqr(dot(H, Y) / alpha_y)) / (NoH * NoH);
    return ks * exp(exponent) / (4.0 * PI * alpha_x * alpha_y * sqrt(NoL * NoV));
}

// The material at texture coordinate uv: the parameters read there, the two models blended
// by the mask.
vec3 SVBRDF(vec2 uv, vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {
    vec3 albedo = texture(albedo_map, uv).rgb;
    float roughness = texture(roughness_map, uv).r;
    float mask = texture(mask_map, uv).r;
    vec3 f_paint = paint(albedo);
    vec3 f_metal = metal(albedo, roughness, roughness * anisotropy, L, V, N, X, Y);
    return mix(f_metal, f_paint, mask);
}

// Given: every model file defines BRDF, which the lab's other views call (brdf-lab watch).
// They know no uv and bind no textures: they show your paint and metal half and half, with
// a gold colour and a fixed roughness. The grader calls SVBRDF.
vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {
    vec3 f_paint = paint(vec3(0.7, 0.25, 0.1));
    vec3 f_metal = metal(vec3(0.95, 0.7, 0.3), 0.15, 0.15 * anisotropy, L, V, N, X, Y);
    return mix(f_paint, f_metal, 0.5);
}

// View: a procedural object (a signed distance field, ray-marched; no mesh files) lit by
// LIGHT_COUNT directional lights plus the Phong illumination model's ambient term u_ambient.
// u_mode shows the lecture's steps to spatially varying BRDFs:
//   0 geometry only (plain grey diffuse), 1 the model with one set of parameters,
//   2 a diffuse colour texture only, 3 procedural textures driving the model's parameters.
// The host turns the model's float and colour uniforms into globals NAME (set per pixel by
// sv_assign, which it generates) fed from uniforms NAME_base.
// @include views/object_shape.glsl
uniform vec2 u_resolution;
uniform vec3 u_light_dir[LAB_MAX_LIGHTS];
uniform vec3 u_light_rgb[LAB_MAX_LIGHTS];
uniform vec3 u_ambient;
uniform int u_mode;
out vec4 frag_color;

void sv_assign(float sv_amount, vec3 sv_albedo);

// Procedural maps: a two-colour tiled albedo and wavy bands that vary the other parameters.
vec3 lab_albedo_map(vec2 uv) {
    float tile = mod(floor(uv.x * 16.0) + floor(uv.y * 6.0), 2.0);
    return mix(vec3(0.75, 0.22, 0.08), vec3(0.9, 0.85, 0.7), tile);
}

float lab_vary_map(vec2 uv) {
    float wave = lab_cos_sin(2.0 * PI * uv.y * 3.0).y;
    float s = 0.5 + 0.5 * lab_cos_sin(2.0 * PI * (uv.x * 5.0 + 0.4 * wave)).y;
    return smoothstep(0.3, 0.7, s);
}

vec3 lab_sky(vec3 d) {
    return mix(vec3(0.25, 0.22, 0.2), vec3(0.55, 0.7, 1.0), 0.5 + 0.5 * d.y);
}

void main() {
    vec2 p = (gl_FragCoord.xy / u_resolution) * 2.0 - 1.0;
    vec3 ray, q, N, X, Y;
    if (!lab_object_surface(p, ray, q, N, X, Y)) {
        frag_color = vec4(0.0);
        return;
    }
    vec3 V = -ray;
    vec2 uv = lab_shape_uv(q);
    // Not called `albedo`: models have parameters of that name.
    vec3 texture_albedo = lab_albedo_map(uv);
    if (u_mode == 3) {
        sv_assign(lab_vary_map(uv), texture_albedo);
    } else {
        sv_assign(0.0, vec3(1.0));
    }
    vec3 color = vec3(0.0);
    vec3 diffuse = u_mode == 0 ? vec3(0.7) : texture_albedo;
    for (int i = 0; i < LIGHT_COUNT; ++i) {
        vec3 L = u_light_dir[i];
        float cosine = max(dot(N, L), 0.0);
        if (u_mode == 0 || u_mode == 2) {
            color += u_light_rgb[i] * diffuse * INV_PI * cosine;
        } else if (cosine > 0.0) {
            color += u_light_rgb[i] * BRDF(L, V, N, X, Y) * cosine;
        }
    }
    color += u_ambient * ((u_mode == 0 || u_mode == 2) ? diffuse : AMBIENT_REFLECTANCE());
    if (IS_DELTA && (u_mode == 1 || u_mode == 3)) {
        vec3 Rv = reflect(-V, N);
        color += DELTA_REFLECTANCE(Rv, N, X, Y) * lab_sky(Rv);
    }
    frag_color = vec4(color, 1.0);
}

// View: a procedural object (a signed distance field, ray-marched; no mesh files) lit by
// LIGHT_COUNT directional lights plus the Phong illumination model's ambient term u_ambient.
// u_mode shows the lecture's steps to spatially varying BRDFs:
//   0 geometry only (plain grey diffuse), 1 the model with one set of parameters,
//   2 a diffuse colour texture only, 3 procedural textures driving the model's parameters.
// The host turns the model's float and colour uniforms into globals NAME (set per pixel by
// sv_assign, which it generates) fed from uniforms NAME_base.
uniform vec2 u_resolution;
uniform vec3 u_light_dir[LAB_MAX_LIGHTS];
uniform vec3 u_light_rgb[LAB_MAX_LIGHTS];
uniform vec3 u_ambient;
uniform int u_shape;  // 0 torus, 1 sphere, 2 rounded box, 3 bumpy sphere
uniform int u_mode;
uniform float u_yaw;
uniform float u_pitch;
out vec4 frag_color;

void sv_assign(float sv_amount, vec3 sv_albedo);

mat3 lab_object_rotation() {
    vec2 y = lab_cos_sin(u_yaw);
    vec2 p = lab_cos_sin(u_pitch);
    float cy = y.x, sy = y.y, cp = p.x, sp = p.y;
    mat3 yaw = mat3(cy, 0.0, -sy, 0.0, 1.0, 0.0, sy, 0.0, cy);
    mat3 pitch = mat3(1.0, 0.0, 0.0, 0.0, cp, sp, 0.0, -sp, cp);
    return pitch * yaw;
}

float lab_shape_distance(vec3 p) {
    if (u_shape == 0) return length(vec2(length(p.xz) - 0.72, p.y)) - 0.3;
    if (u_shape == 2) return length(max(abs(p) - vec3(0.5), 0.0)) - 0.2;
    float r = length(p) - 0.85;
    if (u_shape == 3) {
        r += 0.06 * lab_cos_sin(9.0 * p.x).y * lab_cos_sin(9.0 * p.y).y * lab_cos_sin(9.0 * p.z).y;
    }
    return r;
}

vec3 lab_shape_normal(vec3 p) {
    const vec2 e = vec2(1e-3, 0.0);
    return normalize(vec3(lab_shape_distance(p + e.xyy) - lab_shape_distance(p - e.xyy),
                          lab_shape_distance(p + e.yxy) - lab_shape_distance(p - e.yxy),
                          lab_shape_distance(p + e.yyx) - lab_shape_distance(p - e.yyx)));
}

// Texture coordinates: around the torus' two circles, or longitude/latitude.
vec2 lab_shape_uv(vec3 p) {
    float u = precise_atan(p.z, p.x) / (2.0 * PI) + 0.5;
    if (u_shape == 0) {
        vec2 q = vec2(length(p.xz) - 0.72, p.y);
        return vec2(u, precise_atan(q.y, q.x) / (2.0 * PI) + 0.5);
    }
    return vec2(u, angle_from_cos(p.y / max(length(p), 1e-6)) / PI);
}

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
    vec3 eye = vec3(0.0, 0.0, 3.4);
    vec3 ray = normalize(vec3(p * 0.42, -1.0));
    mat3 R = lab_object_rotation();
    // March in object space: rotate the ray instead of the object.
    vec3 o = transpose(R) * eye;
    vec3 d = transpose(R) * ray;
    float t = 1.5;
    bool hit = false;
    for (int i = 0; i < 96; ++i) {
        float dist = lab_shape_distance(o + t * d);
        if (dist < 5e-4) {
            hit = true;
            break;
        }
        t += dist * 0.8;
        if (t > 6.0) break;
    }
    if (!hit) {
        frag_color = vec4(0.0);
        return;
    }
    // Two more steps put the hit on the surface itself, not anywhere within the 5e-4 of the
    // loop's test: the shading then no longer depends on where the march happened to stop.
    t += lab_shape_distance(o + t * d);
    t += lab_shape_distance(o + t * d);
    vec3 q = o + t * d;
    vec3 n_obj = lab_shape_normal(q);
    vec3 x_obj = u_shape == 0 ? vec3(-q.z, 0.0, q.x) : cross(vec3(0.0, 1.0, 0.0), n_obj);
    if (dot(x_obj, x_obj) < 1e-10) x_obj = vec3(1.0, 0.0, 0.0);
    vec3 N = normalize(R * n_obj);
    vec3 X = R * x_obj;
    X = normalize(X - N * dot(N, X));
    vec3 Y = cross(N, X);
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

// View: the lab's procedural object (the shapes and turn of views/object.glsl, ray-marched
// signed distance fields) under an environment map, by Monte Carlo integration of the
// reflection equation (terms/environment.glsl, which the host puts before this file),
// accumulated like views/ibl.glsl: each pass adds the sum of u_spp samples per pixel, with
// u_spp in alpha on the object and 0 on the background.
// The geometry mirrors views/object.glsl (tests/test_ibl_object.py holds the silhouettes
// equal), with one BRDF for the whole surface (that view's "single BRDF" mode).
uniform vec2 u_resolution;
uniform int u_shape;  // 0 torus, 1 sphere, 2 rounded box, 3 bumpy sphere
uniform float u_yaw;
uniform float u_pitch;
uniform int u_spp;
uniform int u_frame;
uniform int u_seed;
out vec4 frag_color;

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

void main() {
    vec2 p = (gl_FragCoord.xy / u_resolution) * 2.0 - 1.0;
    vec3 eye = vec3(0.0, 0.0, 3.4);
    vec3 ray = normalize(vec3(p * 0.42, -1.0));
    mat3 R = lab_object_rotation();
    vec3 o = transpose(R) * eye;  // march in object space: rotate the ray, not the object
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
        frag_color = vec4(environment(ray) * float(u_spp), 0.0);  // the map behind
        return;
    }
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
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    lab_seed(uint(pixel.y * 8192 + pixel.x), uint(u_frame) * 7919u + uint(u_seed));
    vec3 total = vec3(0.0);
    for (int i = 0; i < 1024; ++i) {
        if (i >= u_spp) break;
        total += one_sample(V, N, X, Y);
    }
    if (IS_DELTA) {
        vec3 Rv = reflect(-V, N);
        total += DELTA_REFLECTANCE(Rv, N, X, Y) * environment(Rv) * float(u_spp);
    }
    frag_color = vec4(total, float(u_spp));
}

// The lab's procedural object, shared by views/object.glsl and views/ibl_object.glsl (each
// has an @include line for it): its shapes (signed distance fields, ray-marched; no mesh
// files), its turn, and the point of its surface that a pixel sees.
uniform int u_shape;  // 0 torus, 1 sphere, 2 rounded box, 3 bumpy sphere
uniform float u_yaw;
uniform float u_pitch;

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

// The surface seen through p (-1..1 across the view), or false for the background: `ray`
// is the view ray, `q` the point in object space, N, X, Y its shading frame (world space).
bool lab_object_surface(vec2 p, out vec3 ray, out vec3 q, out vec3 N, out vec3 X, out vec3 Y) {
    vec3 eye = vec3(0.0, 0.0, 3.4);
    ray = normalize(vec3(p * 0.42, -1.0));
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
    if (!hit) return false;
    // Two more steps put the hit on the surface itself, not anywhere within the 5e-4 of the
    // loop's test: the shading then no longer depends on where the march happened to stop.
    t += lab_shape_distance(o + t * d);
    t += lab_shape_distance(o + t * d);
    q = o + t * d;
    vec3 n_obj = lab_shape_normal(q);
    vec3 x_obj = u_shape == 0 ? vec3(-q.z, 0.0, q.x) : cross(vec3(0.0, 1.0, 0.0), n_obj);
    if (dot(x_obj, x_obj) < 1e-10) x_obj = vec3(1.0, 0.0, 0.0);
    N = normalize(R * n_obj);
    X = R * x_obj;
    X = normalize(X - N * dot(N, X));
    Y = cross(N, X);
    return true;
}

// Texture coordinates of the object-space point p (object.glsl, grade_object.glsl): around
// the torus' two circles, or longitude and latitude. The tangent X above points along u.
vec2 lab_shape_uv(vec3 p) {
    float u = precise_atan(p.z, p.x) / (2.0 * PI) + 0.5;
    if (u_shape == 0) {
        vec2 q = vec2(length(p.xz) - 0.72, p.y);
        return vec2(u, precise_atan(q.y, q.x) / (2.0 * PI) + 0.5);
    }
    return vec2(u, angle_from_cos(p.y / max(length(p), 1e-6)) / PI);
}

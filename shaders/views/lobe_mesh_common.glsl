// Shared by the 3D lobe's programs (lobe_mesh*.glsl): the hemisphere grid and the orbit
// camera. Model-free; the host puts it before the model code.
//
// Grid: vertex (i, j), i < u_grid.x rows of theta_o from 0 to 90 deg, j < u_grid.y columns
// of phi_o once around. Row and column spacing grow quadratically away from the mirror
// direction, which is a vertex itself, so a sharp lobe's tip is sampled densely and exactly.
//
// Camera: world space is the local frame (N = z, X = x). The scene turns by u_yaw about the
// normal; the eye looks down at u_pitch above the horizon, at the point LOBE_TARGET.
// View space: x right, y up, z toward the eye.
uniform ivec2 u_grid;
uniform vec2 u_light_angles;  // theta_i, phi_i in radians
uniform float u_yaw;
uniform float u_pitch;
uniform float u_zoom;
uniform vec2 u_aspect;  // shorter side / width, shorter side / height
uniform bool u_perspective;

const float LOBE_PI = 3.14159265358979;
const vec3 LOBE_TARGET = vec3(0.0, 0.0, 0.3);
const float LOBE_DISTANCE = 5.0;  // eye distance, in units of the lobe's peak radius
const float LOBE_SCALE = 0.85;  // clip units per world unit at the target at zoom 1
const float LOBE_DEPTH = 0.25;  // view-space depth to clip depth

// Value k of n from lo to hi with the spacing growing quadratically away from index kc.
float lobe_warp(int k, int kc, int n, float center, float lo, float hi) {
    if (k < kc) {
        float s = float(kc - k) / float(kc);
        return center - (center - lo) * s * s;
    }
    if (k > kc) {
        float s = float(k - kc) / float(n - 1 - kc);
        return center + (hi - center) * s * s;
    }
    return center;
}

// (theta_o, phi_o) in radians of grid vertex (i, j).
vec2 lobe_grid(int i, int j) {
    float half_pi = 0.5 * LOBE_PI;
    float theta_i = clamp(u_light_angles.x, 0.0, half_pi);
    int kc = int(floor(float(u_grid.x - 1) * min(theta_i / radians(89.5), 1.0) + 0.5));
    // The last row stays a hair above the horizon, where f_r is still defined: the surface
    // ends at its rim instead of folding back to the origin.
    float top = radians(89.5);
    float theta = lobe_warp(i, kc, u_grid.x, min(theta_i, top), 0.0, top);
    float phi_m = u_light_angles.y + LOBE_PI;
    int jc = (u_grid.y - 1) / 2;
    float phi = lobe_warp(j, jc, u_grid.y, phi_m, phi_m - LOBE_PI, phi_m + LOBE_PI);
    return vec2(theta, phi);
}

// Directions by common.glsl's lab_cos_sin (float-precise on every GPU; SwiftShader's sin and
// cos are coarse, and a sharp lobe amplifies that): the model programs define it after this.
// The marks' program (lobe_mesh_lines.glsl, which defines VERTEX) has no model and no need.
#ifndef VERTEX
vec2 lab_cos_sin(float angle);
vec3 lobe_direction(vec2 angles) {
    vec2 t = lab_cos_sin(angles.x);
    vec2 p = lab_cos_sin(angles.y);
    return vec3(t.y * p.x, t.y * p.y, t.x);
}
#endif

// World -> view space.
vec3 lobe_view(vec3 p) {
    float c = cos(u_yaw);
    float s = sin(u_yaw);
    vec3 q = vec3(c * p.x - s * p.y, s * p.x + c * p.y, p.z) - LOBE_TARGET;
    float cp = cos(u_pitch);
    float sp = sin(u_pitch);
    return vec3(q.x, q.y * sp + q.z * cp, q.z * sp - q.y * cp);
}

// View space -> clip space; depth is linear in view-space z (nearer is smaller).
vec4 lobe_clip(vec3 v) {
    float w = u_perspective ? (LOBE_DISTANCE - v.z) / LOBE_DISTANCE : 1.0;
    vec2 xy = v.xy * (LOBE_SCALE * u_zoom) * u_aspect;
    return vec4(xy, -v.z * LOBE_DEPTH * w, w);
}

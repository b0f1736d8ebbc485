// View: f_r over the half/difference angles of Rusinkiewicz (1998): theta_h grows to the
// right (0..90 deg), theta_d upwards (0..90 deg), at a fixed phi_d (and phi_h = 0).
uniform vec2 u_resolution;
uniform float u_phi_d;
out vec4 frag_color;

// Rotation about the bitangent y by angle t.
vec3 lab_rotate_y(vec3 v, float t) {
    vec2 cs = lab_cos_sin(t);
    return vec3(cs.x * v.x + cs.y * v.z, v.y, -cs.y * v.x + cs.x * v.z);
}

void main() {
    vec2 uv = gl_FragCoord.xy / u_resolution;
    float theta_h = uv.x * 0.5 * PI;
    float theta_d = uv.y * 0.5 * PI;
    vec2 cs_d = lab_cos_sin(theta_d);
    vec2 cs_phi = lab_cos_sin(u_phi_d);
    vec3 d = vec3(cs_d.y * cs_phi.x, cs_d.y * cs_phi.y, cs_d.x);
    vec3 L = lab_rotate_y(d, theta_h);
    vec3 V = lab_rotate_y(vec3(-d.x, -d.y, d.z), theta_h);
    frag_color = vec4(BRDF(L, V, vec3(0.0, 0.0, 1.0), vec3(1.0, 0.0, 0.0), vec3(0.0, 1.0, 0.0)), 1.0);
}

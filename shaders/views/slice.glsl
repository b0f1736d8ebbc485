// View: f_r over the half/difference angles of Rusinkiewicz (1998): theta_h grows to the
// right (0..90 deg), theta_d upwards (0..90 deg), at a fixed phi_d (and phi_h = 0).
uniform vec2 u_resolution;
uniform float u_phi_d;
out vec4 frag_color;

// Rotation about the bitangent y by angle t.
vec3 lab_rotate_y(vec3 v, float t) {
    float c = cos(t);
    float s = sin(t);
    return vec3(c * v.x + s * v.z, v.y, -s * v.x + c * v.z);
}

void main() {
    vec2 uv = gl_FragCoord.xy / u_resolution;
    float theta_h = uv.x * 0.5 * PI;
    float theta_d = uv.y * 0.5 * PI;
    vec3 d = vec3(sin(theta_d) * cos(u_phi_d), sin(theta_d) * sin(u_phi_d), cos(theta_d));
    vec3 L = lab_rotate_y(d, theta_h);
    vec3 V = lab_rotate_y(vec3(-d.x, -d.y, d.z), theta_h);
    frag_color = vec4(BRDF(L, V, vec3(0.0, 0.0, 1.0), vec3(1.0, 0.0, 0.0), vec3(0.0, 1.0, 0.0)), 1.0);
}

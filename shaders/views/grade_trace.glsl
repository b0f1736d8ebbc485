// View (grading): the values a BRDF's traced expressions take (lab.grading.trace). An input
// row is the direction pair (theta_i, phi_i, theta_o, phi_o); row 0 holds f_r.
// @include views/trace_common.glsl
out vec4 frag_color;

void main() {
    vec4 a = lab_trace_begin();
    vec3 L = lab_trace_direction(a.x, a.y);
    vec3 V = lab_trace_direction(a.z, a.w);
    frag_color = lab_trace_end(BRDF(L, V, vec3(0.0, 0.0, 1.0), vec3(1.0, 0.0, 0.0), vec3(0.0, 1.0, 0.0)));
}

// View (grading): the values a sampler's traced expressions take (lab.grading.trace), as
// grade_trace.glsl does for a BRDF. An input row holds the random numbers u (x, y) and the
// view direction's (theta_o, phi_o); row 0 holds the sampled L scaled by 1 + its pdf, the
// other rows the values both in sample_lobe and in pdf_lobe at that L.
// @include views/trace_common.glsl
out vec4 frag_color;

void main() {
    vec4 a = lab_trace_begin();
    vec3 V = lab_trace_direction(a.z, a.w);
    vec3 N = vec3(0.0, 0.0, 1.0);
    vec3 X = vec3(1.0, 0.0, 0.0);
    vec3 Y = vec3(0.0, 1.0, 0.0);
    vec3 L = sample_lobe(a.xy, V, N, X, Y);
    frag_color = lab_trace_end(L * (1.0 + pdf_lobe(L, V, N, X, Y)));
}

// View (grading): the values a sampler's traced expressions take (lab.grading.trace), as
// grade_trace.glsl does for a BRDF. Texel x of u_angles holds the random numbers u (x, y)
// and the view direction's (theta_o, phi_o) in radians; row 0 holds the sampled L, row k
// the value of the expression with slot k, both in sample_lobe and in pdf_lobe at that L.
uniform highp sampler2D u_angles;
out vec4 frag_color;

vec3 lab_trace_direction(float theta, float phi) {
    float s = sin(theta);
    return vec3(s * cos(phi), s * sin(phi), cos(theta));
}

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    vec4 a = texelFetch(u_angles, ivec2(pixel.x, 0), 0);
    vec3 V = lab_trace_direction(a.z, a.w);
    vec3 N = vec3(0.0, 0.0, 1.0);
    vec3 X = vec3(1.0, 0.0, 0.0);
    vec3 Y = vec3(0.0, 1.0, 0.0);
    lab_trace_slot = pixel.y;
    lab_trace_value = vec4(0.0);
    vec3 L = sample_lobe(a.xy, V, N, X, Y);
    float pdf = pdf_lobe(L, V, N, X, Y);
    frag_color = pixel.y == 0 ? vec4(L * (1.0 + pdf), 3.0) : lab_trace_value;
}

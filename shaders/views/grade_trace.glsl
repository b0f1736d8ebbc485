// View (grading): the values a program's traced expressions take (lab.grading.trace).
// Column x is the direction pair (theta_i, phi_i, theta_o, phi_o) at texel x of u_angles,
// in radians; row 0 holds f_r, row k the value the expression with slot k last took
// (xyz, and in w its component count; 0 where the expression did not run).
uniform highp sampler2D u_angles;
out vec4 frag_color;

vec3 lab_trace_direction(float theta, float phi) {
    float s = sin(theta);
    return vec3(s * cos(phi), s * sin(phi), cos(theta));
}

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    vec4 a = texelFetch(u_angles, ivec2(pixel.x, 0), 0);
    vec3 L = lab_trace_direction(a.x, a.y);
    vec3 V = lab_trace_direction(a.z, a.w);
    lab_trace_slot = pixel.y;
    lab_trace_value = vec4(0.0);
    vec3 f = BRDF(L, V, vec3(0.0, 0.0, 1.0), vec3(1.0, 0.0, 0.0), vec3(0.0, 1.0, 0.0));
    frag_color = pixel.y == 0 ? vec4(f, 3.0) : lab_trace_value;
}

// View (tests and grading): PDF_BRDF for direction pairs; u_L and u_V hold L and V in the
// local frame (N = z), one pair per texel. Alpha carries f_r cos / pdf's luminance.
uniform sampler2D u_L;
uniform sampler2D u_V;
out vec4 frag_color;

void main() {
    ivec2 texel = ivec2(gl_FragCoord.xy);
    vec3 L = texelFetch(u_L, texel, 0).xyz;
    vec3 V = texelFetch(u_V, texel, 0).xyz;
    vec3 N = vec3(0.0, 0.0, 1.0);
    vec3 X = vec3(1.0, 0.0, 0.0);
    vec3 Y = vec3(0.0, 1.0, 0.0);
    float pdf = HAS_SAMPLER ? PDF_BRDF(L, V, N, X, Y) : 0.0;
    frag_color = vec4(pdf, 0.0, 0.0, 0.0);
}

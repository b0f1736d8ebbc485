// View (tests and grading): one BRDF sample per texel. u_V holds V in the local frame
// (N = z); the output is L and PDF_BRDF(L) (pdf 0 and L = 0 for models without a sampler).
uniform sampler2D u_V;
uniform int u_seed;
out vec4 frag_color;

void main() {
    ivec2 texel = ivec2(gl_FragCoord.xy);
    vec3 V = texelFetch(u_V, texel, 0).xyz;
    vec3 N = vec3(0.0, 0.0, 1.0);
    vec3 X = vec3(1.0, 0.0, 0.0);
    vec3 Y = vec3(0.0, 1.0, 0.0);
    lab_seed(uint(texel.y * 8192 + texel.x), uint(u_seed));
    if (!HAS_SAMPLER) {
        frag_color = vec4(0.0);
        return;
    }
    vec3 L = SAMPLE_BRDF(V, N, X, Y, lab_random3());
    frag_color = vec4(L, PDF_BRDF(L, V, N, X, Y));
}

// View (tests and grading): one BRDF sample per texel. u_V holds V in the local frame
// (N = z); the output is L in that frame and PDF_BRDF(L) (pdf 0 and L = 0 for models
// without a sampler). The shading frame (u_N, u_X, u_Y) may be turned away from the axes,
// so that a sampler that forgets to carry its local directions into (X, Y, N) shows.
uniform sampler2D u_V;
uniform int u_seed;
uniform vec3 u_N;
uniform vec3 u_X;
uniform vec3 u_Y;
out vec4 frag_color;

void main() {
    ivec2 texel = ivec2(gl_FragCoord.xy);
    vec3 v = texelFetch(u_V, texel, 0).xyz;
    vec3 V = v.x * u_X + v.y * u_Y + v.z * u_N;
    lab_seed(uint(texel.y * 8192 + texel.x), uint(u_seed));
    if (!HAS_SAMPLER) {
        frag_color = vec4(0.0);
        return;
    }
    vec3 L = SAMPLE_BRDF(V, u_N, u_X, u_Y, lab_random3());
    float pdf = PDF_BRDF(L, V, u_N, u_X, u_Y);
    frag_color = vec4(dot(L, u_X), dot(L, u_Y), dot(L, u_N), pdf);
}

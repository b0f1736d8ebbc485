// View: a microfacet model's terms on their own, for the D, G, F plot (lab/views/terms.py).
// The model defines MICROFACET_TERMS (shaders/README.md); the (L, V) pairs come from two float
// textures, as in probe.glsl, in the local frame N = z, X = x, Y = y.
// u_part 0: (D, G, 0, 1); u_part 1: (F, 1), one texel per pair.
uniform highp sampler2D u_L;
uniform highp sampler2D u_V;
uniform int u_part;
out vec4 frag_color;

void main() {
    ivec2 texel = ivec2(gl_FragCoord.xy);
    vec3 L = texelFetch(u_L, texel, 0).xyz;
    vec3 V = texelFetch(u_V, texel, 0).xyz;
    float D;
    float G;
    vec3 F;
    MICROFACET_TERMS(L, V, vec3(0.0, 0.0, 1.0), vec3(1.0, 0.0, 0.0), vec3(0.0, 1.0, 0.0), D, G, F);
    frag_color = u_part == 0 ? vec4(D, G, 0.0, 1.0) : vec4(F, 1.0);
}

// View: one BRDF value per pixel for the (L, V) pair stored at that pixel of two float
// textures, in the local frame N = z, X = x, Y = y. The lab's "eval" runs through here.
uniform highp sampler2D u_L;
uniform highp sampler2D u_V;
out vec4 frag_color;

void main() {
    ivec2 texel = ivec2(gl_FragCoord.xy);
    vec3 L = texelFetch(u_L, texel, 0).xyz;
    vec3 V = texelFetch(u_V, texel, 0).xyz;
    frag_color = vec4(BRDF(L, V, vec3(0.0, 0.0, 1.0), vec3(1.0, 0.0, 0.0), vec3(0.0, 1.0, 0.0)), 1.0);
}

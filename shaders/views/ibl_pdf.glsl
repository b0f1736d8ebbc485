// View (tests and grading): PDF_BRDF for direction pairs; u_L and u_V hold L and V in the
// local frame (N = z), one pair per texel, carried into the shading frame (u_N, u_X, u_Y)
// as in ibl_sample.glsl.
uniform sampler2D u_L;
uniform sampler2D u_V;
uniform vec3 u_N;
uniform vec3 u_X;
uniform vec3 u_Y;
out vec4 frag_color;

void main() {
    ivec2 texel = ivec2(gl_FragCoord.xy);
    vec3 l = texelFetch(u_L, texel, 0).xyz;
    vec3 v = texelFetch(u_V, texel, 0).xyz;
    vec3 L = l.x * u_X + l.y * u_Y + l.z * u_N;
    vec3 V = v.x * u_X + v.y * u_Y + v.z * u_N;
    float pdf = HAS_SAMPLER ? PDF_BRDF(L, V, u_N, u_X, u_Y) : 0.0;
    frag_color = vec4(pdf, 0.0, 0.0, 0.0);
}

// View: f_r(L, V) times u_gain for every view direction V of the hemisphere, seen from
// above (the disc), for one light L; alpha 0 off the disc. Added by a test.
uniform vec2 u_resolution;
uniform vec3 u_light;
uniform float u_gain;
out vec4 frag_color;

void main() {
    vec2 p = gl_FragCoord.xy / u_resolution * 2.0 - 1.0;
    float r2 = dot(p, p);
    if (r2 > 1.0) {
        frag_color = vec4(0.0);
        return;
    }
    vec3 V = vec3(p, sqrt(1.0 - r2));
    frag_color = vec4(u_gain * BRDF(u_light, V, vec3(0.0, 0.0, 1.0), vec3(1.0, 0.0, 0.0), vec3(0.0, 1.0, 0.0)), 1.0);
}

// View: the lit sphere under an environment map, by Monte Carlo integration of the
// reflection equation (terms/environment.glsl, which the host puts before this file).
// Each pass adds the sum of u_spp samples per pixel (and u_spp in alpha on the sphere, 0
// outside); the host sums passes by additive blending and divides by the sample count,
// so the image converges progressively.
uniform vec2 u_resolution;
uniform int u_spp;
uniform int u_frame;
uniform int u_seed;
out vec4 frag_color;

void main() {
    vec2 p = gl_FragCoord.xy / u_resolution * 2.0 - 1.0;
    float r2 = dot(p, p);
    if (r2 > 1.0) {
        // The background: the environment behind the sphere, through a 90-degree lens.
        frag_color = vec4(environment(normalize(vec3(p, -1.0))) * float(u_spp), 0.0);
        return;
    }
    vec3 N = vec3(p, sqrt(1.0 - r2));
    vec3 V = vec3(0.0, 0.0, 1.0);
    vec3 X = vec3(N.z, 0.0, -N.x);  // along the latitude circles, as in the sphere view
    X = dot(X, X) > 1e-12 ? normalize(X) : vec3(1.0, 0.0, 0.0);
    vec3 Y = cross(N, X);
    // Sums: the host divides by the sample count.
    frag_color = vec4(pass_sum(V, N, X, Y, u_spp, u_frame, u_seed), float(u_spp));
}

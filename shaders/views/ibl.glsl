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
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    lab_seed(uint(pixel.y * 8192 + pixel.x), uint(u_frame) * 7919u + uint(u_seed));
    vec3 total = vec3(0.0);
    for (int i = 0; i < 1024; ++i) {
        if (i >= u_spp) break;
        total += one_sample(V, N, X, Y);
    }
    if (IS_DELTA) {
        vec3 R = reflect(-V, N);
        total += DELTA_REFLECTANCE(R, N, X, Y) * environment(R) * float(u_spp);
    }
    frag_color = vec4(total, float(u_spp));  // sums: the host divides by the sample count
}

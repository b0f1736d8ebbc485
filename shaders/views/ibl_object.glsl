// View: the lab's procedural object (views/object_shape.glsl, as views/object.glsl draws it)
// under an environment map, by Monte Carlo integration of the reflection equation
// (terms/environment.glsl, which the host puts before this file), accumulated like
// views/ibl.glsl: each pass adds the sum of u_spp samples per pixel, with u_spp in alpha on
// the object and 0 on the background. One BRDF for the whole surface (that view's "single
// BRDF" mode).
// @include views/object_shape.glsl
uniform vec2 u_resolution;
uniform int u_spp;
uniform int u_frame;
uniform int u_seed;
out vec4 frag_color;

void main() {
    vec2 p = (gl_FragCoord.xy / u_resolution) * 2.0 - 1.0;
    vec3 ray, q, N, X, Y;
    if (!lab_object_surface(p, ray, q, N, X, Y)) {
        frag_color = vec4(environment(ray) * float(u_spp), 0.0);  // the map behind
        return;
    }
    frag_color = vec4(pass_sum(-ray, N, X, Y, u_spp, u_frame, u_seed), float(u_spp));
}

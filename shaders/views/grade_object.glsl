// View: a spatially varying BRDF on the lab's object (the `object` check kind, exercise 13).
// The model file defines SVBRDF(uv, L, V, N, X, Y) and declares the sampler2D uniforms it
// reads; the kind binds a texture to each. Every pixel finds the surface point the object
// view finds (views/object_shape.glsl: its texture coordinate uv and its shading frame N, X,
// Y, with X along u) and sums LIGHT_COUNT directional lights, cos(theta) outside the BRDF.
// @include views/object_shape.glsl
uniform vec2 u_resolution;
uniform vec3 u_light_dir[LAB_MAX_LIGHTS];
uniform vec3 u_light_rgb[LAB_MAX_LIGHTS];
out vec4 frag_color;

void main() {
    vec2 p = (gl_FragCoord.xy / u_resolution) * 2.0 - 1.0;
    vec3 ray, q, N, X, Y;
    if (!lab_object_surface(p, ray, q, N, X, Y)) {
        frag_color = vec4(0.0);
        return;
    }
    vec3 V = -ray;
    vec2 uv = lab_shape_uv(q);
    vec3 color = vec3(0.0);
    for (int i = 0; i < LIGHT_COUNT; ++i) {
        vec3 L = u_light_dir[i];
        float cosine = dot(N, L);
        if (cosine > 0.0) color += u_light_rgb[i] * SVBRDF(uv, L, V, N, X, Y) * cosine;
    }
    frag_color = vec4(color, 1.0);
}

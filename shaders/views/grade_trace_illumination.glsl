// View (grading): the values an illumination model's traced expressions take
// (lab.grading.trace), as grade_trace.glsl does for a BRDF. Texel x of u_angles holds the
// normal's (theta, phi) in radians (in camera space, the eye along z); the model's
// phong_illumination(N, V, ambient, light_dir[8], light_rgb[8], count) is lit by three
// coloured lights (one to the side, one behind the sphere, one low on the other side), an
// ambient light, and past `count` a light that is not in the scene, as in
// grade_illumination.glsl, so that code which ignores count shows it.
// @include views/trace_common.glsl
out vec4 frag_color;

void main() {
    vec4 a = lab_trace_begin();
    vec3 N = lab_trace_direction(a.x, a.y);
    vec3 V = vec3(0.0, 0.0, 1.0);
    vec3 dirs[8];
    vec3 rgbs[8];
    for (int i = 0; i < 8; ++i) {
        dirs[i] = normalize(vec3(-0.4, 0.5, 0.75));
        rgbs[i] = vec3(0.9, 0.6, 1.0);
    }
    dirs[0] = normalize(vec3(0.6, 0.3, 0.75));
    rgbs[0] = vec3(1.0, 0.8, 0.6);
    dirs[1] = normalize(vec3(-0.3, 0.2, -0.9));
    rgbs[1] = vec3(0.5, 0.7, 1.2);
    dirs[2] = normalize(vec3(-0.8, -0.5, 0.2));
    rgbs[2] = vec3(0.7, 1.1, 0.6);
    frag_color = lab_trace_end(phong_illumination(N, V, vec3(0.2, 0.15, 0.1), dirs, rgbs, 3));
}

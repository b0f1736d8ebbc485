// View (grading): the sphere of views/sphere.glsl shaded by the model's own
// phong_illumination(N, V, ambient, light_dir[8], light_rgb[8], count), the Phong
// illumination model of exercise 04, instead of the view summing BRDF * cos over lights.
uniform vec2 u_resolution;
uniform vec3 u_light_dir[8];
uniform vec3 u_light_rgb[8];
uniform vec3 u_ambient;
out vec4 frag_color;

void main() {
    vec2 p = gl_FragCoord.xy / u_resolution * 2.0 - 1.0;
    float r2 = dot(p, p);
    if (r2 > 1.0) {
        frag_color = vec4(0.0);
        return;
    }
    vec3 N = vec3(p, sqrt(1.0 - r2));
    vec3 V = vec3(0.0, 0.0, 1.0);
    vec3 dirs[8];
    vec3 rgbs[8];
    for (int i = 0; i < 8; ++i) {
        // Past LIGHT_COUNT a slot holds a light that is not in the scene, so that code
        // which ignores `count` shows it (dark padding would hide the mistake).
        bool used = i < LIGHT_COUNT;
        dirs[i] = used ? u_light_dir[i] : normalize(vec3(-0.4, 0.5, 0.75));
        rgbs[i] = used ? u_light_rgb[i] : vec3(0.9, 0.6, 1.0);
    }
    frag_color = vec4(phong_illumination(N, V, u_ambient, dirs, rgbs, LIGHT_COUNT), 1.0);
}

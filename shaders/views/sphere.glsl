// View: a unit sphere seen by an orthographic camera looking down -z (x right, y up).
// LIGHT_COUNT (a constant from the host) directional lights, and ambient light u_ambient,
// reflected by AMBIENT_REFLECTANCE() (the Phong illumination model's ka; 1 for other models).
// A delta (mirror) model reflects the procedural environment of lab_environment().
uniform vec2 u_resolution;
uniform vec3 u_light_dir[LAB_MAX_LIGHTS];
uniform vec3 u_light_rgb[LAB_MAX_LIGHTS];
uniform vec3 u_ambient;
uniform bool u_multiply_cos;
out vec4 frag_color;

// Sky above the horizon (y > 0), a checkered floor below it, and a sun where light 1 is
// (so dragging the light moves the sun's reflection in the mirror; fixed with no lights).
vec3 lab_environment(vec3 d) {
    vec3 sun_dir = LIGHT_COUNT > 0 ? u_light_dir[0] : normalize(vec3(0.4, 0.7, 0.6));
    float sun = pow(max(dot(d, sun_dir), 0.0), 400.0);
    vec3 sun_rgb = vec3(20.0, 18.0, 14.0) * (LIGHT_COUNT > 0 ? u_light_rgb[0] : vec3(1.0));
    if (d.y >= 0.0) {
        vec3 sky = mix(vec3(0.85, 0.9, 1.0), vec3(0.2, 0.4, 0.85), sqrt(d.y));
        return sky + sun_rgb * sun;
    }
    vec2 floor_point = d.xz / max(-d.y, 0.05);
    float check = mod(floor(floor_point.x) + floor(floor_point.y), 2.0);
    return mix(vec3(0.1), vec3(0.6), check) * (0.4 + 0.6 * min(-d.y * 4.0, 1.0)) + sun_rgb * sun;
}

void main() {
    vec2 p = gl_FragCoord.xy / u_resolution * 2.0 - 1.0;
    float r2 = dot(p, p);
    if (r2 > 1.0) {
        frag_color = vec4(0.0);
        return;
    }
    vec3 N = vec3(p, sqrt(1.0 - r2));
    vec3 V = vec3(0.0, 0.0, 1.0);
    // Tangent along the sphere's latitude circles (around the screen's up axis).
    vec3 X = vec3(N.z, 0.0, -N.x);
    X = dot(X, X) > 1e-12 ? normalize(X) : vec3(1.0, 0.0, 0.0);
    vec3 Y = cross(N, X);
    vec3 color = u_ambient * AMBIENT_REFLECTANCE();
    for (int i = 0; i < LIGHT_COUNT; ++i) {
        vec3 L = u_light_dir[i];
        float cosine = u_multiply_cos ? max(dot(N, L), 0.0) : 1.0;
        color += u_light_rgb[i] * BRDF(L, V, N, X, Y) * cosine;
    }
    if (IS_DELTA) {
        vec3 R = reflect(-V, N);
        color += DELTA_REFLECTANCE(R, N, X, Y) * lab_environment(R);
    }
    frag_color = vec4(color, 1.0);
}

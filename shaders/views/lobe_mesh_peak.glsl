// View: the 3D lobe's values on its grid (lobe_mesh_common.glsl), one texel per vertex, so
// the host scales the surface by exactly what the vertex stage will draw.
// Texel (j, i): r = luminance of f_r (times cos theta_o when u_cos), g = the same but 0
// beyond 87 deg (grazing values some models blow up are left out of the scale), b = the
// luminance of the delta spike's reflectance (0 for models without one).
uniform bool u_cos;
out vec4 frag_color;

void main() {
    ivec2 texel = ivec2(gl_FragCoord.xy);
    vec2 angles = lobe_grid(texel.y, texel.x);
    vec3 N = vec3(0.0, 0.0, 1.0);
    vec3 X = vec3(1.0, 0.0, 0.0);
    vec3 Y = vec3(0.0, 1.0, 0.0);
    vec3 L = lobe_direction(u_light_angles);
    vec3 V = lobe_direction(angles);
    vec3 luma = LAB_LUMA;
    float value = dot(BRDF(L, V, N, X, Y), luma);
    if (u_cos) value *= max(V.z, 0.0);
    float shown = angles.x <= radians(LAB_GRAZING_DEG) ? value : 0.0;
    frag_color = vec4(value, shown, dot(DELTA_REFLECTANCE(L, N, X, Y), luma), 1.0);
}

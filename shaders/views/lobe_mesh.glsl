// View: the 3D lobe as a surface, drawn by the model's own BRDF in the VERTEX stage.
// Vertex gl_VertexID = i * u_grid.y + j is grid vertex (i, j) of lobe_mesh_common.glsl (an
// index buffer makes the triangles; there are no vertex attributes). The vertex lies at
// r * V, r = f_r (or f_r cos theta_o) relative to u_peak, linear or over u_decades decades.
// The fragment stage (lobe_mesh_shade.glsl) shades it.
uniform float u_peak;  // the value drawn at radius 1
uniform bool u_log;
uniform float u_decades;
uniform bool u_cos;
out vec3 v_view;  // view-space position (flat shading from its derivatives)
out vec2 v_angles;  // theta_o, phi_o in degrees (grid lines)

const float LOBE_MAX_RADIUS = 1.5;

void main() {
    int i = gl_VertexID / u_grid.y;
    int j = gl_VertexID - i * u_grid.y;
    vec2 angles = lobe_grid(i, j);
    vec3 N = vec3(0.0, 0.0, 1.0);
    vec3 X = vec3(1.0, 0.0, 0.0);
    vec3 Y = vec3(0.0, 1.0, 0.0);
    vec3 L = lobe_direction(u_light_angles);
    vec3 V = lobe_direction(angles);
    float value = dot(BRDF(L, V, N, X, Y), LAB_LUMA);
    if (u_cos) value *= max(V.z, 0.0);
    float r;
    if (u_log) {
        float floor_value = u_peak * pow(10.0, -u_decades);
        r = max(log(max(value, floor_value) / floor_value) / (log(10.0) * u_decades), 0.0);
    } else {
        r = value / u_peak;
    }
    // NaN (a model dividing by zero at grazing angles) draws at the origin, inf at the edge.
    r = isnan(r) ? 0.0 : clamp(r, 0.0, LOBE_MAX_RADIUS);
    v_view = lobe_view(r * V);
    v_angles = degrees(angles);
    gl_Position = lobe_clip(v_view);
}

// The 3D lobe's marks (horizon circle, normal, incident and mirror directions, delta
// spikes): world-space segments drawn as anti-aliased screen-space quads, dashed or solid,
// by the same camera as the lobe (lobe_mesh_common.glsl). Model-free. Compiled twice:
// with VERTEX defined for the vertex stage and without it for the fragment stage.
// Segment k is u_a[k] -> u_b[k]; u_style[k] = (width in pixels, dash period in pixels or 0).
#ifdef VERTEX
const int MAX_SEGMENTS = 96;
uniform vec3 u_a[MAX_SEGMENTS];
uniform vec3 u_b[MAX_SEGMENTS];
uniform vec4 u_rgba[MAX_SEGMENTS];
uniform vec2 u_style[MAX_SEGMENTS];
uniform vec2 u_viewport;  // pixels
out vec4 v_rgba;
out vec2 v_style;
out float v_across;  // pixels from the segment's centre line
out float v_along;  // pixels from the segment's start

void main() {
    int k = gl_VertexID / 6;
    int corner = gl_VertexID - 6 * k;
    // Two triangles: corners (0, -), (1, -), (1, +), (0, -), (1, +), (0, +).
    bool at_b = corner == 1 || corner == 2 || corner == 4;
    float side = (corner == 2 || corner == 4 || corner == 5) ? 1.0 : -1.0;
    vec4 a = lobe_clip(lobe_view(u_a[k]));
    vec4 b = lobe_clip(lobe_view(u_b[k]));
    vec2 pa = a.xy / a.w * 0.5 * u_viewport;
    vec2 pb = b.xy / b.w * 0.5 * u_viewport;
    vec2 d = pb - pa;
    float len = length(d);
    vec2 t = len > 1e-4 ? d / len : vec2(1.0, 0.0);
    vec2 n = vec2(-t.y, t.x);
    float half_width = 0.5 * u_style[k].x + 1.0;  // a pixel more for the soft edge
    vec4 p = at_b ? b : a;
    // Ends overlap by half a width, so joined segments (the circle) leave no gaps.
    vec2 offset = side * half_width * n + (at_b ? 1.0 : -1.0) * 0.5 * u_style[k].x * t;
    p.xy += offset / (0.5 * u_viewport) * p.w;
    gl_Position = p;
    v_rgba = u_rgba[k];
    v_style = u_style[k];
    v_across = side * half_width;
    v_along = at_b ? len + 0.5 * u_style[k].x : -0.5 * u_style[k].x;
}
#else
in vec4 v_rgba;
in vec2 v_style;
in float v_across;
in float v_along;
uniform float u_fade;  // alpha factor: occluded parts are drawn faintly
out vec4 frag_color;

void main() {
    float coverage = clamp(0.5 * v_style.x + 0.5 - abs(v_across), 0.0, 1.0);
    if (v_style.y > 0.0 && fract(v_along / v_style.y) > 0.6) discard;
    float alpha = v_rgba.a * coverage * u_fade;
    if (alpha <= 0.0) discard;
    frag_color = vec4(v_rgba.rgb, alpha);
}
#endif

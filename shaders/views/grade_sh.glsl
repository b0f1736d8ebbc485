// View: exercise 15's spherical harmonics, one row per pixel. A row of u_rows holds
// (l, m, theta, phi) with the angles in radians in the shading frame's own coordinates
// (N = z): the direction w of sh_basis(l, m, w), or with u_project set the light L of
// sh_coefficient(l, m, L), the lobe's coefficient for whatever BRDF is linked in.
uniform highp sampler2D u_rows;
uniform int u_project;
out vec4 frag_color;

void main() {
    vec4 row = texelFetch(u_rows, ivec2(gl_FragCoord.xy), 0);
    int l = int(floor(row.x + 0.5));
    int m = int(floor(row.y + 0.5));
    vec2 t = lab_cos_sin(row.z);
    vec2 p = lab_cos_sin(row.w);
    vec3 w = vec3(t.y * p.x, t.y * p.y, t.x);
    vec3 value = u_project != 0 ? sh_coefficient(l, m, w) : vec3(sh_basis(l, m, w));
    frag_color = vec4(value, 1.0);
}

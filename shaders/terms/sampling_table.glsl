// Data-driven importance sampling for a model without a sampler of its own (a .brdf file,
// a measured table, a user's shader): lab/ibl/table.py tabulates f_r cos over the
// half-vector hemisphere for TABLE_VIEWS view angles, on the GPU (views/ibl_table.glsl),
// and uploads per view a piecewise-constant distribution over cells of
// (u = (1 - cos theta_h)^(1/4), phi_h - phi_v): theta_h grows about as u^2, which puts
// cells close together near N, where glossy lobes live (as the MERL layout's square root
// does), with no trigonometry to find a cell; phi runs from -pi to pi, so the cells a lobe
// covers around V's azimuth are neighbours. Rows of views are spaced evenly in
// sqrt(1 - cos theta_v) (about theta_v). A row, then a cell of it, is drawn by inverting
// their CDFs (through a guide table: one fetch each, mostly), in order, so that a
// stratified pair (u.x, u.y) stays stratified over the cells (an alias table, one fetch
// too, shuffles them), and H uniformly over the cell's solid angle, then L = reflect(-V, H):
//     p(L) = p_cell / (solid angle of the cell) / (4 V.H)
// exactly. A share of each table is spread uniformly over the half vectors (table.py
// DEFENSIVE), so every direction above the horizon has p > 0 and the estimate stays
// unbiased, with no draw of its own that would break the pair's strata.
uniform sampler2D u_table_density;  // (TABLE_PHI, TABLE_VIEWS * TABLE_U): p_cell / solid angle
// The inverse CDFs (table_invert) of a view's rows, and of a row's cells:
uniform sampler2D u_table_marginal;  // ((TABLE_GUIDES + 1) TABLE_U, TABLE_VIEWS)
uniform sampler2D u_table_conditional;  // ((TABLE_GUIDES + 1) TABLE_PHI, TABLE_VIEWS TABLE_U)
const bool HAS_SAMPLER = true;
const int TABLE_VIEWS = 32;
const int TABLE_U = 64;
const int TABLE_PHI = 32;
const int TABLE_GUIDES = 2;  // guide texels per cell

// The last direction SAMPLE_BRDF drew from the table and its pdf: PDF_BRDF of that
// direction (asked for next) is then known without finding its cell again.
vec3 table_last_L = vec3(0.0);
float table_last_pdf = -1.0;

// V in the local frame and its view-angle row of the table.
int table_view(vec3 v) {
    return clamp(int(sqrt(max(1.0 - v.z, 0.0)) * float(TABLE_VIEWS)), 0, TABLE_VIEWS - 1);
}

// (cos, sin) of V's azimuth: phi of a cell is counted from it.
vec2 table_azimuth(vec3 v) {
    float s = length(v.xy);
    return s > 1e-7 ? v.xy / s : vec2(1.0, 0.0);
}

// The cell of a row of `cdf` that x falls in, and where in it (`frac`, uniform in [0, 1))
// and the cell's probability (`mass`): guide texel g = floor(x n TABLE_GUIDES) holds
// (cell i of g's start, i's lower and upper CDF edge, i + 1's upper edge); x is in i or
// i + 1, but where small cells crowd, where texels n TABLE_GUIDES + k (cell k's edges)
// take the search on (lab/ibl/table.py inversion_tables).
int table_invert(sampler2D cdf, int row, int n, float x, out float frac, out float mass) {
    int guides = n * TABLE_GUIDES;
    vec4 g = texelFetch(cdf, ivec2(min(int(x * float(guides)), guides - 1), row), 0);
    int i = int(g.r);
    vec2 edges = g.gb;
    if (x >= edges.y) {
        ++i;
        edges = vec2(edges.y, g.a);
        while (x >= edges.y && i < n - 1) {
            ++i;
            edges = texelFetch(cdf, ivec2(guides + i, row), 0).rg;
        }
    }
    mass = edges.y - edges.x;
    frac = clamp((x - edges.x) / max(mass, 1e-30), 0.0, 1.0);
    return i;
}

// 1 - cos(theta_h) at the cell edge u.
float table_versine(float u) {
    float u2 = u * u;
    return u2 * u2;
}

vec3 SAMPLE_BRDF(vec3 V, vec3 N, vec3 X, vec3 Y, vec3 u) {
    table_last_pdf = -1.0;
    vec3 v = vec3(dot(V, X), dot(V, Y), dot(V, N));
    int j = table_view(v);
    float fu, fphi, p_row, p_cell;
    int r = table_invert(u_table_marginal, j, TABLE_U, u.x, fu, p_row);
    int c = table_invert(u_table_conditional, j * TABLE_U + r, TABLE_PHI, u.y, fphi, p_cell);
    // Uniform over the cell's solid angle: 1 - cos(theta_h) uniform between its edges (as
    // 1 - cos, not cos: float32 would lose the cells next to N).
    float w0 = table_versine(float(r) / float(TABLE_U));
    float w1 = table_versine(float(r + 1) / float(TABLE_U));
    float w = mix(w0, w1, fu);
    float cos_h = 1.0 - w;
    float sin_h = sqrt(max(w * (2.0 - w), 0.0));
    float phi = 2.0 * PI * ((float(c) + fphi) / float(TABLE_PHI) - 0.5);
    vec2 a = table_azimuth(v);
    vec2 along = cos(phi) * a + sin(phi) * vec2(-a.y, a.x);
    vec3 h = vec3(sin_h * along, cos_h);
    float VoH = dot(v, h);
    if (VoH <= 0.0) return vec3(0.0);  // a failed sample: no direction, no contribution
    vec3 l = 2.0 * VoH * h - v;
    table_last_L = to_world(l, X, Y, N);
    float solid_angle = (w1 - w0) * 2.0 * PI / float(TABLE_PHI);
    table_last_pdf = p_row * p_cell / solid_angle / (4.0 * VoH);
    return table_last_L;
}

float PDF_BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {
    if (table_last_pdf >= 0.0 && L == table_last_L) return table_last_pdf;
    vec3 v = vec3(dot(V, X), dot(V, Y), dot(V, N));
    vec3 l = vec3(dot(L, X), dot(L, Y), dot(L, N));
    vec3 sum = l + v;
    if (dot(sum, sum) < 1e-12) return 0.0;
    vec3 h = normalize(sum);
    float VoH = dot(v, h);
    if (h.z <= 0.0 || VoH <= 0.0) return 0.0;
    float versine = dot(h.xy, h.xy) / (1.0 + h.z);  // 1 - cos(theta_h), exact near N
    float u = sqrt(sqrt(versine));
    int r = min(int(u * float(TABLE_U)), TABLE_U - 1);
    vec2 a = table_azimuth(v);
    float phi = atan(dot(h.xy, vec2(-a.y, a.x)), dot(h.xy, a));  // in [-pi, pi]
    int c = clamp(int((phi / (2.0 * PI) + 0.5) * float(TABLE_PHI)), 0, TABLE_PHI - 1);
    int row = table_view(v) * TABLE_U + r;
    float density = texelFetch(u_table_density, ivec2(c, row), 0).r;
    return density / (4.0 * VoH);
}

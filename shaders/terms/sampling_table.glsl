// Data-driven importance sampling for a model without a sampler of its own (a .brdf file,
// a measured table, a user's shader): lab/ibl/table.py tabulates f_r cos over the
// half-vector hemisphere for TABLE_VIEWS view angles, on the GPU (views/ibl_table.glsl),
// and uploads per view a piecewise-constant distribution over cells of
// (u = (1 - cos theta_h)^(1/4), phi_h - phi_v): theta_h grows about as u^2, which puts
// cells close together near N, where glossy lobes live (as the MERL layout's square root
// does), with no trigonometry to find a cell. Rows of views are spaced evenly in
// sqrt(1 - cos theta_v) (about theta_v). A row, then a cell of it, is drawn by the alias
// method (one texel each: a CDF search took ten dependent fetches)
// and H uniformly over its solid angle, then L = reflect(-V, H), so
//     p(L) = p_cell / (solid angle of the cell) / (4 V.H)
// exactly; a share TABLE_COSINE of cosine-weighted directions covers whatever the table's
// cells missed (a defensive mixture, Hesterberg 1995), so every direction with
// f_r cos > 0 has p > 0 and the estimate stays unbiased.
uniform sampler2D u_table_density;  // (TABLE_PHI, TABLE_VIEWS * TABLE_U): p_cell / solid angle
uniform sampler2D u_table_marginal;  // (TABLE_U, TABLE_VIEWS): alias table of a view's rows
uniform sampler2D u_table_conditional;  // (TABLE_PHI, TABLE_VIEWS * TABLE_U): of a row's cells
const bool HAS_SAMPLER = true;
const int TABLE_VIEWS = 16;
const int TABLE_U = 32;
const int TABLE_PHI = 32;
const float TABLE_COSINE = 0.1;

// V in the local frame and its view-angle row of the table.
int table_view(vec3 v) {
    return clamp(int(sqrt(max(1.0 - v.z, 0.0)) * float(TABLE_VIEWS)), 0, TABLE_VIEWS - 1);
}

// (cos, sin) of V's azimuth: phi of a cell is counted from it.
vec2 table_azimuth(vec3 v) {
    float s = length(v.xy);
    return s > 1e-7 ? v.xy / s : vec2(1.0, 0.0);
}

// Walker's alias method: x picks bin i = floor(x n), which keeps its own cell with
// probability prob[i] and otherwise gives the alias's; what is left of x is uniform in the
// chosen cell (`frac`).
int table_pick(sampler2D alias, int row, int n, float x, out float frac) {
    float t = x * float(n);
    int i = min(int(t), n - 1);
    float f = t - float(i);
    vec2 entry = texelFetch(alias, ivec2(i, row), 0).rg;  // (prob, alias)
    if (f < entry.x) {
        frac = clamp(f / entry.x, 0.0, 1.0);
        return i;
    }
    frac = clamp((f - entry.x) / max(1.0 - entry.x, 1e-30), 0.0, 1.0);
    return int(entry.y);
}

// 1 - cos(theta_h) at the cell edge u.
float table_versine(float u) {
    float u2 = u * u;
    return u2 * u2;
}

vec3 SAMPLE_BRDF(vec3 V, vec3 N, vec3 X, vec3 Y, vec3 u) {
    if (u.z < TABLE_COSINE) return sample_cosine(u.xy, N, X, Y);
    vec3 v = vec3(dot(V, X), dot(V, Y), dot(V, N));
    int j = table_view(v);
    float fu, fphi;
    int r = table_pick(u_table_marginal, j, TABLE_U, u.x, fu);
    int row = j * TABLE_U + r;
    int c = table_pick(u_table_conditional, row, TABLE_PHI, u.y, fphi);
    // Uniform over the cell's solid angle: 1 - cos(theta_h) uniform between its edges (as
    // 1 - cos, not cos: float32 would lose the cells next to N).
    float w = mix(table_versine(float(r) / float(TABLE_U)),
                  table_versine(float(r + 1) / float(TABLE_U)), fu);
    float cos_h = 1.0 - w;
    float sin_h = sqrt(max(w * (2.0 - w), 0.0));
    float phi = 2.0 * PI * (float(c) + fphi) / float(TABLE_PHI);
    vec2 a = table_azimuth(v);
    vec2 along = cos(phi) * a + sin(phi) * vec2(-a.y, a.x);
    vec3 h = vec3(sin_h * along, cos_h);
    float VoH = dot(v, h);
    if (VoH <= 0.0) return vec3(0.0);  // a failed sample: no direction, no contribution
    return to_world(2.0 * VoH * h - v, X, Y, N);
}

float PDF_BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {
    float p = TABLE_COSINE * pdf_cosine(L, N);
    vec3 v = vec3(dot(V, X), dot(V, Y), dot(V, N));
    vec3 l = vec3(dot(L, X), dot(L, Y), dot(L, N));
    vec3 sum = l + v;
    if (dot(sum, sum) < 1e-12) return p;
    vec3 h = normalize(sum);
    float VoH = dot(v, h);
    if (h.z <= 0.0 || VoH <= 0.0) return p;
    float versine = dot(h.xy, h.xy) / (1.0 + h.z);  // 1 - cos(theta_h), exact near N
    float u = sqrt(sqrt(versine));
    int r = min(int(u * float(TABLE_U)), TABLE_U - 1);
    vec2 a = table_azimuth(v);
    float phi = atan(dot(h.xy, vec2(-a.y, a.x)), dot(h.xy, a));
    phi = phi < 0.0 ? phi + 2.0 * PI : phi;
    int c = min(int(phi / (2.0 * PI) * float(TABLE_PHI)), TABLE_PHI - 1);
    int row = table_view(v) * TABLE_U + r;
    float density = texelFetch(u_table_density, ivec2(c, row), 0).r;
    return p + (1.0 - TABLE_COSINE) * density / (4.0 * VoH);
}

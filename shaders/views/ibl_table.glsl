// View (lab/ibl/table.py): the mass of f_r cos in each cell of the data-driven sampler's
// table (terms/sampling_table.glsl), one texel per cell: column = phi cell (from -pi),
// row = view angle * TABLE_U + u cell. SUB x SUB half vectors uniform over the cell's solid
// angle, each at another view angle of the row's range, give the mean of
// luma(f_r) cos(theta_L) 4 V.H (the Jacobian from H to L), times the cell's solid angle:
// the integral of f_r cos over the directions L the cell maps to.
uniform int u_views;
uniform int u_rows;
uniform int u_columns;
out vec4 frag_color;

const int SUB = 4;

void main() {
    ivec2 texel = ivec2(gl_FragCoord.xy);
    int j = texel.y / u_rows;
    int r = texel.y - j * u_rows;
    vec3 N = vec3(0.0, 0.0, 1.0);
    vec3 X = vec3(1.0, 0.0, 0.0);
    vec3 Y = vec3(0.0, 1.0, 0.0);
    float w0 = pow(float(r) / float(u_rows), 4.0);  // 1 - cos(theta_h) at the cell's edges
    float w1 = pow(float(r + 1) / float(u_rows), 4.0);
    float dphi = 2.0 * PI / float(u_columns);
    float total = 0.0;
    for (int a = 0; a < SUB; ++a) {
        for (int t = 0; t < SUB; ++t) {
            float w = mix(w0, w1, (float(a) + 0.5) / float(SUB));
            float cos_h = 1.0 - w;
            float sin_h = sqrt(max(w * (2.0 - w), 0.0));
            float phi = (float(texel.x) + (float(t) + 0.5) / float(SUB)) * dphi - PI;
            // Each of the cell's half vectors at another of the SUB^2 view angles over the
            // view's range (sqrt(1 - cos theta_v), as table_view), in an order apart from
            // theirs: the mass is the range's mean, so a lobe that moves within the range
            // keeps cells wherever it goes (at the range's centre alone, a sharp lobe's
            // cells cut by the horizon there were left to the defensive share elsewhere)
            int k = ((a + t) % SUB) * SUB + t;
            float s = (float(j) + (float(k) + 0.5) / float(SUB * SUB)) / float(u_views);
            float cos_v = 1.0 - s * s;
            vec3 V = vec3(sqrt(max(1.0 - cos_v * cos_v, 0.0)), 0.0, cos_v);
            vec3 H = vec3(sin_h * cos(phi), sin_h * sin(phi), cos_h);
            float VoH = dot(V, H);
            vec3 L = 2.0 * VoH * H - V;
            if (VoH <= 0.0 || L.z <= 0.0) continue;
            float value = lab_luma(BRDF(L, V, N, X, Y)) * L.z * 4.0 * VoH;
            total += isnan(value) || isinf(value) ? 0.0 : max(value, 0.0);
        }
    }
    frag_color = vec4(total / float(SUB * SUB) * dphi * (w1 - w0), 0.0, 0.0, 1.0);
}

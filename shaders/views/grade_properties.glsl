// View: exercise 11's property tests, one row per pixel, run on whatever BRDF is linked in.
// A row of u_rows holds (theta_L, phi_L, theta_V, phi_V) in radians in the shading frame
// u_X, u_Y, u_N (turned away from the axes, so a test that assumes N = z shows); a row with
// theta_L < 0 asks for directional_albedo(V), any other for reciprocity_error(L, V).
uniform highp sampler2D u_rows;
uniform vec3 u_X;
uniform vec3 u_Y;
uniform vec3 u_N;
out vec4 frag_color;

vec3 lab_row_direction(float theta, float phi) {
    vec2 t = lab_cos_sin(theta);
    vec2 p = lab_cos_sin(phi);
    return t.y * p.x * u_X + t.y * p.y * u_Y + t.x * u_N;
}

void main() {
    vec4 row = texelFetch(u_rows, ivec2(gl_FragCoord.xy), 0);
    vec3 V = lab_row_direction(row.z, row.w);
    float value;
    if (row.x < 0.0) {
        value = directional_albedo(V, u_N, u_X, u_Y);
    } else {
        value = reciprocity_error(lab_row_direction(row.x, row.y), V, u_N, u_X, u_Y);
    }
    frag_color = vec4(value, 0.0, 0.0, 1.0);
}

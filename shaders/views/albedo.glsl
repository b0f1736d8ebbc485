// View: directional albedo a(theta_i) = integral of f_r cos(theta_o) over the hemisphere.
// Row k holds theta_i = u_theta0 + k * u_theta_step; column j integrates one wedge of
// azimuth around the mirror direction; the host sums the columns.
// Directions are parametrised around the mirror direction R by t = pi u^2 (u uniform), which
// packs samples into sharp specular lobes; the Jacobian is sin(t) dt/du = sin(t) 2 pi u.
uniform float u_theta0;
uniform float u_theta_step;
uniform float u_phi_i;
uniform int u_samples;
uniform int u_wedges;
out vec4 frag_color;

void main() {
    int wedge = int(gl_FragCoord.x);
    float theta_i = u_theta0 + floor(gl_FragCoord.y) * u_theta_step;
    vec3 N = vec3(0.0, 0.0, 1.0);
    vec3 X = vec3(1.0, 0.0, 0.0);
    vec3 Y = vec3(0.0, 1.0, 0.0);
    vec2 cs_i = lab_cos_sin(theta_i);
    vec2 cs_phi = lab_cos_sin(u_phi_i);
    vec3 L = vec3(cs_i.y * cs_phi.x, cs_i.y * cs_phi.y, cs_i.x);
    vec3 R = vec3(-L.x, -L.y, L.z);
    vec3 T1 = normalize(abs(R.z) < 0.999 ? cross(N, R) : X);
    vec3 T2 = cross(R, T1);
    float dphi = 2.0 * PI / float(u_wedges);
    float phi = (float(wedge) + 0.5) * dphi;
    vec2 cs_around = lab_cos_sin(phi);
    vec3 around = cs_around.x * T1 + cs_around.y * T2;
    float du = 1.0 / float(u_samples);
    vec3 total = vec3(0.0);
    for (int i = 0; i < 4096; ++i) {
        if (i >= u_samples) break;
        float u = (float(i) + 0.5) * du;
        float t = PI * u * u;
        vec2 cs_t = lab_cos_sin(t);
        vec3 Vo = cs_t.x * R + cs_t.y * around;
        float cos_o = Vo.z;
        if (cos_o > 0.0) {
            total += BRDF(L, Vo, N, X, Y) * (cos_o * cs_t.y * 2.0 * PI * u);
        }
    }
    total *= du * dphi;
    total += DELTA_REFLECTANCE(L, N, X, Y) / float(u_wedges);
    frag_color = vec4(total, 1.0);
}

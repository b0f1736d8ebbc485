// View: one layer (theta_h bin u_layer) of a model tabulated in the MERL layout, as
// lab/measured/tabulate.py tabulates it: pixel (phi_d bin, theta_d bin) holds f_r at the
// bin centre's directions (lab/measured/merl.py bin_grid) times the noise factor
// max(1 + u_noise * z, 0). z is tabulate.py's noise_normal, a hash of the bin, the channel
// and the seed: the web page's practice mode makes the grader's table on its own GPU with
// it (static/tables.js; tests/test_web_tables.py holds the two equal).
uniform ivec3 u_dims;  // bins of (theta_h, theta_d, phi_d)
uniform int u_layer;   // the theta_h bin drawn
uniform float u_noise; // sigma of the relative noise; 0: none
uniform int u_seed;    // tabulate's seed (>= 0)
out vec4 frag_color;

// tabulate.py hash32: xor-shift and multiply rounds on 32-bit unsigned integers (they wrap).
uint lab_hash32(uint x) {
    x ^= x >> 16u;
    x *= 0x7feb352du;
    x ^= x >> 15u;
    x *= 0x846ca68bu;
    x ^= x >> 16u;
    return x;
}

// tabulate.py noise_normal for counter k = 3 * bin + channel: four 16-bit pieces of two
// hashes, centred and scaled to standard deviation 1 (exact integers up to one product).
float lab_noise_normal(uint k, uint salt) {
    uint key = (k << 1u) ^ salt;
    uint a = lab_hash32(key);
    uint b = lab_hash32(key ^ 1u);
    uint pieces = (a & 0xffffu) + (a >> 16u) + (b & 0xffffu) + (b >> 16u);
    return float(int(pieces) - 131070) * 2.6428997e-05;
}

void main() {
    int p = int(gl_FragCoord.x);
    int d = int(gl_FragCoord.y);
    int h = u_layer;
    float theta_h = (float(h) + 0.5) / float(u_dims.x);
    theta_h = theta_h * theta_h * (0.5 * PI);
    float theta_d = (float(d) + 0.5) / float(u_dims.y) * (0.5 * PI);
    float phi_d = (float(p) + 0.5) / float(u_dims.z) * PI;
    vec3 diff = vec3(sin(theta_d) * cos(phi_d), sin(theta_d) * sin(phi_d), cos(theta_d));
    float c = cos(theta_h);
    float s = sin(theta_h);
    // merl.py directions: V is L mirrored about H; both turned by theta_h about y.
    vec3 L = vec3(c * diff.x + s * diff.z, diff.y, -s * diff.x + c * diff.z);
    vec3 V = vec3(-c * diff.x + s * diff.z, -diff.y, s * diff.x + c * diff.z);
    vec3 f = BRDF(L, V, vec3(0.0, 0.0, 1.0), vec3(1.0, 0.0, 0.0), vec3(0.0, 1.0, 0.0));
    if (u_noise > 0.0) {
        uint salt = lab_hash32(uint(u_seed) + 0x9e3779b9u);
        uint bin = uint((h * u_dims.y + d) * u_dims.z + p);
        // Three lines, not a loop: the page's loop guard leaves a view without loops alone.
        f.r *= max(1.0 + u_noise * lab_noise_normal(3u * bin, salt), 0.0);
        f.g *= max(1.0 + u_noise * lab_noise_normal(3u * bin + 1u, salt), 0.0);
        f.b *= max(1.0 + u_noise * lab_noise_normal(3u * bin + 2u, salt), 0.0);
    }
    frag_color = vec4(f, 1.0);
}

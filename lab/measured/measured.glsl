// @model measured
// @title Measured BRDF: a table in the MERL layout, looked up through a 3D texture
// @formula f_r = table(theta_h, theta_d, phi_d), the half/difference angles of Rusinkiewicz
// @formula bins: sqrt(theta_h / 90 deg) * n_h, theta_d / 90 deg * n_d, phi_d / 180 deg * n_p
// @formula nearest: the bin's value; linear: trilinear between bin centres (phi_d wraps)
// @source W. Matusik, H. Pfister, M. Brand, L. McMillan, "A Data-Driven Reflectance Model",
// @source ACM TOG 22(3) (SIGGRAPH 2003); S. Rusinkiewicz, "A New Change of Variables for
// @source Efficient BRDF Representation", EGWR 1998.
// @param interpolation enum linear nearest | interpolation between the table's bins
// @param gain float 0.01 100 1 log | multiplies the table (exposure of the data)

// The host binds the table: texel (phi_d, theta_d, theta_h) holds f_r (RGB, 1/sr), with
// unmeasured (negative) values already replaced by 0.
uniform highp sampler3D u_measured;

vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {
    float NoL = dot(N, L);
    float NoV = dot(N, V);
    if (NoL <= 0.0 || NoV <= 0.0) return vec3(0.0);
    vec3 l = vec3(dot(L, X), dot(L, Y), NoL);
    vec3 v = vec3(dot(V, X), dot(V, Y), NoV);
    vec3 h = normalize(l + v);
    // atan of (sin, cos), not acos: near the peak cos(theta_h) is within float rounding of
    // 1, and acos would misplace theta_h by a whole bin of the sqrt spacing.
    float sin_h = length(h.xy);
    float theta_h = atan(sin_h, h.z);
    // d: l in a frame whose pole is h, i.e. l turned by -phi_h about N, then by -theta_h
    // about the bitangent. The sines and cosines come from h itself (no trigonometry).
    vec2 azimuth = sin_h > 1e-7 ? h.xy / sin_h : vec2(1.0, 0.0);  // (cos, sin) of phi_h
    vec3 r = vec3(azimuth.x * l.x + azimuth.y * l.y, -azimuth.y * l.x + azimuth.x * l.y, l.z);
    vec3 d = vec3(h.z * r.x - sin_h * r.z, r.y, sin_h * r.x + h.z * r.z);
    float theta_d = atan(length(d.xy), d.z);
    float phi_d = length(d.xy) > 1e-7 ? atan(d.y, d.x) : 0.0;
    if (phi_d < 0.0) phi_d += PI;  // phi_d and phi_d + pi: L and V swapped
    ivec3 size = textureSize(u_measured, 0);  // (n_p, n_d, n_h)
    // Position in bin units: bin i spans [i, i + 1).
    vec3 c = vec3(phi_d / PI * float(size.x), theta_d / (0.5 * PI) * float(size.y),
                  sqrt(theta_h / (0.5 * PI)) * float(size.z));
    if (interpolation == INTERPOLATION_NEAREST) {
        ivec3 bin = clamp(ivec3(floor(c)), ivec3(0), size - 1);
        return gain * texelFetch(u_measured, bin, 0).rgb;
    }
    // Trilinear between bin centres (i + 0.5) from 8 texel fetches: exact float weights
    // (a texture unit's filter rounds them to 1/256) and no float-linear extension, so
    // WebGL2 runs the same code. theta_h and theta_d clamp at their edges; phi_d wraps.
    vec3 t = c - 0.5;
    t.yz = clamp(t.yz, vec2(0.0), vec2(size.yz - 1));
    vec3 base = floor(t);
    vec3 w = t - base;
    ivec3 i0 = ivec3(base);
    i0.x = i0.x < 0 ? i0.x + size.x : i0.x;  // phi_d just below the first centre
    ivec3 i1 = ivec3((i0.x + 1) % size.x, min(i0.yz + 1, size.yz - 1));
    #define LAB_TABLE(x, y, z) texelFetch(u_measured, ivec3(x, y, z), 0).rgb
    vec3 low = mix(mix(LAB_TABLE(i0.x, i0.y, i0.z), LAB_TABLE(i1.x, i0.y, i0.z), w.x),
                   mix(LAB_TABLE(i0.x, i1.y, i0.z), LAB_TABLE(i1.x, i1.y, i0.z), w.x), w.y);
    vec3 high = mix(mix(LAB_TABLE(i0.x, i0.y, i1.z), LAB_TABLE(i1.x, i0.y, i1.z), w.x),
                    mix(LAB_TABLE(i0.x, i1.y, i1.z), LAB_TABLE(i1.x, i1.y, i1.z), w.x), w.y);
    #undef LAB_TABLE
    return gain * mix(low, high, w.z);
}

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

// The host binds the table: texel (phi_d, theta_d, theta_h) holds f_r (RGB, 1/sr); negative
// texels were not measured and count as 0.
uniform highp sampler3D u_measured;

// Rotation of v about the z axis (t > 0 turns x toward y) and about the y axis (z toward x).
vec3 rotate_z(vec3 v, float t) {
    float c = cos(t);
    float s = sin(t);
    return vec3(c * v.x - s * v.y, s * v.x + c * v.y, v.z);
}

vec3 rotate_y(vec3 v, float t) {
    float c = cos(t);
    float s = sin(t);
    return vec3(c * v.x + s * v.z, v.y, -s * v.x + c * v.z);
}

vec3 table_texel(ivec3 bin) {
    return max(texelFetch(u_measured, bin, 0).rgb, vec3(0.0));
}

vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {
    float NoL = dot(N, L);
    float NoV = dot(N, V);
    if (NoL <= 0.0 || NoV <= 0.0) return vec3(0.0);
    vec3 l = vec3(dot(L, X), dot(L, Y), NoL);
    vec3 v = vec3(dot(V, X), dot(V, Y), NoV);
    vec3 h = normalize(l + v);
    float theta_h = acos(clamp(h.z, -1.0, 1.0));
    float phi_h = length(h.xy) > 1e-7 ? atan(h.y, h.x) : 0.0;
    vec3 d = rotate_y(rotate_z(l, -phi_h), -theta_h);
    float theta_d = acos(clamp(d.z, -1.0, 1.0));
    float phi_d = length(d.xy) > 1e-7 ? atan(d.y, d.x) : 0.0;
    if (phi_d < 0.0) phi_d += PI;  // phi_d and phi_d + pi: L and V swapped
    ivec3 size = textureSize(u_measured, 0);  // (n_p, n_d, n_h)
    // Position in bin units: bin i spans [i, i + 1).
    vec3 c = vec3(phi_d / PI * float(size.x), theta_d / (0.5 * PI) * float(size.y),
                  sqrt(theta_h / (0.5 * PI)) * float(size.z));
    if (interpolation == INTERPOLATION_NEAREST) {
        ivec3 bin = clamp(ivec3(floor(c)), ivec3(0), size - 1);
        return gain * table_texel(bin);
    }
    // Trilinear between bin centres: clamped in theta, periodic in phi_d.
    vec3 p = c - 0.5;
    p.yz = clamp(p.yz, vec2(0.0), vec2(size.yz - 1));
    vec3 base = floor(p);
    vec3 t = p - base;
    ivec3 i0 = ivec3(base);
    ivec3 i1 = min(i0 + 1, size - 1);
    i0.x = (i0.x + size.x) % size.x;
    i1.x = (ivec3(base).x + 1 + size.x) % size.x;
    vec3 c00 = mix(table_texel(ivec3(i0.x, i0.y, i0.z)), table_texel(ivec3(i1.x, i0.y, i0.z)), t.x);
    vec3 c10 = mix(table_texel(ivec3(i0.x, i1.y, i0.z)), table_texel(ivec3(i1.x, i1.y, i0.z)), t.x);
    vec3 c01 = mix(table_texel(ivec3(i0.x, i0.y, i1.z)), table_texel(ivec3(i1.x, i0.y, i1.z)), t.x);
    vec3 c11 = mix(table_texel(ivec3(i0.x, i1.y, i1.z)), table_texel(ivec3(i1.x, i1.y, i1.z)), t.x);
    return gain * mix(mix(c00, c10, t.y), mix(c01, c11, t.y), t.z);
}

// @model measured
// @title Exercise 12: a tabulated BRDF, looked up in the MERL layout
// @formula angles: theta_h, theta_d, phi_d, the half/difference angles of Rusinkiewicz
// @formula bins: sqrt(theta_h / 90 deg) * 90, theta_d / 90 deg * 90, phi_d / 180 deg * 180
// @formula phi_d < 0 folds to phi_d + 180 deg (L and V swapped: the same entry)
// @formula linear: trilinear between bin centres (phi_d wraps, theta_h and theta_d clamp)
// @source W. Matusik, H. Pfister, M. Brand, L. McMillan, "A Data-Driven Reflectance Model",
// @source SIGGRAPH 2003; S. Rusinkiewicz, "A New Change of Variables for Efficient BRDF
// @source Representation", EGWR 1998.
// @param interpolation enum linear nearest | nearest: the bin's value; linear: trilinear

// The grader binds the table here: texel (phi_d, theta_d, theta_h) holds f_r (RGB, 1/sr).
uniform highp sampler3D u_table;

const int N_THETA_H = 90;  // bins of theta_h (square-root spacing, dense near the peak)
const int N_THETA_D = 90;  // bins of theta_d over 90 degrees
const int N_PHI_D = 180;   // bins of phi_d over 180 degrees

// The table's value in bin (theta_h, theta_d, phi_d): the texture's axes run the other way.
vec3 table_texel(ivec3 bin) {
    return texelFetch(u_table, ivec3(bin.z, bin.y, bin.x), 0).rgb;
}

// (theta_h, theta_d, phi_d) in radians, phi_d in (-pi, pi], for directions in the frame
// X, Y, N: theta_h is the angle of H from N; d is L seen from a frame whose pole is H.
vec3 half_diff_angles(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {
    // TODO: L and V in the local frame (x along X, y along Y, z along N), and H.
    // TODO: theta_h with atan(length(h.xy), h.z) (acos loses whole bins near the peak).
    // TODO: d = L turned by -phi_h about N, then by -theta_h about the bitangent.
    // TODO: theta_d and phi_d of d (phi_d = 0 where d is the pole).
    return vec3(0.0);
}

// Position in bin units along (theta_h, theta_d, phi_d): bin i spans [i, i + 1).
vec3 merl_position(vec3 angles) {
    // TODO: fold phi_d < 0 to phi_d + pi (L and V swapped: the same entry).
    // TODO: theta_h by sqrt(theta_h / (pi/2)) * N_THETA_H, theta_d and phi_d linearly.
    return vec3(0.0);
}

// The MERL index (theta_h, theta_d, phi_d) of the bin holding the angles, within the table.
ivec3 merl_index(vec3 angles) {
    // TODO: floor of the position, clamped to the table's bins.
    return ivec3(0);
}

// f_r blended between the 8 bin centres around the angles: each sample stands for the
// centre of its bin (i + 0.5); theta_h and theta_d clamp at the table's ends, phi_d wraps.
vec3 table_lookup(vec3 angles) {
    // TODO: the position less half a bin; clamp theta_h and theta_d to [0, N - 1].
    // TODO: the lower corner (floor), the weights (the rest), the upper corner (+1):
    //       clamped in theta_h and theta_d, wrapped around in phi_d (both ends).
    // TODO: blend the 8 table_texel values with mix, one axis after the other.
    return vec3(0.0);
}

vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {
    if (dot(N, L) <= 0.0 || dot(N, V) <= 0.0) return vec3(0.0);
    vec3 angles = half_diff_angles(L, V, N, X, Y);
    if (interpolation == INTERPOLATION_NEAREST) return table_texel(merl_index(angles));
    return table_lookup(angles);
}

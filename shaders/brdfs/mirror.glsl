// @model mirror
// @title Ideal mirror: specular reflection as a delta function
// @property reciprocal isotropic energy-conserving
// @formula f_r = rho_s * delta(omega_o - R(omega_i)) / cos(theta_i),  R = 2(N.L)N - L
// @source Law of reflection; see e.g. Pharr, Jakob, Humphreys, PBR 4th ed., 9.2.
// @delta
// @param rho_s color 0.9 0.9 0.9 | fraction of light the mirror reflects

// A delta has no finite value: off the spike the BRDF is 0, and views draw the spike
// (plots) or the reflected environment (sphere) from DELTA_REFLECTANCE.
vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {
    return vec3(0.0);
}

vec3 DELTA_REFLECTANCE(vec3 L, vec3 N, vec3 X, vec3 Y) {
    if (dot(N, L) <= 0.0) return vec3(0.0);
    return rho_s;
}

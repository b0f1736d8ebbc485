// Exercise 15: a BRDF lobe in spherical harmonics. The real harmonics Y_lm up to any band,
// and the coefficients of the cosine-weighted lobe of whatever BRDF(L, V, N, X, Y) the
// grader links in, which this file calls but does not define. Directions are in the shading
// frame's own coordinates: N = (0, 0, 1), X = (1, 0, 0), Y = (0, 1, 0).
// Read README.md first: it gives the formulas, the conventions and the quadrature.
// @include terms/brdf_stand_in.glsl

const int N_THETA = 32;   // the midpoint rule's steps in theta over [0, pi/2]
const int N_PHI = 64;     // and in phi over [0, 2 pi)

// The associated Legendre function P_l^m(x) for 0 <= m <= l, with the Condon-Shortley
// phase (-1)^m (the handout's recurrence).
float legendre(int l, int m, float x) {
    // TODO: P_m^m = (-1)^m (2m - 1)!! (1 - x^2)^(m/2), a loop over k = 1..m.
    // TODO: return it when l == m; else P_{m+1}^m = (2m + 1) x P_m^m.
    // TODO: climb in l to P_l^m: (k - m) P_k^m = (2k - 1) x P_{k-1}^m - (k + m - 1) P_{k-2}^m.
    return 0.0;
}

// The real orthonormal harmonic Y_lm at the unit direction w (theta from the z axis, phi
// from x towards y).
float sh_basis(int l, int m, vec3 w) {
    // TODO: the normalisation K_l^|m| = sqrt((2l + 1) / (4 pi) (l - |m|)! / (l + |m|)!).
    // TODO: cos(theta) is w.z; phi = atan(w.y, w.x).
    // TODO: m = 0: K P_l^0; m > 0: sqrt(2) K P_l^m cos(m phi);
    //       m < 0: sqrt(2) K P_l^|m| sin(|m| phi).
    return 0.0;
}

// The coefficient c_lm of the lobe g(w) = f_r(L, w) cos(theta_w), extended below the horizon
// as an odd function of z: the integral of g Y_lm over the whole sphere.
vec3 sh_coefficient(int l, int m, vec3 L) {
    // TODO: 0 for the harmonics that are even in z (l + |m| even).
    // TODO: a midpoint rule over the upper hemisphere: cells of dtheta x dphi, each centre
    //       a direction w; sum BRDF(L, w, N, X, Y) cos(theta) Y_lm(w) times the cell's
    //       solid angle sin(theta) dtheta dphi.
    // TODO: twice that sum (the lower hemisphere gives as much as the upper one).
    return vec3(0.0);
}

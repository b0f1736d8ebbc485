// Exercise 15: a BRDF lobe in spherical harmonics. The real harmonics Y_lm up to any band,
// and the coefficients of the cosine-weighted lobe of whatever BRDF(L, V, N, X, Y) the
// grader links in, which this file calls but does not define. Directions are in the shading
// frame's own coordinates: N = (0, 0, 1), X = (1, 0, 0), Y = (0, 1, 0).
// @include terms/brdf_stand_in.glsl

const int N_THETA = 32;   // the midpoint rule's steps in theta over [0, pi/2]
const int N_PHI = 64;     // and in phi over [0, 2 pi)

// The associated Legendre function P_l^m(x), 0 <= m <= l, with the Condon-Shortley phase
// (-1)^m: P_m^m = (-1)^m (2m - 1)!! (1 - x^2)^(m/2), P_{m+1}^m = (2m + 1) x P_m^m, then
// (l - m) P_l^m = (2l - 1) x P_{l-1}^m - (l + m - 1) P_{l-2}^m.
float legendre(int l, int m, float x) {
    float s = sqrt(max(1.0 - x * x, 0.0));
    float p_mm = 1.0;
    for (int k = 1; k <= m; ++k) {
        p_mm *= -(2.0 * float(k) - 1.0) * s;
    }
    if (l == m) return p_mm;
    float p_next = (2.0 * float(m) + 1.0) * x * p_mm;
    for (int k = m + 2; k <= l; ++k) {
        float p_k = ((2.0 * float(k) - 1.0) * x * p_next - float(k + m - 1) * p_mm) / float(k - m);
        p_mm = p_next;
        p_next = p_k;
    }
    return p_next;
}

// The normalisation K_l^m = sqrt((2l + 1) / (4 pi) (l - m)! / (l + m)!), m >= 0.
float sh_norm(int l, int m) {
    float ratio = 1.0;
    for (int k = l - m + 1; k <= l + m; ++k) {
        ratio /= float(k);
    }
    return sqrt((2.0 * float(l) + 1.0) * 0.25 * INV_PI * ratio);
}

// The real orthonormal harmonic Y_lm at the unit direction w (theta from the z axis, phi
// from x towards y): K P_l^0 for m = 0, sqrt(2) K P_l^m cos(m phi) for m > 0 and
// sqrt(2) K P_l^|m| sin(|m| phi) for m < 0.
float sh_basis(int l, int m, vec3 w) {
    int k = abs(m);
    float y = sh_norm(l, k) * legendre(l, k, w.z);
    if (m == 0) return y;
    float phi = atan(w.y, w.x);
    return sqrt(2.0) * y * (m > 0 ? cos(float(k) * phi) : sin(float(k) * phi));
}

// The coefficient c_lm of the lobe g(w) = f_r(L, w) cos(theta_w), extended below the horizon
// as an odd function of z, g(x, y, -z) = -g(x, y, z): the integral of g Y_lm over the
// sphere. Y_lm is odd in z when l + |m| is odd, even otherwise, so c_lm is twice the
// integral over the upper hemisphere for odd ones and 0 for even ones.
vec3 sh_coefficient(int l, int m, vec3 L) {
    if ((l + abs(m)) % 2 == 1) return vec3(0.0);
    vec3 N = vec3(0.0, 0.0, 1.0);
    vec3 X = vec3(1.0, 0.0, 0.0);
    vec3 Y = vec3(0.0, 1.0, 0.0);
    float dtheta = 0.5 * PI / float(N_THETA);
    float dphi = 2.0 * PI / float(N_PHI);
    vec3 total = vec3(0.0);
    for (int i = 0; i < N_THETA; ++i) {
        float theta = (float(i) + 0.5) * dtheta;
        float c = cos(theta);
        float s = sin(theta);
        for (int j = 0; j < N_PHI; ++j) {
            float phi = (float(j) + 0.5) * dphi;
            vec3 w = vec3(s * cos(phi), s * sin(phi), c);
            // g Y_lm times the cell's solid angle sin(theta) dtheta dphi
            total += BRDF(L, w, N, X, Y) * (c * sh_basis(l, m, w) * s);
        }
    }
    return 2.0 * total * (dtheta * dphi);
}

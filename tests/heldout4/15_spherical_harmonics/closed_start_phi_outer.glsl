// Exercise 15: a BRDF lobe in spherical harmonics. The real harmonics Y_lm up to any band,
// and the coefficients of the cosine-weighted lobe of whatever BRDF(L, V, N, X, Y) the
// grader links in, which this file calls but does not define. Directions are in the shading
// frame's own coordinates: N = (0, 0, 1), X = (1, 0, 0), Y = (0, 1, 0).
// @include terms/brdf_stand_in.glsl

const int N_THETA = 32;   // the midpoint rule's steps in theta over [0, pi/2]
const int N_PHI = 64;     // and in phi over [0, 2 pi)

// P_m^m = (-1)^m (2m-1)!! (1-x^2)^(m/2), then the upward recurrence in l.
float legendre(int l, int m, float x) {
    float s = sqrt(max(1.0 - x * x, 0.0));
    float double_factorial = 1.0;
    float s_power = 1.0;
    for (int k = 1; k <= m; ++k) {
        double_factorial *= float(2 * k - 1);
        s_power *= s;
    }
    float sign = (m % 2 == 0) ? 1.0 : -1.0;
    float prev = sign * double_factorial * s_power;  // P_m^m
    if (l == m) return prev;
    float cur = float(2 * m + 1) * x * prev;          // P_{m+1}^m
    for (int k = m + 2; k <= l; ++k) {
        float next = (float(2 * k - 1) * x * cur - float(k + m - 1) * prev) / float(k - m);
        prev = cur;
        cur = next;
    }
    return cur;
}

float factorial(int n) {
    float f = 1.0;
    for (int k = 2; k <= n; ++k) f *= float(k);
    return f;
}

float sh_norm(int l, int m) {
    return sqrt(float(2 * l + 1) / (4.0 * PI) * factorial(l - m) / factorial(l + m));
}

float sh_basis(int l, int m, vec3 w) {
    int am = m < 0 ? -m : m;
    float base = sh_norm(l, am) * legendre(l, am, w.z);
    float phi = atan(w.y, w.x);
    if (m > 0) return 1.4142135623730951 * base * cos(float(am) * phi);
    if (m < 0) return 1.4142135623730951 * base * sin(float(am) * phi);
    return base;
}

vec3 sh_coefficient(int l, int m, vec3 L) {
    int parity = (l + (m < 0 ? -m : m)) - 2 * ((l + (m < 0 ? -m : m)) / 2);
    if (parity == 0) return vec3(0.0);  // even harmonic: the odd lobe has none of it
    float dtheta = 0.5 * PI / float(N_THETA);
    float dphi = 2.0 * PI / float(N_PHI);
    vec3 sum = vec3(0.0);
    for (int j = 0; j < N_PHI; ++j) {
        float phi = (float(j) + 0.5) * dphi;
        for (int i = 0; i < N_THETA; ++i) {
            float theta = (float(i) + 0.5) * dtheta;
            vec3 w = vec3(sin(theta) * cos(phi), sin(theta) * sin(phi), cos(theta));
            float weight = w.z * sin(theta) * dtheta * dphi;
            sum += weight * sh_basis(l, m, w) * BRDF(L, w, vec3(0.0, 0.0, 1.0), vec3(1.0, 0.0, 0.0), vec3(0.0, 1.0, 0.0));
        }
    }
    return 2.0 * sum;
}

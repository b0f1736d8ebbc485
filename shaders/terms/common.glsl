// Constants and small helpers shared by every model (always included first).
const float PI = 3.14159265358979;
const float INV_PI = 0.318309886183791;
const float EPS = 1e-7;

float sqr(float x) { return x * x; }

// tan^2 of the angle whose cosine is c (c in (0, 1]). The floor on c^2 only keeps it finite
// (1e-30, not EPS: a floor of 1e-7 would freeze tan^2 at 1e7 from 89.98 degrees on).
float tan2_from_cos(float c) {
    float c2 = max(c * c, 1e-30);
    return max(1.0 - c2, 0.0) / c2;
}

// atan(y, x) to float precision. Some drivers' inverse trigonometry is coarse (llvmpipe:
// errors of 3e-6 rad), which exponentials of the angle amplify; one Newton step on
// y cos(a) - x sin(a) = 0 with the accurate sin and cos fixes it.
float precise_atan(float y, float x) {
    float a = atan(y, x);
    float r = length(vec2(x, y));
    return r > 0.0 ? a + (y * cos(a) - x * sin(a)) / r : a;
}

// The angle whose cosine is c.
float angle_from_cos(float c) {
    c = clamp(c, -1.0, 1.0);
    return precise_atan(sqrt(max(1.0 - c * c, 0.0)), c);
}

// (cos t, sin t) by Taylor series, to float precision on every GPU: some built-in sin and
// cos are coarse (SwiftShader: 1e-4), which sharp lobes amplify into visible differences
// between two renderers of the same view (the views use it to make their directions).
vec2 lab_cos_sin(float angle) {
    float wrapped = mod(angle + PI, 2.0 * PI) - PI;  // [-pi, pi)
    float t = abs(wrapped);
    bool far_half = t > 0.5 * PI;
    float x = far_half ? PI - t : t;
    float x2 = x * x;
    float s = x * (1.0 - x2 / 6.0 * (1.0 - x2 / 20.0 * (1.0 - x2 / 42.0 * (1.0 - x2 / 72.0
        * (1.0 - x2 / 110.0 * (1.0 - x2 / 156.0))))));
    float c = 1.0 - x2 / 2.0 * (1.0 - x2 / 12.0 * (1.0 - x2 / 30.0 * (1.0 - x2 / 56.0
        * (1.0 - x2 / 90.0 * (1.0 - x2 / 132.0 * (1.0 - x2 / 182.0))))));
    return vec2(far_half ? -c : c, wrapped < 0.0 ? -s : s);
}

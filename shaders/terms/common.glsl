// Constants and small helpers shared by every model (always included first).
const float PI = 3.14159265358979;
const float INV_PI = 0.318309886183791;
const float EPS = 1e-7;

float sqr(float x) { return x * x; }

// tan^2 of the angle whose cosine is c (c in (0, 1]).
float tan2_from_cos(float c) {
    float c2 = max(c * c, EPS);
    return max(1.0 - c2, 0.0) / c2;
}

// The angle whose cosine is c. atan is used because acos is imprecise on some drivers
// (llvmpipe: 1.5e-4 rad), which matters for exponentials of the angle.
float angle_from_cos(float c) {
    c = clamp(c, -1.0, 1.0);
    return atan(sqrt(max(1.0 - c * c, 0.0)), c);
}

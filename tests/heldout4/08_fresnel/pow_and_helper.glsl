// Exercise 08: the Fresnel reflectance F (Schlick and exact dielectric).

float square(float x) { return x * x; }

vec3 F_schlick(vec3 f0, float VoH) {
    return f0 + (1.0 - f0) * pow(1.0 - clamp(VoH, 0.0, 1.0), 5.0);
}

float F_dielectric(float VoH, float ior) {
    float c = clamp(VoH, 0.0, 1.0);
    float g2 = square(ior) + square(c) - 1.0;
    if (g2 < 0.0) {
        return 1.0;
    }
    float g = sqrt(g2);
    float first = square((g - c) / (g + c));
    float second = 1.0 + square((c * (g + c) - 1.0) / (c * (g - c) + 1.0));
    return first * second / 2.0;
}

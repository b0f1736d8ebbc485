// Fresnel reflectance F.

// Schlick (1994): F = f0 + (1 - f0)(1 - cos)^5, cos = V.H.
vec3 F_schlick(vec3 f0, float VoH) {
    float k = 1.0 - clamp(VoH, 0.0, 1.0);
    float k2 = k * k;
    return f0 + (vec3(1.0) - f0) * (k2 * k2 * k);
}

// Exact Fresnel reflectance of unpolarised light at a dielectric interface with relative
// index of refraction ior (Cook & Torrance 1982, eq. in terms of c = cos and g).
float F_dielectric(float VoH, float ior) {
    float c = clamp(VoH, 0.0, 1.0);
    float g2 = ior * ior - 1.0 + c * c;
    if (g2 < 0.0) return 1.0;  // total internal reflection
    float g = sqrt(g2);
    float a = (g - c) / (g + c);
    float b = (c * (g + c) - 1.0) / (c * (g - c) + 1.0);
    return 0.5 * a * a * (1.0 + b * b);
}

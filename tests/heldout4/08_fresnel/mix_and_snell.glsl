// Exercise 08: the Fresnel reflectance F.

vec3 F_schlick(vec3 f0, float VoH) {
    float c = clamp(VoH, 0.0, 1.0);
    float w = pow(1.0 - c, 5.0);
    return mix(f0, vec3(1.0), w);
}

// Exact Fresnel for unpolarised light from the s and p amplitudes and Snell's law:
// sin_t = sin_i / n, rs = (c - n ct) / (c + n ct), rp = (ct - n c) / (ct + n c).
float F_dielectric(float VoH, float ior) {
    float c = clamp(VoH, 0.0, 1.0);
    float sin2_t = (1.0 - c * c) / (ior * ior);
    if (sin2_t > 1.0) return 1.0;
    float ct = sqrt(1.0 - sin2_t);
    float rs = (c - ior * ct) / (c + ior * ct);
    float rp = (ct - ior * c) / (ct + ior * c);
    return 0.5 * (rs * rs + rp * rp);
}

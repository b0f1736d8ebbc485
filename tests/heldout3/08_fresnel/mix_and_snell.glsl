// Exercise 08: the Fresnel reflectance F.
// This file stands in for shaders/terms/fresnel.glsl: the library's Cook-Torrance
// model (shaders/brdfs/cook_torrance.glsl) calls F_schlick and F_dielectric with
// VoH = V.H, the cosine of the angle of incidence on the microfacet.

// Schlick's approximation: F = f0 + (1 - f0)(1 - cos)^5, per colour channel.
vec3 F_schlick(vec3 f0, float VoH) {
    return mix(f0, vec3(1.0), pow(1.0 - clamp(VoH, 0.0, 1.0), 5.0));
}

// Exact reflectance of unpolarised light at a dielectric with relative index ior:
// c = cos, g = sqrt(ior^2 - 1 + c^2),
// F = 1/2 ((g - c) / (g + c))^2 (1 + ((c (g + c) - 1) / (c (g - c) + 1))^2);  F = 1 if g^2 < 0.
float F_dielectric(float VoH, float ior) {
    float c = clamp(VoH, 0.0, 1.0);
    float sin2_t = (1.0 - c * c) / (ior * ior);  // Snell
    if (sin2_t > 1.0) return 1.0;                 // total internal reflection
    float cos_t = sqrt(1.0 - sin2_t);
    float rs = (c - ior * cos_t) / (c + ior * cos_t);
    float rp = (cos_t - ior * c) / (cos_t + ior * c);
    return 0.5 * (rs * rs + rp * rp);
}

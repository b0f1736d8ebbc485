// Exercise 08: the Fresnel reflectance F.
// This file stands in for shaders/terms/fresnel.glsl: the library's Cook-Torrance
// model (shaders/brdfs/cook_torrance.glsl) calls F_schlick and F_dielectric with
// VoH = V.H, the cosine of the angle of incidence on the microfacet.

// Schlick's approximation: F = f0 + (1 - f0)(1 - cos)^5, per colour channel.
vec3 F_schlick(vec3 f0, float VoH) {
    float cosine = clamp(VoH, 0.0, 1.0);
    // a blend from f0 (normal incidence) towards white (grazing)
    float w = pow(1.0 - cosine, 5.0);
    return mix(f0, vec3(1.0), w);
}

// Exact reflectance of unpolarised light at a dielectric with relative index ior:
// c = cos, g = sqrt(ior^2 - 1 + c^2),
// F = 1/2 ((g - c) / (g + c))^2 (1 + ((c (g + c) - 1) / (c (g - c) + 1))^2);  F = 1 if g^2 < 0.
float F_dielectric(float VoH, float ior) {
    // Fresnel equations for s and p polarisation, averaged (unpolarised light)
    float cos_i = clamp(VoH, 0.0, 1.0);
    float sin2_t = (1.0 - cos_i * cos_i) / (ior * ior);   // Snell
    if (sin2_t >= 1.0) return 1.0;   // total internal reflection
    float cos_t = sqrt(1.0 - sin2_t);
    float rs = (cos_i - ior * cos_t) / (cos_i + ior * cos_t);
    float rp = (cos_t - ior * cos_i) / (cos_t + ior * cos_i);
    return 0.5 * (rs * rs + rp * rp);
}

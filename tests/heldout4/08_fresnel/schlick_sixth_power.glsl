// Exercise 08: the Fresnel reflectance F.
// This file stands in for shaders/terms/fresnel.glsl: the library's Cook-Torrance
// model (shaders/brdfs/cook_torrance.glsl) calls F_schlick and F_dielectric with
// VoH = V.H, the cosine of the angle of incidence on the microfacet.

// Schlick's approximation: F = f0 + (1 - f0)(1 - cos)^5, per colour channel.
vec3 F_schlick(vec3 f0, float VoH) {
    float k = 1.0 - clamp(VoH, 0.0, 1.0);
    float k2 = k * k;
    return f0 + (vec3(1.0) - f0) * (k2 * k2 * k2);
}

// Exact reflectance of unpolarised light at a dielectric with relative index ior:
// c = cos, g = sqrt(ior^2 - 1 + c^2),
// F = 1/2 ((g - c) / (g + c))^2 (1 + ((c (g + c) - 1) / (c (g - c) + 1))^2);  F = 1 if g^2 < 0.
float F_dielectric(float VoH, float ior) {
    float c = clamp(VoH, 0.0, 1.0);
    float g2 = ior * ior - 1.0 + c * c;
    if (g2 < 0.0) return 1.0;
    float g = sqrt(g2);
    float a = (g - c) / (g + c);
    float b = (c * (g + c) - 1.0) / (c * (g - c) + 1.0);
    return 0.5 * a * a * (1.0 + b * b);
}

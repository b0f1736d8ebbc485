// @model cook_torrance
// @title Exercise 09: the Cook-Torrance microfacet model
// @formula f_r = kd / pi + ks * F D G / (pi (N.L)(N.V))
// @source R. L. Cook and K. E. Torrance, "A Reflectance Model for Computer Graphics", ACM TOG 1(1), 1982.
// @include terms/distributions.glsl
// @include terms/geometry.glsl
// @include terms/fresnel.glsl
// @param kd color 0.1 0.1 0.1 | diffuse albedo
// @param ks color 1 1 1 | specular weight
// @param m float 0.01 1 0.3 log | RMS slope of the microfacets (roughness)
// @param f0 color 0.04 0.04 0.04 | Fresnel reflectance at normal incidence (Schlick)
// @param ior float 1 3 1.5 linear | index of refraction for the exact dielectric Fresnel term
// @param distribution enum beckmann blinn gaussian | microfacet distribution D
// @param fresnel enum schlick dielectric none | Fresnel term F

// Given: the distribution and Fresnel term that the parameters choose.
float microfacet_D(float NoH) {
    if (distribution == DISTRIBUTION_BLINN) return D_blinn(NoH, atan(m));
    if (distribution == DISTRIBUTION_GAUSSIAN) return D_gaussian(NoH, atan(m));
    return D_beckmann(NoH, m);
}

vec3 fresnel_F(float VoH) {
    if (fresnel == FRESNEL_DIELECTRIC) return vec3(F_dielectric(VoH, ior));
    if (fresnel == FRESNEL_NONE) return vec3(1.0);
    return F_schlick(f0, VoH);
}

vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {
    float NoL = dot(N, L);
    float NoV = dot(N, V);
    if (NoL <= 0.0 || NoV <= 0.0) return vec3(0.0);
    vec3 H = normalize(L + V);
    float NoH = dot(N, H);
    float VoH = dot(V, H);
    float D = microfacet_D(NoH);
    float G = G_vgroove(NoL, NoV, NoH, VoH);
    vec3 F = fresnel_F(VoH);
    return kd * INV_PI + ks * F * (D * G / (PI * NoL));
}

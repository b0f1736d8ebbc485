// @model cook_torrance
// @title Cook-Torrance microfacet model
// @property reciprocal isotropic energy-conserving
// @formula f_r = kd / pi + ks * F D G / (pi (N.L)(N.V))
// @formula D: Beckmann exp(-tan^2(a) / m^2) / (4 m^2 cos^4(a)), cos(a) = N.H; or Blinn / Gaussian
// @formula    with half-angle beta = atan(m) (see terms/distributions.glsl for their normalisation)
// @formula G = min(1, 2 (N.H)(N.V) / (V.H), 2 (N.H)(N.L) / (V.H))
// @formula F: Schlick f0 + (1 - f0)(1 - V.H)^5, exact dielectric with ior, or none (F = 1)
// @source R. L. Cook and K. E. Torrance, "A Reflectance Model for Computer Graphics", ACM TOG 1(1), 1982.
// @include terms/distributions.glsl
// @include terms/geometry.glsl
// @include terms/fresnel.glsl
// @param kd color 0.25 0.1 0.05 | diffuse albedo
// @param ks color 1 1 1 | specular weight
// @param m float 0.01 1 0.15 log | RMS slope of the microfacets (roughness)
// @param f0 color 0.04 0.04 0.04 | Fresnel reflectance at normal incidence (Schlick)
// @param ior float 1 3 1.5 linear | index of refraction for the exact dielectric Fresnel term
// @param distribution enum beckmann blinn gaussian | microfacet distribution D
// @param fresnel enum schlick dielectric none | Fresnel term F

float microfacet_D(float NoH) {
    if (distribution == DISTRIBUTION_BLINN) return D_blinn(NoH, precise_atan(m, 1.0));
    if (distribution == DISTRIBUTION_GAUSSIAN) return D_gaussian(NoH, precise_atan(m, 1.0));
    return D_beckmann(NoH, m);
}

vec3 fresnel_F(float VoH) {
    if (fresnel == FRESNEL_DIELECTRIC) return vec3(F_dielectric(VoH, ior));
    if (fresnel == FRESNEL_NONE) return vec3(1.0);
    return F_schlick(f0, VoH);
}

// The three terms on their own (also drawn by the microfacet terms view, views/terms.glsl).
void MICROFACET_TERMS(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y, out float D, out float G, out vec3 F) {
    float NoL = dot(N, L);
    float NoV = dot(N, V);
    vec3 H = normalize(L + V);
    float NoH = dot(N, H);
    // V.H = |L + V| / 2 for unit L, V: accurate where dot(V, H) is not, at grazing mirror
    // pairs (L + V nearly vertical, its tilt error times |V| = 1 would swamp V.H there).
    float VoH = 0.5 * length(L + V);
    D = microfacet_D(NoH);
    G = G_vgroove(NoL, NoV, NoH, VoH);
    F = fresnel_F(VoH);
}

vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {
    float NoL = dot(N, L);
    float NoV = dot(N, V);
    if (NoL <= 0.0 || NoV <= 0.0) return vec3(0.0);
    float D;
    float G;
    vec3 F;
    MICROFACET_TERMS(L, V, N, X, Y, D, G, F);
    return kd * INV_PI + ks * F * (D * G / (PI * NoL * NoV));
}

// @model ggx
// @title GGX / Trowbridge-Reitz microfacet model with height-correlated Smith shadowing
// @property reciprocal isotropic energy-conserving
// @formula f_r = kd / pi + ks * F D G2 / (4 (N.L)(N.V)) = kd / pi + ks * F D V2
// @formula V2 = G2 / (4 (N.L)(N.V)) = 0.5 / ((N.V) sqrt(a^2 + (1 - a^2)(N.L)^2) + (N.L) sqrt(a^2 + (1 - a^2)(N.V)^2))
// @formula D = alpha^2 / (pi ((N.H)^2 (alpha^2 - 1) + 1)^2);  G2 = 1 / (1 + Lambda(L) + Lambda(V))
// @formula Lambda = (-1 + sqrt(1 + alpha^2 tan^2(theta))) / 2;  F = f0 + (1 - f0)(1 - V.H)^5
// @source B. Walter et al., "Microfacet Models for Refraction through Rough Surfaces", EGSR 2007;
// @source E. Heitz, "Understanding the Masking-Shadowing Function in Microfacet-Based BRDFs", JCGT 2014.
// @include terms/distributions.glsl
// @include terms/geometry.glsl
// @include terms/fresnel.glsl
// @param kd color 0.05 0.1 0.25 | diffuse albedo
// @param ks color 1 1 1 | specular weight
// @param alpha float 0.01 1 0.15 log | roughness (GGX width, alpha = slope scale)
// @param f0 color 0.04 0.04 0.04 | Fresnel reflectance at normal incidence

// The three terms on their own, for the microfacet terms view (views/terms.glsl): the BRDF
// below uses V2 instead of G2, which stays finite at the horizon.
void MICROFACET_TERMS(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y, out float D, out float G, out vec3 F) {
    vec3 H = normalize(L + V);
    vec3 NxH = cross(N, H);
    D = D_ggx_sin2(dot(N, H), dot(NxH, NxH), alpha);
    G = G2_smith_ggx(dot(N, L), dot(N, V), alpha);
    F = F_schlick(f0, 0.5 * length(L + V));
}

vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {
    float NoL = dot(N, L);
    float NoV = dot(N, V);
    if (NoL <= 0.0 || NoV <= 0.0) return vec3(0.0);
    vec3 H = normalize(L + V);
    float NoH = dot(N, H);
    // V.H = |L + V| / 2 for unit L, V: accurate where dot(V, H) is not, at grazing mirror
    // pairs (L + V nearly vertical, its tilt error times |V| = 1 would swamp V.H there).
    float VoH = 0.5 * length(L + V);
    vec3 NxH = cross(N, H);
    float D = D_ggx_sin2(NoH, dot(NxH, NxH), alpha);
    // G2 / (4 N.L N.V) in one finite term: G2 and 1/(N.V) would each run away at the horizon.
    float V2 = V_smith_ggx_correlated(NoL, NoV, alpha);
    vec3 F = F_schlick(f0, VoH);
    return kd * INV_PI + ks * F * (D * V2);
}

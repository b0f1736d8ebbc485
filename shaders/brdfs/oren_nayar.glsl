// @model oren_nayar
// @title Oren-Nayar: rough diffuse surface (qualitative model)
// @property reciprocal isotropic energy-conserving
// @formula f_r = albedo / pi * (A + B max(0, cos(phi_i - phi_o)) sin(a) tan(b))
// @formula A = 1 - 0.5 s^2 / (s^2 + 0.33),  B = 0.45 s^2 / (s^2 + 0.09),  a = max(theta_i, theta_o), b = min(...)
// @source M. Oren and S. K. Nayar, "Generalization of Lambert's Reflectance Model", SIGGRAPH 1994, eq. 30.
// @param albedo color 0.8 0.8 0.8 | diffuse albedo
// @param sigma float 0 1.5 0.35 linear | standard deviation of the facet slope angle (radians)

vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {
    float NoL = dot(N, L);
    float NoV = dot(N, V);
    if (NoL <= 0.0 || NoV <= 0.0) return vec3(0.0);
    float s2 = sigma * sigma;
    float A = 1.0 - 0.5 * s2 / (s2 + 0.33);
    float B = 0.45 * s2 / (s2 + 0.09);
    float theta_i = precise_atan(length(cross(N, L)), NoL);
    float theta_o = precise_atan(length(cross(N, V)), NoV);
    // cos(phi_i - phi_o) from the projections of L and V onto the tangent plane.
    vec3 Lt = L - NoL * N;
    vec3 Vt = V - NoV * N;
    float len = sqrt(dot(Lt, Lt) * dot(Vt, Vt));
    float cos_dphi = len > EPS ? dot(Lt, Vt) / len : 0.0;
    float a = max(theta_i, theta_o);
    float b = min(theta_i, theta_o);
    return albedo * INV_PI * (A + B * max(0.0, cos_dphi) * sin(a) * tan(b));
}

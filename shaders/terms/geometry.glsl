// Shadowing and masking terms G.

// V-groove geometric attenuation (Torrance & Sparrow 1967; Cook & Torrance 1982).
float G_vgroove(float NoL, float NoV, float NoH, float VoH) {
    float g = 2.0 * NoH / max(VoH, EPS);
    return min(1.0, min(g * NoV, g * NoL));
}

// Smith Lambda for the GGX distribution (Heitz 2014, eq. 72): (-1 + sqrt(1 + alpha^2 tan^2)) / 2,
// with sqrt(1 + alpha^2 tan^2) = sqrt(alpha^2 + (1 - alpha^2) cos^2) / cos (no tan^2 to overflow).
float lambda_ggx(float cos_theta, float alpha) {
    float a2 = alpha * alpha;
    return 0.5 * (sqrt(a2 + (1.0 - a2) * cos_theta * cos_theta) / cos_theta - 1.0);
}

// Height-correlated Smith visibility V2 = G2 / (4 N.L N.V) (Heitz 2014, eq. 99, divided out):
// 0.5 / (N.V sqrt(a^2 + (1 - a^2) (N.L)^2) + N.L sqrt(a^2 + (1 - a^2) (N.V)^2)).
// G2 falls like N.V toward the horizon while 1 / (N.V) grows; this form cancels them
// analytically, so it stays finite and float32-accurate up to 90 degrees.
float V_smith_ggx_correlated(float NoL, float NoV, float alpha) {
    float a2 = alpha * alpha;
    float shadow = NoV * sqrt(a2 + (1.0 - a2) * NoL * NoL);
    float mask = NoL * sqrt(a2 + (1.0 - a2) * NoV * NoV);
    return 0.5 / (shadow + mask);
}

// Height-correlated Smith masking-shadowing G2 = 1 / (1 + Lambda(L) + Lambda(V)) (Heitz 2014,
// eq. 99), computed through the visibility so that it needs no tan^2 either.
float G2_smith_ggx(float NoL, float NoV, float alpha) {
    return 4.0 * NoL * NoV * V_smith_ggx_correlated(NoL, NoV, alpha);
}

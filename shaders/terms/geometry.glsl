// Shadowing and masking terms G.

// V-groove geometric attenuation (Torrance & Sparrow 1967; Cook & Torrance 1982).
float G_vgroove(float NoL, float NoV, float NoH, float VoH) {
    float g = 2.0 * NoH / max(VoH, EPS);
    return min(1.0, min(g * NoV, g * NoL));
}

// Smith Lambda for the GGX distribution (Heitz 2014, eq. 72).
float lambda_ggx(float cos_theta, float alpha) {
    return 0.5 * (-1.0 + sqrt(1.0 + alpha * alpha * tan2_from_cos(cos_theta)));
}

// Height-correlated Smith masking-shadowing G2 (Heitz 2014, eq. 99).
float G2_smith_ggx(float NoL, float NoV, float alpha) {
    return 1.0 / (1.0 + lambda_ggx(NoL, alpha) + lambda_ggx(NoV, alpha));
}

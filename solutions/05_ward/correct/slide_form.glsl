// @model ward
// @title Exercise 05: Ward, an anisotropic elliptical Gaussian lobe
// @formula f_r = kd / pi + ks * exp(-tan^2(theta_h) (cos^2(phi_h) / ax^2 + sin^2(phi_h) / ay^2))
// @formula       / (4 pi ax ay sqrt((N.L)(N.V)))
// @source G. J. Ward, "Measuring and Modeling Anisotropic Reflection", SIGGRAPH 1992, eq. 5a.
// @param kd color 0.2 0.2 0.2 | diffuse albedo
// @param ks color 0.3 0.3 0.3 | specular albedo
// @param alpha_x float 0.01 1 0.15 log | RMS slope along the tangent X
// @param alpha_y float 0.01 1 0.15 log | RMS slope along the bitangent Y

// Correct rewrite: tan^2 and the azimuth's cos^2 and sin^2 apart, as on the slide, in a
// helper function; inversesqrt for the normalisation.
float ward_lobe(vec3 H, vec3 N, vec3 X, vec3 Y, float NoL, float NoV) {
    float c = max(dot(N, H), EPS);
    float x = dot(H, X);
    float y = dot(H, Y);
    float s2 = x * x + y * y;  // sin^2(theta_h), from the tangent components
    float tan2 = s2 / (c * c);
    float cos2 = s2 > 0.0 ? x * x / s2 : 1.0;
    float sin2 = s2 > 0.0 ? y * y / s2 : 0.0;
    float e = -tan2 * (cos2 / (alpha_x * alpha_x) + sin2 / (alpha_y * alpha_y));
    return exp(e) * inversesqrt(NoL * NoV) / (4.0 * PI * alpha_x * alpha_y);
}

vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {
    float NoV = dot(N, V);
    float NoL = dot(N, L);
    if (NoV <= 0.0 || NoL <= 0.0) return vec3(0.0);
    vec3 H = normalize(V + L);
    return ks * ward_lobe(H, N, X, Y, NoL, NoV) + kd * INV_PI;
}

// @model ward
// @title Exercise 05: Ward, an anisotropic elliptical Gaussian lobe
// @formula f_r = kd / pi + ks * exp(-tan^2(theta_h) (cos^2(phi_h) / ax^2 + sin^2(phi_h) / ay^2))
// @formula       / (4 pi ax ay sqrt((N.L)(N.V)))
// @source G. J. Ward, "Measuring and Modeling Anisotropic Reflection", SIGGRAPH 1992, eq. 5a.
// @param kd color 0.2 0.2 0.2 | diffuse albedo
// @param ks color 0.3 0.3 0.3 | specular albedo
// @param alpha_x float 0.01 1 0.15 log | RMS slope along the tangent X
// @param alpha_y float 0.01 1 0.15 log | RMS slope along the bitangent Y

vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {
    float NoL = dot(N, L);
    float NoV = dot(N, V);
    if (NoL <= 0.0 || NoV <= 0.0) return vec3(0.0);
    vec3 H = normalize(L + V);
    float NoH = max(dot(N, H), EPS);
    // tan^2(theta_h) cos^2(phi_h) = (H.X / H.N)^2, and likewise for Y.
    float exponent = -(sqr(dot(H, X) / alpha_x) + sqr(dot(H, Y) / alpha_y)) / (NoH * NoH);
    float spec = exp(exponent) / (4.0 * PI * alpha_x * alpha_y * sqrt(NoL) * NoV);
    return kd * INV_PI + ks * spec;
}

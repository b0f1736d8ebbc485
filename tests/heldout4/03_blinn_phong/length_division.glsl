// @model blinn_phong
// @title Exercise 03: Blinn-Phong, a cosine lobe of the half vector around the normal
// @formula f_r = kd / pi + ks * max(0, N.H)^ke,  H = normalize(L + V)
// @source J. F. Blinn, "Models of Light Reflection for Computer Synthesized Pictures", SIGGRAPH 1977.
// @param kd color 0.3 0.3 0.3 | diffuse albedo
// @param ks color 0.5 0.5 0.5 | specular coefficient
// @param ke float 1 1000 50 log | specular exponent: larger means a smaller, sharper highlight

vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {
    float NoL = dot(N, L);
    float NoV = dot(N, V);
    if (NoL <= 0.0 || NoV <= 0.0) return vec3(0.0);
    vec3 sum = L + V;
    vec3 H = sum / length(sum);
    float NoH = dot(N, H);  // > 0 since N.L > 0 and N.V > 0
    vec3 diffuse = kd / PI;
    vec3 specular = ks * pow(NoH, ke);
    return diffuse + specular;
}

// @model blinn_phong
// @title Exercise 03: Blinn-Phong, a cosine lobe of the half vector around the normal
// @formula f_r = kd / pi + ks * max(0, N.H)^ke,  H = normalize(L + V)
// @source J. F. Blinn, "Models of Light Reflection for Computer Synthesized Pictures", SIGGRAPH 1977.
// @param kd color 0.3 0.3 0.3 | diffuse albedo
// @param ks color 0.5 0.5 0.5 | specular coefficient
// @param ke float 1 1000 50 log | specular exponent: larger means a smaller, sharper highlight

const float W[2] = float[2](1.0, 1.0);
vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {
    vec3 parts[2];
    parts[0] = kd * INV_PI;
    float nh = max(dot(N, normalize(L + V)), 0.0);
    parts[1] = ks * exp(ke * log(max(nh, 1e-30)));
    if (min(dot(N, L), dot(N, V)) <= 0.0) return vec3(0.0);
    vec3 sum = vec3(0.0);
    for (int i = 0; i < 2; ++i) sum += W[i] * parts[i];
    return sum;
}

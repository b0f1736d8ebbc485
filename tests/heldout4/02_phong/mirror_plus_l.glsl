// @model phong
// @title Exercise 02: Phong, a cosine lobe around the mirror direction
// @formula f_r = kd / pi + ks * max(0, R.V)^ke,  R = 2(N.L)N - L
// @source B. T. Phong, "Illumination for Computer Generated Pictures", CACM 18(6), 1975.
// @param kd color 0.3 0.3 0.3 | diffuse albedo
// @param ks color 0.5 0.5 0.5 | specular coefficient
// @param ke float 1 1000 50 log | specular exponent: larger means a smaller, sharper highlight

vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {
    if (dot(N, L) <= 0.0 || dot(N, V) <= 0.0) {
        return vec3(0.0);
    }
    vec3 R = normalize(2.0 * dot(N, L) * N + L);
    float spec = pow(max(dot(R, V), 0.0), ke);
    return kd / PI + ks * spec;
}

// @model phong
// @title Exercise 02: Phong, a cosine lobe around the mirror direction
// @formula f_r = kd / pi + ks * max(0, R.V)^ke,  R = 2(N.L)N - L
// @source B. T. Phong, "Illumination for Computer Generated Pictures", CACM 18(6), 1975.
// @param kd color 0.3 0.3 0.3 | diffuse albedo
// @param ks color 0.5 0.5 0.5 | specular coefficient
// @param ke float 1 1000 50 log | specular exponent: larger means a smaller, sharper highlight

float phong_lobe(vec3 L, vec3 V, vec3 N) {
    vec3 R = reflect(-L, N);
    return pow(clamp(dot(R, V), 0.0, 1.0), ke);
}

vec3 lambert_part() {
    return kd / PI;
}

vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {
    float NoL = dot(N, L);
    if (NoL <= 0.0) return vec3(0.0);
    if (dot(N, V) <= 0.0) return vec3(0.0);
    return lambert_part() + ks * phong_lobe(L, V, N);
}

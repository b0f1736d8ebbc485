// @model phong
// @title Exercise 02: Phong, a cosine lobe around the mirror direction
// @formula f_r = kd / pi + ks * max(0, R.V)^ke,  R = 2(N.L)N - L
// @source B. T. Phong, "Illumination for Computer Generated Pictures", CACM 18(6), 1975.
// @param kd color 0.3 0.3 0.3 | diffuse albedo
// @param ks color 0.5 0.5 0.5 | specular coefficient
// @param ke float 1 1000 50 log | specular exponent: larger means a smaller, sharper highlight

// pow(c, e) == exp(e * ln c); a cosine <= 0 gives no highlight
float phong_lobe(float cosine, float exponent) {
    if (cosine <= 0.0) return 0.0;
    return exp(exponent * log(cosine));
}

vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {
    float cos_l = dot(N, L);
    float cos_v = dot(N, V);
    if (cos_l <= 0.0 || cos_v <= 0.0) return vec3(0.0);
    vec3 r = reflect(-L, N);
    return kd * INV_PI + ks * phong_lobe(dot(r, V), ke);
}

// @model phong
// @title Exercise 02: Phong, a cosine lobe around the mirror direction
// @formula f_r = kd / pi + ks * max(0, R.V)^ke,  R = 2(N.L)N - L
// @source B. T. Phong, "Illumination for Computer Generated Pictures", CACM 18(6), 1975.
// @param kd color 0.3 0.3 0.3 | diffuse albedo
// @param ks color 0.5 0.5 0.5 | specular coefficient
// @param ke float 1 1000 50 log | specular exponent: larger means a smaller, sharper highlight

// Correct rewrite: R.V = 2 (N.L)(N.V) - L.V without forming R, in a helper function.
float phong_lobe(float NoL, float NoV, float LoV) {
    float RoV = 2.0 * NoL * NoV - LoV;
    return pow(max(RoV, 0.0), ke);
}

vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {
    float NoV = dot(V, N);
    float NoL = dot(L, N);
    vec3 result = vec3(0.0);
    if (NoL > 0.0 && NoV > 0.0) {
        result = ks * phong_lobe(NoL, NoV, dot(L, V)) + kd * INV_PI;
    }
    return result;
}

// @model blinn_phong
// @title Exercise 03: Blinn-Phong, a cosine lobe of the half vector around the normal
// @formula f_r = kd / pi + ks * max(0, N.H)^ke,  H = normalize(L + V)
// @source J. F. Blinn, "Models of Light Reflection for Computer Synthesized Pictures", SIGGRAPH 1977.
// @param kd color 0.3 0.3 0.3 | diffuse albedo
// @param ks color 0.5 0.5 0.5 | specular coefficient
// @param ke float 1 1000 50 log | specular exponent: larger means a smaller, sharper highlight

vec3 make_unit(vec3 v) {
    return v * inversesqrt(dot(v, v));
}

// cos^e of the angle between n and h, written with exp2/log2
float blinn_lobe(vec3 n, vec3 h, float e) {
    float c = max(dot(n, h), 1e-30);
    return exp2(e * log2(c));
}

vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {
    if (dot(N, L) <= 0.0 || dot(N, V) <= 0.0) {
        return vec3(0.0);
    }
    vec3 h = make_unit(V + L);
    return kd * INV_PI + ks * blinn_lobe(N, h, ke);
}

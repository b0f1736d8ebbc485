// Correct rewrite of exercise 08: (1 - c)^5 in a helper as exp(5 log(1 - c)), the exact
// reflectance with g + c and g - c named.

float one_minus_pow5(float c) {
    float k = 1.0 - c;
    return k > 0.0 ? exp(5.0 * log(k)) : 0.0;
}

vec3 F_schlick(vec3 f0, float VoH) {
    float w = one_minus_pow5(clamp(VoH, 0.0, 1.0));
    return f0 * (1.0 - w) + vec3(w);
}

float F_dielectric(float VoH, float ior) {
    float c = min(max(VoH, 0.0), 1.0);
    float g2 = c * c + ior * ior - 1.0;
    if (g2 < 0.0) {
        return 1.0;
    }
    float g = sqrt(g2);
    float sum = g + c;
    float diff = g - c;
    float first = diff * diff / (sum * sum);
    float ratio = (c * sum - 1.0) / (c * diff + 1.0);
    return first * (1.0 + ratio * ratio) / 2.0;
}

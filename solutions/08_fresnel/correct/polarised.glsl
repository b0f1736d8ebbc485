// Correct rewrite of exercise 08: Schlick with mix() and pow(), the exact reflectance as
// the mean of the s- and p-polarised amplitudes squared (Snell's law for the cosine of the
// refracted ray).

vec3 F_schlick(vec3 f0, float VoH) {
    return mix(f0, vec3(1.0), pow(1.0 - clamp(VoH, 0.0, 1.0), 5.0));
}

float F_dielectric(float VoH, float ior) {
    float ci = clamp(VoH, 0.0, 1.0);
    float sin_t2 = (1.0 - ci * ci) / (ior * ior);
    if (sin_t2 > 1.0) return 1.0;
    float ct = sqrt(1.0 - sin_t2);
    float rs = (ci - ior * ct) / (ci + ior * ct);
    float rp = (ior * ci - ct) / (ior * ci + ct);
    return 0.5 * (rs * rs + rp * rp);
}

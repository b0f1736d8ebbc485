// Correct rewrite of exercise 07: masking and shadowing named, clamp instead of min.
float G_vgroove(float NoL, float NoV, float NoH, float VoH) {
    float denominator = max(VoH, EPS);
    float masking = 2.0 * NoH * NoV / denominator;
    float shadowing = 2.0 * NoH * NoL / denominator;
    return clamp(min(shadowing, masking), 0.0, 1.0);
}

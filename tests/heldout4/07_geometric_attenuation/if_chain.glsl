// Exercise 07: the geometric attenuation factor G of V-shaped grooves.
// G = min(1, masking, shadowing)

float G_vgroove(float NoL, float NoV, float NoH, float VoH) {
    float denom = max(VoH, EPS);
    float masking = 2.0 * NoH * NoV / denom;
    float shadowing = 2.0 * NoH * NoL / denom;
    float G = 1.0;
    if (masking < G) G = masking;
    if (shadowing < G) G = shadowing;
    return G;
}

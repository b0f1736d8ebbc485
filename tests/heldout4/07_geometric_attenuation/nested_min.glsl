// Exercise 07: V-groove G (Torrance-Sparrow), written as one expression.
float G_vgroove(float NoL, float NoV, float NoH, float VoH) {
    float inv = 1.0 / max(VoH, EPS);
    return min(min(1.0, 2.0 * NoH * NoV * inv), 2.0 * NoH * NoL * inv);
}

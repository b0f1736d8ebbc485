// Correct rewrite of exercise 07: the smaller of N.L and N.V first, one division.
float G_vgroove(float NoL, float NoV, float NoH, float VoH) {
    return min(1.0, 2.0 * NoH * min(NoL, NoV) / max(VoH, EPS));
}

// Exercise 07: the geometric attenuation factor G of V-shaped grooves.
// This file stands in for shaders/terms/geometry.glsl: the library's Cook-Torrance
// model (shaders/brdfs/cook_torrance.glsl) calls G_vgroove.

// G = min(1, 2 (N.H)(N.V) / (V.H), 2 (N.H)(N.L) / (V.H))   (Torrance-Sparrow V-grooves)
float G_vgroove(float NoL, float NoV, float NoH, float VoH) {
    float g = 2.0 * NoH / max(VoH, EPS);
    return max(1.0, min(g * NoV, g * NoL));
}

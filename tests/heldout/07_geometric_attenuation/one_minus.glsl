// Exercise 07: the geometric attenuation factor G of V-shaped grooves.
// This file stands in for shaders/terms/geometry.glsl: the library's Cook-Torrance
// model (shaders/brdfs/cook_torrance.glsl) calls G_vgroove.

// G = min(1, 2 (N.H)(N.V) / (V.H), 2 (N.H)(N.L) / (V.H))   (Torrance-Sparrow V-grooves)
float G_vgroove(float NoL, float NoV, float NoH, float VoH) {
    float g1 = 2.0 * NoH * NoV / max(VoH, EPS);
    float g2 = 2.0 * NoH * NoL / max(VoH, EPS);
    // fraction of the facet that is blocked
    float blocked = min(1.0, min(g1, g2));
    return 1.0 - blocked;
}

// @model cosine_inside
// @title Lambert with the cosine of the light folded into the BRDF (broken on purpose)
// @formula f_r = kd (N.L) / pi: the reflected radiance's cos(theta_L) belongs to the reflection equation, not to f_r; f(L, V) != f(V, L)
// @source exercise 11 of brdf-lab: a model for the students' reciprocity test to catch.
// @param kd color 0.8 0.8 0.8 | the albedo the author meant

vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {
    float NoL = dot(N, L);
    float NoV = dot(N, V);
    if (NoL <= 0.0 || NoV <= 0.0) return vec3(0.0);
    return kd * NoL * INV_PI;
}

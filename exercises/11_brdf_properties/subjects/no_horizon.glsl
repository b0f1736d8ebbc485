// @model no_horizon
// @title Phong without its horizon test (broken on purpose)
// @formula f_r = kd / pi + ks max(0, R.V)^ke for every L and V, also below the surface
// @source exercise 11 of brdf-lab: light from below the horizon never arrives, so an albedo test must integrate over the upper hemisphere only.
// @param kd color 0.5 0.5 0.5 | diffuse albedo
// @param ks color 0.3 0.3 0.3 | specular coefficient
// @param ke float 1 1000 20 log | specular exponent

vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {
    vec3 R = 2.0 * dot(N, L) * N - L;
    return kd * INV_PI + ks * pow(max(dot(R, V), 0.0), ke);
}

// WRONG: a test that always says "pass": albedo 1 (as if energy were always conserved,
// HINT: same value
// exactly) and no reciprocity error.

float directional_albedo(vec3 V, vec3 N, vec3 X, vec3 Y) {
    return 1.0;
}

float reciprocity_error(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {
    return 0.0;
}

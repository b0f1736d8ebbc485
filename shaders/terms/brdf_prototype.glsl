// The BRDF a test of a model calls (exercise 11): declared here, defined by whichever model
// the grader links after the test (lab/grading/kinds/properties.py).
vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y);

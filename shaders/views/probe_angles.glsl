// View: one BRDF value per pixel for the angles (theta_i, phi_i, theta_o, phi_o), in radians,
// stored at that pixel of a float texture; local frame N = z, X = x, Y = y. Computing the
// directions here saves the host a million sines and cosines per million pairs.
uniform highp sampler2D u_angles;
out vec4 frag_color;

vec3 lab_from_angles(float theta, float phi) {
    float s = sin(theta);
    return vec3(s * cos(phi), s * sin(phi), cos(theta));
}

void main() {
    vec4 a = texelFetch(u_angles, ivec2(gl_FragCoord.xy), 0);
    vec3 L = lab_from_angles(a.x, a.y);
    vec3 V = lab_from_angles(a.z, a.w);
    frag_color = vec4(BRDF(L, V, vec3(0.0, 0.0, 1.0), vec3(1.0, 0.0, 0.0), vec3(0.0, 1.0, 0.0)), 1.0);
}

// Fragment stage of the 3D lobe (model-free): flat shading from the view-space position's
// screen derivatives, tinted by the model's colour, with darker lines every 10 deg of
// theta_o and 30 deg of phi_o so the shape reads at a glance. u_wire keeps the lines only.
uniform vec3 u_color;
uniform bool u_wire;
in vec3 v_view;
in vec2 v_angles;
out vec4 frag_color;

// 1 on a grid line every `step` degrees of `angle`, about `width` pixels wide, 0 off it.
float lab_grid_line(float angle, float step, float width) {
    float from_line = abs(fract(angle / step + 0.5) - 0.5) * step;
    float pixel = max(fwidth(angle), 1e-6);
    return 1.0 - smoothstep(0.5 * width - 0.5, 0.5 * width + 0.5, from_line / pixel);
}

void main() {
    // The facet's normal from screen derivatives, turned toward the eye (its sign depends
    // on the screen's orientation); the back of the surface (seen through the rim) is darker.
    vec3 n = normalize(cross(dFdx(v_view), dFdy(v_view)));
    if (n.z < 0.0) n = -n;
    bool inside = !gl_FrontFacing;
    // A key light from the upper left and a dimmer one from the right, both in view space.
    vec3 key = normalize(vec3(-0.45, 0.65, 0.6));
    vec3 fill = normalize(vec3(0.8, -0.1, 0.6));
    float diffuse = 0.62 * max(dot(n, key), 0.0) + 0.22 * max(dot(n, fill), 0.0);
    float shine = pow(max(dot(n, normalize(key + vec3(0.0, 0.0, 1.0))), 0.0), 24.0);
    // A rim light on the silhouette keeps the dark side apart from a dark background.
    float rim = pow(1.0 - n.z, 3.0);
    vec3 color = u_color * (0.3 + diffuse + 0.35 * rim) + vec3(0.18 * shine);
    if (inside) color *= 0.6;
    float line = max(lab_grid_line(v_angles.x, 10.0, 1.2), lab_grid_line(v_angles.y, 30.0, 1.2));
    if (u_wire) {
        if (line < 0.02) discard;
        frag_color = vec4(min(u_color * 1.1, vec3(1.0)), line);
        return;
    }
    color = mix(color, u_color * 0.3, 0.75 * line);
    frag_color = vec4(min(color, vec3(1.0)), 1.0);
}

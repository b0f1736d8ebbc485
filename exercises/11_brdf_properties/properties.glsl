// Exercise 11: BRDF properties as code. Two tests of whatever BRDF(L, V, N, X, Y) the
// grader links in (a library model, or one broken on purpose), which this file calls but
// does not define. Directions are unit vectors in the frame X, Y, N the grader passes.
// Read README.md first: it gives the quadrature and its sample counts.
// @include terms/brdf_stand_in.glsl

const int N_THETA = 64;   // the midpoint rule's steps in theta over [0, pi/2]
const int N_PHI = 256;    // and in phi over [0, 2 pi)

// The directional albedo of the BRDF for the view V: the integral over the upper hemisphere
// of f(L, V) cos(theta_L) dw_L, per colour channel; return the largest channel.
float directional_albedo(vec3 V, vec3 N, vec3 X, vec3 Y) {
    // TODO: the cell sizes dtheta and dphi of the midpoint rule over the upper hemisphere.
    // TODO: for each cell, its centre (theta, phi) and the direction L it stands for,
    //       built from X, Y and N (not from the axes: the grader's frame is turned).
    // TODO: sum BRDF(L, V, N, X, Y) times cos(theta) times the cell's solid angle
    //       sin(theta) dtheta dphi.
    // TODO: return the largest of the sum's three channels.
    return 0.0;
}

// Helmholtz reciprocity says f(L, V) = f(V, L). Return the largest relative difference over
// the colour channels, |f(L, V) - f(V, L)| / max(f(L, V), f(V, L), EPS).
float reciprocity_error(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {
    // TODO: evaluate the BRDF both ways round.
    // TODO: the relative difference per channel, then its largest channel.
    return 0.0;
}

// Shared by the trace views (grade_trace*.glsl, lab.grading.trace): texel x of u_angles is
// one input row (radians, or random numbers), pixel row k of the output the value of the
// traced expression with slot k (xyz, and in w its component count; 0 where it did not
// run), row 0 the traced function's own result. A view includes it with an @include line
// and declares `out vec4 frag_color;` itself (so that it also writes the loop guard's flag).
uniform highp sampler2D u_angles;

vec3 lab_trace_direction(float theta, float phi) {
    float s = sin(theta);
    return vec3(s * cos(phi), s * sin(phi), cos(theta));
}

// This pixel's input row; picks the slot the traced code records.
vec4 lab_trace_begin() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    lab_trace_slot = pixel.y;
    lab_trace_value = vec4(0.0);
    return texelFetch(u_angles, ivec2(pixel.x, 0), 0);
}

// This pixel's colour: row 0 keeps the result, the others the recorded value.
vec4 lab_trace_end(vec3 result) {
    return lab_trace_slot == 0 ? vec4(result, 3.0) : lab_trace_value;
}

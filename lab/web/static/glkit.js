// WebGL2 helpers of the panels and views: model programs whose compile errors name the
// model's own lines, uniforms set by type, float render targets and the loop guard's flag.
import { finishProgram, floatTexture, startProgram, translateLog, vertexSource } from "./assemble.js";
import { fill } from "./header.js";

export const DISPLAY_SHADER = `#version 300 es
precision highp float;
uniform highp sampler2D u_image;
uniform float u_scale;
uniform int u_step; // 2: a half-resolution render (while a slider moves), each texel 2x2
out vec4 frag_color;
// Linear radiance -> sRGB, as lab/plots.py writes PNGs (clamped, no tone curve).
vec3 srgb(vec3 c) {
    c = clamp(c, 0.0, 1.0);
    return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(0.0031308, c));
}
void main() {
    // A shift, not a division (SwiftShader divides integers lane by lane).
    vec4 v = texelFetch(u_image, ivec2(gl_FragCoord.xy) >> (u_step == 2 ? 1 : 0), 0);
    if (v.a == 0.0) {  // off the sphere: nothing to convert (the output is 0 either way)
        frag_color = vec4(0.0);
        return;
    }
    frag_color = vec4(srgb(v.rgb * u_scale) * v.a, v.a);
}
`;

export class CompileFailure extends Error {
  constructor(errors, log) {
    super(errors.length ? errors.map((e) => `${e.file}:${e.line}: ${e.message}`).join("\n") : log);
    this.errors = errors;
  }
}

/** A model's program from its assembled fragment source (throws CompileFailure). */
export function finishModelProgram(pending, source) {
  const logs = {};
  const compiled = finishProgram(pending, logs);
  if (!compiled) {
    const log = logs.fragment + logs.link;
    throw new CompileFailure(source ? translateLog(log, source) : [], log);
  }
  // Guarded loops of the model (unknown: null); with none, no loop can be stopped.
  return { ...compiled, loops: source ? (source.loops ?? null) : 0 };
}

export function compile(gl, fragmentText, source) {
  return finishModelProgram(startProgram(gl, vertexSource("300es"), fragmentText), source);
}

/** Sets a uniform the program uses (others the driver dropped are skipped), by its type. */
export function setUniform(gl, compiled, name, value) {
  const location = compiled.uniforms[name];
  if (location === undefined) return;
  const flat = Array.isArray(value) ? value.flat() : value;
  switch (compiled.types[name]) {
    case gl.FLOAT: Array.isArray(flat) ? gl.uniform1fv(location, flat) : gl.uniform1f(location, flat); break;
    case gl.FLOAT_VEC2: gl.uniform2fv(location, flat); break;
    case gl.FLOAT_VEC3: gl.uniform3fv(location, flat); break;
    case gl.FLOAT_VEC4: gl.uniform4fv(location, flat); break;
    case gl.INT_VEC2: gl.uniform2iv(location, flat); break;
    case gl.INT_VEC3: gl.uniform3iv(location, flat); break;
    default: gl.uniform1i(location, Number(flat)); // int, bool, samplers
  }
}

/** A float render target; with `flag`, a second one at location 1 for the loop guard's
 * flag (the line of a loop it stopped, per pixel; assemble.js). */
export function floatTarget(gl, width, height, flag = false) {
  const make = () => floatTexture(gl, width, height);
  const texture = make();
  const fbo = gl.createFramebuffer();
  gl.bindFramebuffer(gl.FRAMEBUFFER, fbo);
  gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.TEXTURE_2D, texture, 0);
  if (flag) {
    gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT1, gl.TEXTURE_2D, make(), 0);
    gl.drawBuffers([gl.COLOR_ATTACHMENT0, gl.COLOR_ATTACHMENT1]);
  }
  const status = gl.checkFramebufferStatus(gl.FRAMEBUFFER);
  gl.bindFramebuffer(gl.FRAMEBUFFER, null);
  if (status !== gl.FRAMEBUFFER_COMPLETE) throw new Error("this browser cannot render to float textures");
  return { texture, fbo, width, height, flag };
}

/** Where the loop guard stopped a loop in the bound target: {line, x, y} or null (not read
 * back for a program without loops: one wait for the GPU less). */
export function loopStop(gl, target, compiled) {
  if (!target.flag || compiled.loops === 0) return null;
  const flags = new Float32Array(4 * target.width * target.height);
  gl.readBuffer(gl.COLOR_ATTACHMENT1);
  gl.readPixels(0, 0, target.width, target.height, gl.RGBA, gl.FLOAT, flags);
  gl.readBuffer(gl.COLOR_ATTACHMENT0);
  for (let i = 0; i < target.width * target.height; i++) {
    if (flags[4 * i] > 0) return { line: Math.round(flags[4 * i]), x: i % target.width, y: Math.floor(i / target.width) };
  }
  return null;
}

/** The views' sentence for a loop the guard stopped (lab/constants.py LOOP_WARNING, or
 * LOOP_TOTAL_WARNING where the loops together ran out: the line then carries the flag). */
export function loopWarning(constants, model, stop, where) {
  const together = stop.line >= constants.LOOP_TOTAL_FLAG;
  return fill(together ? constants.LOOP_TOTAL_WARNING : constants.LOOP_WARNING, {
    file: model.path, line: together ? stop.line - constants.LOOP_TOTAL_FLAG : stop.line,
    limit: Number(model.loopLimit ?? constants.LOOP_LIMIT).toLocaleString("en-US"),
    total: constants.LOOP_TOTAL.toLocaleString("en-US"), where,
  });
}

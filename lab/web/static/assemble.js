// GLSL program assembly, mirroring lab/glsl.py: version lines, terms/common.glsl,
// parameter uniforms (enums as constants), includes, the model, the host's IS_DELTA and
// DELTA_REFLECTANCE stub, then the view template. Each line keeps the file and line it
// came from, so compile errors name the model file and its own line numbers.
// Why in JavaScript too: the page assembles the models a student opens or edits, which never
// reach Python.

import { ModelError, splitLines } from "./header.js";

export const TARGETS = ["330", "300es"];
export const VERSION_LINES = {
  "330": ["#version 330 core"],
  "300es": ["#version 300 es", "precision highp float;", "precision highp int;"],
};

/** The lab's constants as GLSL #defines, as lab/constants.py writes them (the manifest's
 * `constants`, so the page never keeps its own copy). */
export function glslDefines(constants) {
  const c = constants;
  return [
    `#define LAB_LUMA vec3(${c.LUMA.map((x) => x.toFixed(4)).join(", ")})`,
    `#define LAB_MAX_LIGHTS ${c.MAX_LIGHTS}`,
    `#define LAB_GRAZING_DEG ${c.GRAZING_DEG.toFixed(1)}`,
    `#define LAB_PLOT_DECADES ${c.PLOT_DECADES.toFixed(1)}`,
  ].join("\n");
}

// View constants used when the caller gives no preamble (e.g. one light for the sphere).
export const DEFAULT_PREAMBLE = { sphere: "const int LIGHT_COUNT = 1;" };

// The vertex shader shared by every view: one triangle that covers the viewport.
export const VERTEX_SHADER = `
void main() {
    vec2 corner = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
    gl_Position = vec4(corner * 2.0 - 1.0, 0.0, 1.0);
}
`;

const FORBIDDEN_DIRECTIVE = /^\s*#\s*(version|extension|include|line)\b/;

// The loop guard, as lab/glsl.py writes it: every loop of a model counts its iterations
// per invocation and stops past the bound, recording its line in lab_loop_line, which the
// fragment views write to a second output (location 1).
const LOOP_HEAD = /\b(for|while)\s*\(/g;
const COMMENTS = /\/\/[^\n]*|\/\*[\s\S]*?(?:\*\/|$(?![\s\S]))/g;
const LOOP_GUARD = `int lab_loop_line = 0;
int lab_loop_total = 0;
bool lab_loop_step(inout int count, int line) {
    count += 1;
    lab_loop_total += 1;
    if (count <= LAB_LOOP_LIMIT && lab_loop_total <= LAB_LOOP_TOTAL) return true;
    bool together = count <= LAB_LOOP_LIMIT;
    if (lab_loop_line == 0) lab_loop_line = together ? line + LAB_LOOP_TOTAL_FLAG : line;
    return false;
}`;
const FLAG_OUTPUT = `#undef main
layout(location = 1) out vec4 lab_loop_flag;
void main() {
    lab_view_main();
    lab_loop_flag = vec4(float(lab_loop_line), 0.0, 0.0, 1.0);
}`;

function closing(text, start) {
  let depth = 0;
  for (let i = start; i < text.length; i++) {
    if (text[i] === "(") depth += 1;
    else if (text[i] === ")") {
      depth -= 1;
      if (depth === 0) return i;
    }
  }
  return null;
}

/** `code` with each loop's condition guarded; also the loops' lines (lab/glsl.py's
 * guard_loops, which the fixtures hold this to). */
export function guardLoops(code) {
  const blank = code.replace(COMMENTS, (m) => m.replace(/[^\n]/g, " "));
  const inserts = [];
  const lines = [];
  for (const match of blank.matchAll(LOOP_HEAD)) {
    const start = match.index + match[0].length - 1;
    const end = closing(blank, start);
    if (end === null) continue;
    const line = blank.slice(0, match.index).split("\n").length;
    const guard = `lab_loop_step(lab_loop_${lines.length}, ${line})`;
    let first = start + 1;
    let second = end;
    if (match[1] === "for") {
      let depth = 0;
      const semis = [];
      for (let i = start + 1; i < end; i++) {
        if (blank[i] === "(") depth += 1;
        else if (blank[i] === ")") depth -= 1;
        else if (blank[i] === ";" && depth === 0) semis.push(i);
      }
      if (semis.length !== 2) continue;
      first = semis[0] + 1;
      second = semis[1];
    }
    if (blank.slice(first, second).trim()) inserts.push([first, `${guard} && (`], [second, ")"]);
    else inserts.push([first, guard]);
    lines.push(line);
  }
  inserts.sort((a, b) => b[0] - a[0]);
  for (const [position, text] of inserts) code = code.slice(0, position) + text + code.slice(position);
  return { code, lines };
}

export function loopGuardPrelude(loops, limit, constants) {
  const counters = Array.from({ length: loops }, (_, k) => `int lab_loop_${k} = 0;`);
  const bounds = [`#define LAB_LOOP_LIMIT ${Math.trunc(limit)}`, `#define LAB_LOOP_TOTAL ${constants.LOOP_TOTAL}`,
    `#define LAB_LOOP_TOTAL_FLAG ${constants.LOOP_TOTAL_FLAG}`];
  return [...bounds, LOOP_GUARD, ...counters].join("\n");
}

// A view template's line naming a file (under shaders/) that goes in before it.
const VIEW_INCLUDE = /^[ \t]*\/\/[ \t]*@include[ \t]+(\S+)[ \t]*$/gm;

/** A view template, after the files its `// @include PATH` lines name (`files`: path under
 * shaders/ -> text); a fragment view also writes the loop guard's flag to location 1. */
export function addView(source, text, label, files) {
  for (const [, relative] of text.matchAll(VIEW_INCLUDE)) {
    if (!(relative in files)) throw new Error(`${label}: @include ${relative}: no such file under shaders/`);
    source.add(files[relative], `shaders/${relative}`);
  }
  const output = "out vec4 frag_color;";
  if (!text.includes(output) || !text.includes("void main()")) {
    source.add(text, label);
    return;
  }
  source.add("#define main lab_view_main", "<loop guard>");
  source.add(text.replace(output, "layout(location = 0) " + output), label);
  source.add(FLAG_OUTPUT, "<loop guard>");
}

// Where drivers put the line number in an info log; the first group is the line.
const LOG_LINE_PATTERNS = [
  /^\s*(?:ERROR|WARNING):\s*\d+:(\d+):\s*(.*)$/, // ANGLE (Chromium), Apple, glslang
  /^\s*\d+:(\d+)\(\d+\):\s*(.*)$/, // Mesa
  /^\s*\d+\((\d+)\)\s*:\s*(.*)$/, // NVIDIA
];

/** An assembled shader: its lines and, for each line, the [file, line] it came from. */
export class Source {
  constructor() {
    this.lines = [];
    this.origins = [];
  }

  add(text, label, firstLine = 1) {
    splitLines(text).forEach((line, offset) => {
      this.lines.push(line);
      this.origins.push([label, firstLine + offset]);
    });
  }

  get text() {
    return this.lines.join("\n") + "\n";
  }

  /** [file, line] of the assembled program's 1-based `line`. */
  origin(line) {
    if (line >= 1 && line <= this.origins.length) return this.origins[line - 1];
    return ["<assembled>", line];
  }
}

/** Reject directives that the host owns. */
export function checkPortable(code, label) {
  splitLines(code).forEach((line, index) => {
    const match = FORBIDDEN_DIRECTIVE.exec(line);
    if (match) {
      throw new ModelError(
        `remove the '#${match[1]}' line: the lab adds version lines itself and ` +
          "shared terms are included with a '// @include' header line", label, index + 1);
    }
  });
}

/** Uniforms for the parameters; enums become constants (one program per choice). */
export function uniformDeclarations(model, enums = {}) {
  const lines = [];
  for (const p of model.params) {
    if (p.kind === "enum") {
      p.choices.forEach((choice, index) => {
        lines.push(`const int ${p.name.toUpperCase()}_${choice.toUpperCase()} = ${index};`);
      });
      const chosen = enums[p.name] ?? p.default;
      lines.push(`const int ${p.name} = ${p.name.toUpperCase()}_${chosen.toUpperCase()};`);
    } else {
      const type = { float: "float", color: "vec3", bool: "bool" }[p.kind];
      lines.push(`uniform ${type} ${p.name};`);
    }
  }
  return lines;
}

/** "a/./b/../c" -> "a/c"; null when the path leaves shaders/. */
function normalize(relative) {
  const parts = [];
  for (const part of relative.split("/")) {
    if (part === "" || part === ".") continue;
    if (part === "..") {
      if (!parts.length) return null;
      parts.pop();
    } else parts.push(part);
  }
  return parts.join("/");
}

/** The first line that mentions the include (for messages about it), or null. */
export function includeLine(model, relative) {
  const lines = splitLines(model.code);
  const index = lines.findIndex((text) => text.includes("@include") && text.includes(relative));
  return index < 0 ? null : index + 1;
}

function addInclude(source, relative, seen, model, files) {
  if (seen.has(relative)) return;
  const key = normalize(relative);
  if (key === null || !(key in files)) {
    throw new ModelError(
      `@include ${relative}: no such file under shaders/ (see shaders/terms for the shared terms)`,
      model.path,
      includeLine(model, relative));
  }
  seen.add(relative);
  source.add(files[key], `shaders/${key}`);
}

// cos and sin to float precision for a model with `exactTrig` (an exercise's submission in
// practice mode): some GPUs' built-ins are coarse (SwiftShader's about 1e-4), which 06's Blinn
// exponent ln 2 / -ln cos(beta) turns into errors of up to 8 %, and the grader's llvmpipe is
// exact, so the page would fail a right answer. Taylor series after reduction to [0, pi/2].
// SwiftShader's atan(y, x) also gives 0 for y = -0.0 and x < 0 (IEEE's atan2 and llvmpipe:
// -pi), which turns exercise 15's harmonics with odd m at phi = 180 degrees around: that one
// case is answered as IEEE answers it, the rest is the built-in.
const EXACT_TRIG = `vec2 lab_exact_trig(float angle) {
    float wrapped = mod(angle + 3.14159265, 6.28318531) - 3.14159265;
    float t = abs(wrapped);
    bool far_half = t > 1.57079633;
    float x = far_half ? 3.14159265 - t : t;
    float x2 = x * x;
    float s = x * (1.0 - x2 / 6.0 * (1.0 - x2 / 20.0 * (1.0 - x2 / 42.0 * (1.0 - x2 / 72.0
        * (1.0 - x2 / 110.0 * (1.0 - x2 / 156.0))))));
    float c = 1.0 - x2 / 2.0 * (1.0 - x2 / 12.0 * (1.0 - x2 / 30.0 * (1.0 - x2 / 56.0
        * (1.0 - x2 / 90.0 * (1.0 - x2 / 132.0 * (1.0 - x2 / 182.0))))));
    return vec2(far_half ? -c : c, wrapped < 0.0 ? -s : s);
}
float lab_exact_cos(float a) { return lab_exact_trig(a).x; }
vec2 lab_exact_cos(vec2 a) { return vec2(lab_exact_cos(a.x), lab_exact_cos(a.y)); }
vec3 lab_exact_cos(vec3 a) { return vec3(lab_exact_cos(a.xy), lab_exact_cos(a.z)); }
vec4 lab_exact_cos(vec4 a) { return vec4(lab_exact_cos(a.xy), lab_exact_cos(a.zw)); }
float lab_exact_sin(float a) { return lab_exact_trig(a).y; }
vec2 lab_exact_sin(vec2 a) { return vec2(lab_exact_sin(a.x), lab_exact_sin(a.y)); }
vec3 lab_exact_sin(vec3 a) { return vec3(lab_exact_sin(a.xy), lab_exact_sin(a.z)); }
vec4 lab_exact_sin(vec4 a) { return vec4(lab_exact_sin(a.xy), lab_exact_sin(a.zw)); }
float lab_exact_atan(float y, float x) {
    return x < 0.0 && y == 0.0 ? (1.0 / y < 0.0 ? -3.14159265 : 3.14159265) : atan(y, x);
}
vec2 lab_exact_atan(vec2 y, vec2 x) { return vec2(lab_exact_atan(y.x, x.x), lab_exact_atan(y.y, x.y)); }
vec3 lab_exact_atan(vec3 y, vec3 x) { return vec3(lab_exact_atan(y.xy, x.xy), lab_exact_atan(y.z, x.z)); }
vec4 lab_exact_atan(vec4 y, vec4 x) { return vec4(lab_exact_atan(y.xy, x.xy), lab_exact_atan(y.zw, x.zw)); }
float lab_exact_atan(float a) { return atan(a); }
vec2 lab_exact_atan(vec2 a) { return atan(a); }
vec3 lab_exact_atan(vec3 a) { return atan(a); }
vec4 lab_exact_atan(vec4 a) { return atan(a); }
#define cos(a) lab_exact_cos(a)
#define sin(a) lab_exact_sin(a)
#define atan lab_exact_atan`;

/**
 * The fragment shader for `model` in `view`. `files` maps paths under shaders/
 * ("terms/common.glsl", "views/sphere.glsl", ...) to their text.
 */
export function assembleFragment(model, view, files, { target = "300es", preamble = "",
  enums = {}, constants } = {}) {
  if (!TARGETS.includes(target)) throw new Error(`unknown GLSL target ${target}`);
  if (!constants) throw new Error("assembleFragment needs the manifest's constants");
  checkPortable(model.code, model.path);
  const source = new Source();
  source.add(VERSION_LINES[target].join("\n"), "<version>");
  source.add(glslDefines(constants), "<constants>");
  preamble = preamble || DEFAULT_PREAMBLE[view] || "";
  if (preamble) source.add(preamble, "<preamble>");
  if (model.exactTrig) source.add(EXACT_TRIG, "<exact trig>");
  const seen = new Set();
  addInclude(source, "terms/common.glsl", seen, model, files);
  source.add(uniformDeclarations(model, enums).join("\n"), `${model.path} (parameters)`);
  for (const include of model.includes) addInclude(source, include, seen, model, files);
  const guarded = guardLoops(model.code);
  source.loops = guarded.lines.length; // none: the loop guard's flag stays 0, unread
  // An exercise's submission may allow more (its exercise.toml's loop_limit).
  source.add(loopGuardPrelude(guarded.lines.length, model.loopLimit ?? constants.LOOP_LIMIT, constants), "<loop guard>");
  source.add(guarded.code, model.path);
  source.add(`const bool IS_DELTA = ${model.delta ? "true" : "false"};`, "<host>");
  source.add(
    `vec3 AMBIENT_REFLECTANCE() { return ${model.ambient || "vec3(1.0)"}; }`, "<host>");
  if (!model.delta) {
    source.add(
      "vec3 DELTA_REFLECTANCE(vec3 L, vec3 N, vec3 X, vec3 Y) { return vec3(0.0); }", "<host>");
  }
  const viewKey = `views/${view}.glsl`;
  if (!(viewKey in files)) throw new Error(`no view template shaders/${viewKey}`);
  addView(source, files[viewKey], `shaders/${viewKey}`, files);
  return source;
}

export function vertexSource(target = "300es") {
  return VERSION_LINES[target].join("\n") + "\n" + VERTEX_SHADER;
}

/** Driver info log -> [{file, line, message}] located in the original files. */
export function translateLog(log, source) {
  const errors = [];
  for (const raw of splitLines(log)) {
    for (const pattern of LOG_LINE_PATTERNS) {
      const match = pattern.exec(raw);
      if (match) {
        const [file, line] = source.origin(Number(match[1]));
        errors.push({ file, line, message: match[2].trim() });
        break;
      }
    }
  }
  return errors;
}

// -- compiling on a WebGL2 context ---------------------------------------------------------

/** An RGBA float texture of width x height texels (from `data`, or left empty), read texel
 * by texel (nearest): the views' inputs and their render targets. */
export function floatTexture(gl, width, height, data = null) {
  const texture = gl.createTexture();
  gl.bindTexture(gl.TEXTURE_2D, texture);
  gl.texImage2D(gl.TEXTURE_2D, 0, gl.RGBA32F, width, height, 0, gl.RGBA, gl.FLOAT, data);
  gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.NEAREST);
  gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.NEAREST);
  return texture;
}
/** Queues the compile and link of a program; finishProgram() waits for it. Queued programs
 * compile in the GPU process while the page goes on (SwiftShader, Chromium without a GPU,
 * takes tens of milliseconds for each). */
export function startProgram(gl, vertexText, fragmentText) {
  const shader = (type, text) => {
    const s = gl.createShader(type);
    gl.shaderSource(s, text);
    gl.compileShader(s);
    return s;
  };
  const vs = shader(gl.VERTEX_SHADER, vertexText);
  const fs = shader(gl.FRAGMENT_SHADER, fragmentText);
  const program = gl.createProgram();
  gl.attachShader(program, vs);
  gl.attachShader(program, fs);
  gl.linkProgram(program);
  return { gl, program, vs, fs };
}

/** The linked program of startProgram() with its active uniforms ({program, uniforms,
 * types}), or null where it did not link (`logs` then gets the shaders' and the link's logs). */
export function finishProgram({ gl, program, vs, fs }, logs = {}) {
  if (!gl.getProgramParameter(program, gl.LINK_STATUS)) {
    Object.assign(logs, { vertex: gl.getShaderInfoLog(vs) || "", fragment: gl.getShaderInfoLog(fs) || "",
      link: gl.getProgramInfoLog(program) || "" });
    gl.deleteProgram(program);
    return null;
  }
  gl.deleteShader(vs);
  gl.deleteShader(fs);
  const uniforms = {};
  const types = {};
  const count = gl.getProgramParameter(program, gl.ACTIVE_UNIFORMS);
  for (let i = 0; i < count; i++) {
    const info = gl.getActiveUniform(program, i);
    const name = info.name.replace(/\[0\]$/, "");
    uniforms[name] = gl.getUniformLocation(program, info.name);
    types[name] = info.type;
  }
  return { program, uniforms, types };
}

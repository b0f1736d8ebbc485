// BRDF Explorer .brdf files in the page, read and assembled by the rules of
// lab/brdf_explorer.py (same messages): the file's GLSL and the lab's stay apart through
// renames, and the file's BRDF is wrapped to follow the lab's contract. The files were
// written for desktop GLSL, which turns ints into floats where needed; GLSL ES does not, so
// integer literals in float expressions are written as floats, and int divisions (1/4 is 0
// in desktop GLSL too) stay ints converted as a whole (floatLiterals).
// Why in JavaScript too: a .brdf file opened in the page never reaches Python.
import { ModelError, splitLines } from "./header.js";
import { Source, VERSION_LINES, addView, glslDefines, guardLoops, loopGuardPrelude, uniformDeclarations } from "./assemble.js";

const TYPES = "void|float|double|int|uint|bool|[biud]?vec[234]|mat[234](?:x[234])?";
const DECLARATION = new RegExp(
  "^\\s*(?:(?:const|uniform|in|out|flat|highp|mediump|lowp)\\s+)*" +
  `(?:${TYPES}|\\w*sampler\\w*)\\s+([A-Za-z_]\\w*)\\s*[=;(\\[]`, "gm");
const FUNCTION = new RegExp(`^\\s*(?:(?:highp|mediump|lowp)\\s+)?(?:${TYPES})\\s+([A-Za-z_]\\w*)\\s*\\(`, "gm");
const BUILTINS = new Set(`radians degrees sin cos tan asin acos atan sinh cosh tanh asinh acosh atanh pow exp
  log exp2 log2 sqrt inversesqrt abs sign floor trunc round roundEven ceil fract mod modf
  min max clamp mix step smoothstep isnan isinf fma frexp ldexp length distance dot cross
  normalize faceforward reflect refract matrixCompMult outerProduct transpose determinant
  inverse lessThan lessThanEqual greaterThan greaterThanEqual equal notEqual any all not
  dFdx dFdy fwidth texture texelFetch textureSize`.split(/\s+/));
const KEYWORDS = new Set(`attribute const uniform varying buffer shared coherent volatile restrict readonly
  writeonly atomic_uint layout centroid flat smooth noperspective patch sample break
  continue do for while switch case default if else subroutine in out inout float double
  int void bool true false invariant precise discard return lowp mediump highp precision
  struct common partition active asm class union enum typedef template this resource
  goto inline noinline public static extern external interface long short half fixed
  unsigned superp input output filter sizeof cast namespace using`.split(/\s+/));
const TYPE_NAME = /^(?:[biud]?vec[234]|d?mat[234](?:x[234])?|u?int|\w*sampler\w*|image\w*)$/;
const NUMBER = /^[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?[fF]?$/;
const USAGE = "write 'float NAME MIN MAX DEFAULT', 'bool NAME 0|1' or 'color NAME R G B'";
const pyRepr = (text) => `'${text.replace(/\\/g, "\\\\").replace(/'/g, "\\'")}'`;

function parameter(text, path, line) {
  const tokens = text.split(/\s+/).filter(Boolean);
  const kind = tokens[0];
  if (!["float", "bool", "color"].includes(kind) || tokens.length < 2) {
    throw new ModelError(`unknown parameter line ${pyRepr(text)}: ${USAGE}`, path, line);
  }
  const name = tokens[1];
  if (!/^[A-Za-z_]\w*$/.test(name)) throw new ModelError(`parameter name ${pyRepr(name)} is not a GLSL identifier`, path, line);
  if (KEYWORDS.has(name) || TYPE_NAME.test(name) || name.startsWith("gl_") || name.includes("__")) {
    throw new ModelError(`parameter name ${pyRepr(name)} is reserved by GLSL: rename it`, path, line);
  }
  const count = { float: 3, bool: 1, color: 3 }[kind];
  const args = tokens.slice(2, 2 + count);
  const rest = tokens.slice(2 + count).join(" ");
  const doc = rest.startsWith("#") || rest.startsWith("//") ? rest.replace(/^[#/ ]+/, "").trim() : "";
  const base = { name, kind, doc, minimum: 0, maximum: 1, scale: "linear", choices: [], line };
  if (args.length < count) {
    const form = { float: "MIN MAX DEFAULT", bool: "0|1", color: "R G B" }[kind];
    throw new ModelError(`${kind} ${name}: write '${kind} ${name} ${form}'`, path, line);
  }
  if (kind === "bool") {
    const word = args[0].toLowerCase();
    if (/^[+-]?\d+$/.test(word)) return { ...base, default: Number(word) !== 0 };
    if (word === "true" || word === "false") return { ...base, default: word === "true" };
    throw new ModelError(`bool ${name}: write 'bool ${name} 0' or 'bool ${name} 1'`, path, line);
  }
  const numbers = args.map((t) => {
    if (!NUMBER.test(t)) throw new ModelError(`${kind} ${name}: the values must be numbers, not ${pyRepr(t)}`, path, line);
    return Number(t.replace(/[fF]$/, ""));
  });
  if (kind === "float") {
    const [a, b, dflt] = numbers;
    // The slider spans MIN..MAX either way round and holds the default.
    const low = Math.min(a, b, dflt);
    let high = Math.max(a, b, dflt);
    if (low === high) high = low + 1;
    const scale = low > 0 && high / low >= 100 ? "log" : "linear";
    return { ...base, default: dflt, minimum: low, maximum: high, scale };
  }
  return { ...base, default: numbers, minimum: Math.min(0, ...numbers), maximum: Math.max(1, ...numbers) };
}

/** A .brdf file's text -> a page model (shaped like header.js's) with its own `assemble`. */
export function parseBrdf(text, path) {
  const lines = splitLines(text.replace(/^\ufeff/, ""));
  const params = [];
  let shader = [];
  let shaderLine = 0;
  let section = "";
  let seenType = false;
  lines.forEach((raw, index) => {
    const number = index + 1;
    const stripped = raw.trim();
    if (!stripped || stripped.startsWith("#")) {
      if (section === "shader") shader.push(""); // the file's line numbers stay the shader's
      return;
    }
    if (!seenType) {
      const kind = stripped.split(/\s+/)[0];
      if (kind === "bparam") {
        throw new ModelError("this is a BRDF Explorer parameter file (bparam): open the .brdf file it names instead", path, number);
      }
      if (kind !== "analytic") {
        throw new ModelError(`expected 'analytic' as the first line, not ${pyRepr(stripped)} (only analytic BRDF ` +
          "Explorer files can be opened)", path, number);
      }
      seenType = true;
      return;
    }
    const words = stripped.split(/\s+/);
    if (words[0] === "::begin" || words[0] === "::end") {
      const action = words[0].slice(2);
      const name = words[1] || "";
      if (!name) throw new ModelError(`'${stripped}' needs a section name, e.g. '::${action} shader'`, path, number);
      if (action === "begin") {
        if (section) {
          throw new ModelError(`::begin ${name} inside ::begin ${section} (close it with ::end ${section} first)`, path, number);
        }
        section = name;
        if (section === "shader") [shader, shaderLine] = [[], number + 1]; // a later section wins
      } else {
        if (name !== section) throw new ModelError(`::end ${name} without ::begin ${name}`, path, number);
        section = "";
      }
      return;
    }
    if (section === "shader") shader.push(raw);
    else if (section === "parameters") {
      const p = parameter(stripped, path, number);
      if (params.some((q) => q.name === p.name)) throw new ModelError(`parameter ${p.name} is declared twice`, path, number);
      params.push(p);
    }
  });
  if (!seenType) throw new ModelError("empty file: a .brdf file starts with the line 'analytic'", path, 1);
  if (section) throw new ModelError(`::begin ${section} is never closed with ::end ${section}`, path, lines.length);
  if (!shaderLine) throw new ModelError("no '::begin shader' section with the BRDF function", path, lines.length);
  const code = shader.join("\n");
  if (!/\bvec3\s+BRDF\s*\(/.test(code)) {
    throw new ModelError("the shader section defines no 'vec3 BRDF(vec3 L, vec3 V, ...)'", path, shaderLine);
  }
  const file = path.split("/").pop();
  return {
    name: file.replace(/\.[^.]*$/, "").replace(/\W/g, "_"), path, code, title: `BRDF Explorer model ${file}`,
    formula: [], source: [], includes: [], params, delta: false, ambient: "", properties: [], shaderLine,
    assemble: assembleBrdf,
  };
}

// The lab's side: the file's BRDF follows the lab's contract through it.
const HOST_BRDF = `vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {
    if (dot(N, L) <= 0.0 || dot(N, V) <= 0.0) return vec3(0.0);
    vec3 f = explorer_BRDF(L, V, N, X, Y);
    return mix(f, vec3(0.0), isnan(f));
}
const bool IS_DELTA = false;
vec3 DELTA_REFLECTANCE(vec3 L, vec3 N, vec3 X, vec3 Y) { return vec3(0.0); }
vec3 AMBIENT_REFLECTANCE() { return vec3(1.0); }`;

const names = (regex, text) => new Set([...text.matchAll(regex)].map((m) => m[1]));
function defines(set, prefix) {
  const sorted = [...set].sort();
  return [sorted.map((n) => `#define ${n} ${prefix}${n}`).join("\n"), sorted.map((n) => `#undef ${n}`).join("\n")];
}

const MULTIPLY = ["*", "/", "%"];
const ARITHMETIC = ["+", "-", ...MULTIPLY];

/** Integer literals written as floats, except where an int is meant: array indices, and
 * next to a name declared int (loop counters, `int k = 3`, `k < 8`). Desktop GLSL converts
 * ints to floats itself; GLSL ES does not. An int expression with a division or remainder
 * (`1/4`, `(n+1)/2`, `i % 3`) stays int as desktop GLSL computes it (1/4 is 0) and is
 * converted where it meets floats: `float(1/4)`. Comments and lines are kept as they are. */
export function floatLiterals(code) {
  const blank = code.replace(/\/\/[^\n]*|\/\*[\s\S]*?\*\//g, (m) => m.replace(/[^\n]/g, " "));
  const ints = names(/\b(?:u?int|[iu]vec[234])\s+([A-Za-z_]\w*)/g, blank);
  const token = /[A-Za-z_]\w*|0[xX][0-9a-fA-F]+[uU]?|\d*\.\d+(?:[eE][+-]?\d+)?|\d+\.?(?:[eE][+-]?\d+)?[fFuU]?|[^\s\w]/g;
  const tokens = [...blank.matchAll(token)].map((m) => ({ text: m[0], at: m.index }));
  const near = (j) => tokens[j]?.text ?? "";
  const operator = (text) => /^[-+*/%<>=!&|^,(]$/.test(text);
  const intName = (text) => ints.has(text) || text === "int" || /^[iu]vec[234]$/.test(text);
  const depth = []; // brackets open before each token
  let brackets = 0;
  tokens.forEach((t, k) => {
    if (t.text === "]") brackets = Math.max(0, brackets - 1);
    depth[k] = brackets;
    if (t.text === "[") brackets++;
  });
  const closing = (k) => { // the ")" matching the "(" at k, or -1
    for (let j = k, open = 0; j < tokens.length; j++) {
      if (near(j) === "(") open++;
      else if (near(j) === ")" && --open === 0) return j;
    }
    return -1;
  };
  // A sign is unary after an operator, an opening bracket or the start of a statement.
  const unary = (k) => ["-", "+"].includes(near(k)) && (k === 0 || /^[-+*/%<>=!&|^,(?:{;[]$/.test(near(k - 1)) ||
    near(k - 1) === "return");
  // The end (exclusive) of an int operand starting at k (signs, an int literal or name,
  // int(...), or a bracketed int expression), or -1.
  const intOperand = (k) => {
    while (unary(k)) k++;
    const t = near(k);
    let end = -1;
    if (/^(?:\d+|0[xX][0-9a-fA-F]+)$/.test(t) || (ints.has(t) && near(k + 1) !== "(")) end = k + 1;
    else if (t === "int" && near(k + 1) === "(") end = closing(k + 1) + 1 || -1;
    else if (t === "(") {
      const close = closing(k);
      for (let j = k + 1; close > 0; j++) { // int operands joined by + - * / %
        const next = intOperand(j);
        if (next === close) end = close + 1;
        if (next < 0 || next === close || !ARITHMETIC.includes(near(next))) break;
        j = next;
      }
    }
    return end > 0 && !(near(end) === "." || near(end) === "[") ? end : -1;
  };
  const leftInt = (k) => operator(near(k - 1)) && (intName(near(k - 2)) || (near(k - 1) === "=" && intName(near(k - 3))) ||
    (["=", "<", ">", "!"].includes(near(k - 2)) && intName(near(k - 3))));
  const rightInt = (k) => operator(near(k)) && near(k) !== "," && near(k) !== "(" && intName(near(k + 1));
  const callOf = (k) => { // the function or constructor the token at k is an argument of
    for (let j = k - 1, open = 0; j >= 0; j--) {
      if (near(j) === ")") open++;
      else if (near(j) === "(" && open-- === 0) return near(j - 1);
      else if (near(j) === ";" || near(j) === "{") break;
    }
    return "";
  };
  const intContext = (first, end) => depth[first] > 0 || leftInt(first) || rightInt(end) || intName(callOf(first));
  // Int expressions with a division: their literals stay ints, the whole is converted.
  const kept = new Set();
  const wraps = [];
  for (let k = 0; k < tokens.length; k++) {
    const prev = near(k - 1);
    if (MULTIPLY.includes(prev) || (unary(k - 1) && k > 0)) continue; // (x * 1) / 4 is a float
    if (near(k) === "(" && /^[A-Za-z_]\w*$/.test(prev) && prev !== "return") continue; // a call's brackets
    let end = intOperand(k);
    let divides = false;
    while (end > 0 && MULTIPLY.includes(near(end))) {
      const next = intOperand(end + 1);
      if (next < 0) break;
      divides ||= near(end) !== "*";
      end = next;
    }
    if (!divides) continue;
    for (let j = k; j < end; j++) kept.add(j);
    if (!intContext(k, end)) wraps.push([k, end - 1]);
    k = end - 1;
  }
  const edits = []; // [offset, text inserted there]
  for (const [first, last] of wraps) {
    edits.push([tokens[first].at, "float("], [tokens[last].at + tokens[last].text.length, ")"]);
  }
  tokens.forEach((t, k) => {
    if (!/^\d+$/.test(t.text) || depth[k] || kept.has(k)) return;
    if (leftInt(k) || rightInt(k + 1) || intName(callOf(k))) return; // `k < 8`, `int(3)`, `3 * k`
    edits.push([t.at + t.text.length, ".0"]);
  });
  edits.sort((a, b) => b[0] - a[0]);
  for (const [at, text] of edits) code = `${code.slice(0, at)}${text}${code.slice(at)}`;
  return code;
}

/** The fragment shader for a .brdf model in `view`, as lab/brdf_explorer.assemble does it
 * (GLSL ES instead of the context's newest desktop GLSL). */
export function assembleBrdf(model, view, files, { target = "300es", preamble = "", enums = {}, constants } = {}) {
  const commonKey = "terms/common.glsl";
  const viewKey = `views/${view}.glsl`;
  if (!(viewKey in files)) throw new Error(`no view template shaders/${viewKey}`);
  const common = files[commonKey];
  const viewText = files[viewKey];
  preamble = preamble || (view === "sphere" ? "const int LIGHT_COUNT = 1;" : "");
  const code = floatLiterals(model.code);
  const host = names(DECLARATION, [preamble, common, HOST_BRDF, viewText].join("\n"));
  const fileNames = names(DECLARATION, code);
  for (const p of model.params) fileNames.add(p.name);
  const ours = new Set([...host].filter((n) => fileNames.has(n) && n !== "main" && n !== "BRDF"));
  const [hostOn, hostOff] = defines(ours, "lab_");
  const theirs = new Set([...names(FUNCTION, code)].filter((n) => BUILTINS.has(n)));
  theirs.add("BRDF");
  const [fileOn, fileOff] = defines(theirs, "explorer_");
  const source = new Source();
  source.add(VERSION_LINES[target].join("\n"), "<version>");
  source.add(glslDefines(constants), "<constants>");
  source.add(hostOn, "<host>");
  if (preamble) source.add(preamble, "<preamble>");
  source.add(common, `shaders/${commonKey}`);
  source.add(hostOff, "<host>");
  source.add(uniformDeclarations(model, enums).join("\n"), `${model.path} (parameters)`);
  source.add(fileOn, "<host>");
  const guarded = guardLoops(code);
  source.loops = guarded.lines.length;
  source.add(loopGuardPrelude(guarded.lines.length, constants.LOOP_LIMIT, constants), "<loop guard>");
  source.add(guarded.code, model.path, model.shaderLine);
  source.add(fileOff, "<host>");
  source.add(hostOn, "<host>");
  source.add(HOST_BRDF, "<host>");
  addView(source, viewText, `shaders/${viewKey}`, files);
  source.add(hostOff, "<host>");
  return source;
}

// Model file headers, parsed by the rules of shaders/README.md.
// This mirrors lab/models.py line for line (messages included); the fixture files in
// tests/fixtures/headers/ are checked against both, so the two parsers cannot drift.
// Why in JavaScript too: the page parses the files a student opens or edits, which never reach
// Python (the library's come parsed in the manifest).

export const PARAM_TYPES = ["float", "color", "bool", "enum"];
const IDENTIFIER = /^[A-Za-z_][A-Za-z0-9_]*$/;
// Python's float() syntax (digits may be grouped with single underscores).
const DIGITS = "\\d(?:_?\\d)*";
export const PY_FLOAT = new RegExp(
  `^[+-]?(?:(?:${DIGITS}(?:\\.(?:${DIGITS})?)?|\\.${DIGITS})(?:[eE][+-]?${DIGITS})?` +
    "|inf|infinity|nan)$",
  "i",
);

/** A problem in a model file, with where it happened (like lab.models.ModelError). */
export class ModelError extends Error {
  constructor(message, file = null, line = null) {
    const where = file && line ? `${file}:${line}: ` : file ? `${file}: ` : "";
    super(where + message);
    this.name = "ModelError";
    this.detail = message;
    this.file = file;
    this.line = line;
  }
}

/** Python's format(x, f".{digits}g"): `digits` significant digits, trailing zeros dropped,
 * an exponent of two digits at least; the page's one %g (its parity with Python is
 * tests/test_web_mirrors.py's). */
export function formatDigits(x, digits = 6) {
  if (!Number.isFinite(x)) return Number.isNaN(x) ? "nan" : x > 0 ? "inf" : "-inf";
  if (x === 0) return Object.is(x, -0) ? "-0" : "0";
  const sign = x < 0 ? "-" : "";
  const [mantissa, exponent] = roundSignificant(Math.abs(x), digits);
  const strip = (t) => (t.includes(".") ? t.replace(/0+$/, "").replace(/\.$/, "") : t);
  if (exponent < -4 || exponent >= digits) {
    const e = `${exponent < 0 ? "-" : "+"}${String(Math.abs(exponent)).padStart(2, "0")}`;
    return `${sign}${strip(mantissa[0] + (digits > 1 ? `.${mantissa.slice(1)}` : ""))}e${e}`;
  }
  if (exponent < 0) return sign + strip(`0.${"0".repeat(-exponent - 1)}${mantissa}`);
  const whole = mantissa.slice(0, exponent + 1);
  return sign + strip(exponent + 1 < digits ? `${whole}.${mantissa.slice(exponent + 1)}` : whole);
}

/** The exact decimal digits of x >= 0 ("0.125", "30000000000000000000000"), or null where
 * they run past 100 places (no tie can then fall within a double's digits). */
function exactDecimal(x) {
  if (x >= 1e21) return BigInt(x).toString();
  return Number.isInteger(x * 2 ** 100) ? x.toFixed(100) : null;
}

/** x > 0 to `digits` significant digits as Python rounds (an exact tie to the even digit,
 * where toExponential rounds it up): the digits, and the exponent of the first. */
function roundSignificant(x, digits) {
  const [m, e] = x.toExponential(digits - 1).split("e");
  const exact = exactDecimal(x);
  if (exact) {
    const point = exact.includes(".") ? exact.indexOf(".") : exact.length;
    const all = exact.replace(".", "");
    const lead = all.search(/[1-9]/);
    const kept = all.slice(lead, lead + digits).padEnd(digits, "0");
    if (/^50*$/.test(all.slice(lead + digits)) && Number(kept.slice(-1)) % 2 === 0) return [kept, point - lead - 1];
  }
  return [m.replace(".", ""), Number(e)];
}

/** Python's `format(x, "g")`: 6 significant digits. */
export const formatG = (x) => formatDigits(x, 6);

/** Python's format(x, f".{digits}f"): toFixed, but an exact tie goes to the even digit as
 * in Python (0.125 -> "0.12", 2.5 -> "2"), not away from zero. */
export function formatFixed(x, digits) {
  if (!Number.isFinite(x)) return Number.isNaN(x) ? "nan" : x > 0 ? "inf" : "-inf";
  const sign = x < 0 || Object.is(x, -0) ? "-" : "";
  const exact = exactDecimal(Math.abs(x));
  if (Math.abs(x) >= 1e21) return sign + exact + (digits ? `.${"0".repeat(digits)}` : "");
  let text = Math.abs(x).toFixed(digits);
  if (exact) {
    const [whole, fraction = ""] = exact.split(".");
    const kept = fraction.slice(0, digits);
    if (/^50*$/.test(fraction.slice(digits)) && Number((kept || whole).slice(-1)) % 2 === 0) {
      text = digits ? `${whole}.${kept}` : whole;
    }
  }
  return sign + text;
}

/** Python's str.format for the lab's sentences, templates that come from Python as data
 * (lab/grading/words.py): {name}, and {name:spec} with spec g, .Ng, .Nf or +.Nf. */
export function fill(template, values) {
  return template.replace(/\{(\w+)(?::([^}]*))?\}/g, (_, name, spec) => {
    if (!(name in values)) throw new Error(`fill: no value for {${name}} in "${template}"`);
    const value = values[name];
    if (spec === undefined) return String(value);
    const parts = /^(\+?)(?:\.(\d+))?([fg%])$/.exec(spec);
    if (!parts) throw new Error(`fill: the format spec "${spec}" of "${template}" is not one the page knows`);
    const digits = parts[2] === undefined ? 6 : Number(parts[2]);
    const text = parts[3] === "%" ? `${formatFixed(100 * value, digits)}%`
      : parts[3] === "f" ? formatFixed(value, digits) : formatDigits(value, Math.max(digits, 1));
    return parts[1] && !text.startsWith("-") ? `+${text}` : text;
  });
}

/** Python's repr() of a string (quotes chosen the way Python chooses them). */
export function pyRepr(text) {
  const quote = text.includes("'") && !text.includes('"') ? '"' : "'";
  let body = text.replace(/\\/g, "\\\\").replace(/\n/g, "\\n").replace(/\r/g, "\\r");
  body = body.replace(/\t/g, "\\t");
  if (quote === "'") body = body.replace(/'/g, "\\'");
  return quote + body + quote;
}

/** Python's str.splitlines() (no trailing empty line). */
export function splitLines(text) {
  // eslint-disable-next-line no-control-regex -- Python's str.splitlines() breaks at these too
  const lines = text.split(/\r\n|[\n\r\v\f\x1c-\x1e\x85\u2028\u2029]/);
  if (lines.length && lines[lines.length - 1] === "") lines.pop();
  return lines;
}

// Python's str.split() / str.strip() whitespace.
const pySplit = (text) => text.split(/\s+/).filter((t) => t.length > 0);
const pyStrip = (text) => text.replace(/^\s+|\s+$/g, "");

function number(token, what, path, line) {
  if (!PY_FLOAT.test(token)) {
    throw new ModelError(`${what} must be a number, not ${pyRepr(token)}`, path, line);
  }
  const value = Number(token.replace(/_/g, "").replace(/^([+-]?)inf(inity)?$/i, "$1Infinity"));
  if (!Number.isFinite(value)) {
    throw new ModelError(`${what} must be finite, not ${pyRepr(token)}`, path, line);
  }
  return value;
}

function partition(text, separator) {
  const at = text.indexOf(separator);
  return at < 0 ? [text, ""] : [text.slice(0, at), text.slice(at + separator.length)];
}

/** One `@param` line (without the `// @param` prefix). */
export function parseParam(text, path, line) {
  let [spec, doc] = partition(text, "|");
  const tokens = pySplit(spec);
  const usage = "write '@param NAME TYPE ... | meaning' (see shaders/README.md)";
  if (tokens.length < 2) throw new ModelError(`incomplete @param line: ${usage}`, path, line);
  const [name, kind, ...args] = tokens;
  if (!IDENTIFIER.test(name)) {
    throw new ModelError(`parameter name ${pyRepr(name)} is not a GLSL identifier`, path, line);
  }
  if (!PARAM_TYPES.includes(kind)) {
    throw new ModelError(
      `unknown parameter type ${pyRepr(kind)}: use one of ${PARAM_TYPES.join(", ")}`, path, line);
  }
  doc = pyStrip(doc);
  const base = { name, kind, doc, minimum: 0, maximum: 1, scale: "linear", choices: [], line };
  if (kind === "float") {
    if (args.length !== 3 && args.length !== 4) {
      throw new ModelError(
        `float parameter ${name}: write 'MIN MAX DEFAULT [linear|log]'`, path, line);
    }
    const [low, high, dflt] = args.slice(0, 3).map(
      (a) => number(a, `${name} range/default`, path, line));
    const scale = args.length === 4 ? args[3] : "linear";
    if (scale !== "linear" && scale !== "log") {
      throw new ModelError(
        `${name}: slider scale must be linear or log, not ${pyRepr(scale)}`, path, line);
    }
    if (!(low < high)) {
      throw new ModelError(
        `${name}: MIN (${formatG(low)}) must be below MAX (${formatG(high)})`, path, line);
    }
    if (!(low <= dflt && dflt <= high)) {
      throw new ModelError(
        `${name}: default ${formatG(dflt)} is outside [${formatG(low)}, ${formatG(high)}]`,
        path, line);
    }
    if (scale === "log" && low <= 0) {
      throw new ModelError(`${name}: a log slider needs MIN > 0`, path, line);
    }
    return { ...base, default: dflt, minimum: low, maximum: high, scale };
  }
  if (kind === "color") {
    if (args.length !== 3) {
      throw new ModelError(`color parameter ${name}: write 'R G B' (each 0..1)`, path, line);
    }
    const rgb = args.map((a) => number(a, `${name} channel`, path, line));
    if (rgb.some((c) => !(c >= 0 && c <= 1))) {
      throw new ModelError(`color parameter ${name}: channels must be in 0..1`, path, line);
    }
    return { ...base, default: rgb };
  }
  if (kind === "bool") {
    if (args.length !== 1 || (args[0] !== "0" && args[0] !== "1")) {
      throw new ModelError(`bool parameter ${name}: write 0 or 1 as the default`, path, line);
    }
    return { ...base, default: args[0] === "1" };
  }
  if (!args.length) {
    throw new ModelError(
      `enum parameter ${name}: list its choices (the first is the default)`, path, line);
  }
  for (const choice of args) {
    if (!IDENTIFIER.test(choice)) {
      throw new ModelError(
        `enum choice ${pyRepr(choice)} of ${name} is not an identifier`, path, line);
    }
  }
  if (new Set(args).size !== args.length) {
    throw new ModelError(`enum parameter ${name} lists a choice twice`, path, line);
  }
  return { ...base, default: args[0], choices: args };
}

/**
 * Parse a model file's header. `path` is the label used in messages (for library files
 * "shaders/brdfs/NAME.glsl"); `expectedName` is given for library files, whose @model
 * must match the file name. Returns a plain object shaped like lab.models.Model.
 */
// What a model's header may claim (@property), as lab/models.py's PROPERTIES.
export const PROPERTIES = ["reciprocal", "isotropic", "energy-conserving"];

export function parseModel(code, path, expectedName = null) {
  const stem = path.split("/").pop().replace(/\.[^.]*$/, "");
  const model = {
    name: expectedName || stem, path, code, title: "", formula: [], source: [],
    includes: [], params: [], delta: false, ambient: "", properties: [],
  };
  let named = false;
  let ambientLine = 0;
  const lines = splitLines(code);
  for (let index = 0; index < lines.length; index++) {
    const number = index + 1;
    const stripped = pyStrip(lines[index]);
    if (!stripped) continue;
    if (!stripped.startsWith("//")) break; // the header ends at the first line of code
    const body = pyStrip(stripped.slice(2));
    if (!body.startsWith("@")) continue;
    let [keyword, rest] = partition(body.slice(1), " ");
    rest = pyStrip(rest);
    if (keyword === "model") {
      if (!IDENTIFIER.test(rest)) {
        throw new ModelError(`@model name ${pyRepr(rest)} is not an identifier`, path, number);
      }
      model.name = rest;
      named = true;
    } else if (keyword === "title") model.title = rest;
    else if (keyword === "formula") model.formula.push(rest);
    else if (keyword === "source") model.source.push(rest);
    else if (keyword === "include") model.includes.push(rest);
    else if (keyword === "delta") model.delta = true;
    else if (keyword === "ambient") {
      model.ambient = rest;
      ambientLine = number;
    } else if (keyword === "property") {
      for (const word of pySplit(rest)) {
        if (!PROPERTIES.includes(word)) {
          throw new ModelError(
            `@property ${word}: unknown property; use ${PROPERTIES.join(", ")}`, path, number);
        }
        if (!model.properties.includes(word)) model.properties.push(word);
      }
    } else if (keyword === "param") {
      const param = parseParam(rest, path, number);
      if (model.params.some((p) => p.name === param.name)) {
        throw new ModelError(`parameter ${param.name} is declared twice`, path, number);
      }
      model.params.push(param);
    } else {
      throw new ModelError(
        `unknown header keyword @${keyword}: use @model, @title, @formula, @source, ` +
          "@include, @delta, @ambient, @property or @param", path, number);
    }
  }
  if (ambientLine) {
    const param = model.params.find((p) => p.name === model.ambient);
    if (!param || param.kind !== "color") {
      throw new ModelError(
        `@ambient ${model.ambient}: name a color parameter of this model ` +
          "(declared with '@param NAME color R G B')", path, ambientLine);
    }
  }
  if (named && expectedName && model.name !== expectedName) {
    throw new ModelError(
      `@model ${model.name} does not match the file name ${path.split("/").pop()}`, path, 1);
  }
  return model;
}

/** Parameter defaults as a {name: value} object. */
export function defaults(model) {
  return Object.fromEntries(model.params.map((p) => [p.name, structuredClone(p.default)]));
}

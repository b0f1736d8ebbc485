// A student's submission as a model every view renders, as lab/grading/exercise.py's
// build_model makes it: the required functions checked against the grader's signatures,
// a sampler exercise's functions made the library model's sampler, a wrapper's text put in
// front of its wrapper model; tests/test_web_exercise.py runs it on the stubs and solutions.
// Why in JavaScript too: practice mode runs in the page alone (the student's text never
// reaches Python).
import { ModelError, parseModel } from "./header.js";

const COMMENTS = /\/\/[^\n]*|\/\*[\s\S]*?\*\//g;
const SIGNATURE = /\b(\w+)\s+(\w+)\s*\(([^()]*)\)\s*\{/g;
const QUALIFIERS = ["in", "const", "highp", "mediump", "lowp"];

function types(params) {
  const out = [];
  for (const part of params.split(",")) {
    const words = part.split(/\s+/).filter((w) => w && !QUALIFIERS.includes(w));
    if (words.length && !(words.length === 1 && words[0] === "void")) {
      out.push(words.length > 1 ? words.slice(0, -1).join(" ") : words[0]);
    }
  }
  return out;
}

/** Each required function is defined with the grader's signature (check_functions). */
export function checkFunctions(code, required, label) {
  const stripped = code.replace(COMMENTS, (m) => m.replace(/[^\n]/g, " "));
  const defined = {};
  for (const match of stripped.matchAll(SIGNATURE)) {
    const [, ret, name, params] = match;
    if (["if", "for", "while", "return", "else"].includes(ret) || name in defined) continue;
    defined[name] = [ret, types(params), stripped.slice(0, match.index).split("\n").length];
  }
  for (const signature of required) {
    const [, ret, name, params] = new RegExp(SIGNATURE.source).exec(`${signature} {`);
    if (!(name in defined)) {
      const close = Object.keys(defined).find((n) => n.toLowerCase() === name.toLowerCase());
      const hint = close ? ` (you defined ${close}: check the spelling)` : "";
      throw new ModelError(`function ${name} is missing${hint}; define ${signature}`, label);
    }
    const [gotRet, gotTypes, line] = defined[name];
    if (gotRet !== ret || gotTypes.join(",") !== types(params).join(",")) {
      throw new ModelError(`${gotRet} ${name}(${gotTypes.join(", ")}) has the wrong signature; the grader calls ${signature}`, label, line);
    }
  }
}

const SAMPLING = "terms/sampling.glsl"; // what a sampler exercise is given (PI, to_world, ...)
// The student's functions as the model's sampler (lab/ibl/integrator.py LOBE_SAMPLER).
const LOBE_SAMPLER = `
const bool HAS_SAMPLER = true;
vec3 SAMPLE_BRDF(vec3 V, vec3 N, vec3 X, vec3 Y, vec3 u) { return sample_lobe(u.xy, V, N, X, Y); }
float PDF_BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) { return pdf_lobe(L, V, N, X, Y); }`;

/** The student's text as a model every view renders, named after the exercise. */
export function buildSubmission(exercise, text, path, models) {
  checkFunctions(text, exercise.functions, path);
  // As the grader's: its cos, and the exercise's loop limit (exercise.toml's loop_limit).
  return { ...submission(exercise, text, path, models), exactTrig: true, loopLimit: exercise.loop_limit };
}

function submission(exercise, text, path, models) {
  if (exercise.sampler_for) {
    // A sampler: the library model with the student's functions in front and made its
    // sampler, for the sampling views (ibl_sample, ibl_pdf) of sampling.js. An estimator
    // (exercise.estimator): the student's estimate between the grader's two texts, with a
    // stand-in for the environment map the page's other views lack (lab/web/exercises.py).
    const model = models[exercise.sampler_for];
    const includes = model.includes.includes(SAMPLING) ? model.includes : [...model.includes, SAMPLING];
    const estimator = exercise.estimator;
    const [line, host] = estimator ? [estimator.line, estimator.host + estimator.stand_in] : ["", LOBE_SAMPLER];
    return { ...model, name: exercise.name, path, code: `${line}${text.replace(/\n+$/, "")}\n${model.code}${host}`, includes,
      studentLines: text.split("\n").length };
  }
  if (exercise.wrapper) {
    const wrapper = models[exercise.wrapper];
    return { ...wrapper, name: exercise.name, path, code: `${text.replace(/\n+$/, "")}\n${wrapper.code}`,
      includes: wrapper.includes.filter((i) => i !== exercise.replaces), studentLines: text.split("\n").length };
  }
  const model = { ...parseModel(text, path), name: exercise.name };
  // The grader sets the stub's parameters; a default changed to try things out costs nothing.
  const stub = parseModel(exercise.stub, path);
  model.params = model.params.map((p) => {
    const given = stub.params.find((q) => q.name === p.name);
    return given ? { ...p, default: given.default } : p;
  });
  // Checks that link the file with a model of their own (kinds/properties.py) leave its
  // includes out: the panel compiles it with the stub's (a stand-in for what is linked).
  if (exercise.checks.some((c) => c.linked_with)) model.includes = stub.includes;
  return model;
}

// Practice mode of a `properties` check (exercise 11: the student's tests of a BRDF's
// energy conservation and reciprocity), as lab/grading/kinds/properties.py runs it: the
// student's file linked with the check's model (a library model, or a file of the exercise
// carried in exercises.json) after it, both tests run in the grader's view
// (shaders/views/grade_properties.glsl) at the grader's rows and turned frame, and the
// values compared with the grader's own measurement of that model (exercises.json carries
// it: the committed reference's second row), with the kind's tolerances, verdicts, messages
// and likely mistakes (nearest, explain).
// Why in JavaScript too: practice mode checks the student's text in the browser, which never
// reaches Python; tests/test_web_practice.py holds the two to the same verdicts and words.
import { floatTexture } from "./assemble.js";
import { defaults, fill, formatDigits, parseModel } from "./header.js";
import { sentence } from "./diagnosis.js";
import { el } from "./dom.js";

const VIEW = "grade_properties";
const RAD = Math.PI / 180;

/** The model the check's tests run on: a library model by name, or the exercise's file. */
function target(check, models) {
  const linked = check.linked_with;
  if (linked.source === undefined) {
    const model = models[linked.name];
    if (!model) throw new Error(`the page has no model ${linked.name} to run the tests on`);
    return model;
  }
  check.targetModel ??= parseModel(linked.source, linked.path, linked.name);
  return check.targetModel;
}

/** The student's tests with the target's BRDF after them (properties.linked): the prototype
 * on the first line keeps the file's own line numbers; the target's includes and parameters. */
export function linkedModel(check, submission, models) {
  const model = target(check, models);
  const text = submission.code;
  const code = check.prototype + text.replace(/\n+$/, "") + "\n" + model.code;
  return { ...model, name: submission.name, path: submission.path, code, exactTrig: true,
    loopLimit: submission.loopLimit, studentLines: text.replace(/\n+$/, "").split("\n").length,
    targetPath: model.path };
}

/** Compile errors past the student's last line belong to the target's file (_from_target). */
export function fromTarget(err, linked) {
  if (!err.errors) return err;
  for (const e of err.errors) {
    if (e.file === linked.path && e.line > linked.studentLines) {
      e.file = linked.targetPath;
      e.line -= linked.studentLines;
      e.message += " (the model your tests run on is linked after your file: rename your function or global if " +
        "the model defines the same name)";
    }
  }
  err.message = err.errors.map((e) => `${e.file}:${e.line}: ${e.message}`).join("\n");
  return err;
}

/** Rows outside the tolerance of the grader's measurement (NaN and Inf are): _off. */
function off(check, got, truth) {
  return truth.map((t, k) => !(Math.abs(got[k] - t) <= check.atol + check.rtol * Math.abs(t)));
}

const finite = (x) => (Number.isNaN(x) ? 0 : x); // np.nan_to_num(nan=0): infinities stay large

/** What values say of the model on the rows clear of the thresholds: verdicts(). */
export function verdicts(check, values, truth) {
  const n = check.options.albedo_rows;
  const tol = truth.map((t) => 2 * (check.atol + check.rtol * Math.abs(t)));
  let gain = false;
  let broken = false;
  truth.forEach((t, k) => {
    const v = finite(values[k]);
    if (k < n) gain ||= Math.abs(t - 1) > tol[k] && v > 1;
    else broken ||= (t > check.reciprocal + tol[k] || t < check.reciprocal - tol[k]) && v > check.reciprocal;
  });
  const W = check.words;
  return [gain ? W.gains : W.conserves, broken ? W.not_reciprocal : W.reciprocal];
}

const deg0 = (row) => row.map((a) => `${a.toFixed(0)}°`).join(", ");
const g4 = (x) => formatDigits(x, 4);

/** The verdict on the student's values `got` (compare()): {passed, message, off}. */
export function compareProperties(check, got, truth) {
  const W = check.words; // lab/grading/words.py PROPERTIES
  const n = check.options.albedo_rows;
  const rows = check.rows;
  const wrong = off(check, got, truth);
  const mine = verdicts(check, got, truth);
  const real = verdicts(check, truth, truth);
  const found = fill(W.found, { energy: real[0], reciprocity: real[1] });
  const same = mine[0] === real[0] && mine[1] === real[1];
  if (!wrong.some(Boolean) && same) {
    const albedo = Math.max(...truth.slice(0, n));
    const largest = truth.length > n ? fill(W.largest_error, { albedo, error: Math.max(...truth.slice(n)) })
      : fill(W.largest, { albedo });
    return { passed: true, message: fill(W.passes, { found, largest }), off: wrong };
  }
  const parts = [];
  const albedoOff = wrong.slice(0, n);
  if (albedoOff.some(Boolean)) {
    const k = albedoOff.indexOf(true);
    parts.push(fill(W.albedo_off, { count: albedoOff.filter(Boolean).length, n, theta: rows[k][2], got: got[k],
      truth: truth[k] }));
  }
  const pairsOff = wrong.slice(n);
  if (pairsOff.some(Boolean)) {
    const k = n + pairsOff.indexOf(true);
    const [tl, pl, tv, pv] = rows[k];
    parts.push(fill(W.pairs_off, { count: pairsOff.filter(Boolean).length, n: truth.length - n, tl, pl, tv, pv,
      got: got[k], truth: truth[k] }));
  }
  if (!same) parts.push(fill(W.verdicts_off, { energy: mine[0], reciprocity: mine[1], found }));
  return { passed: false, message: parts.join("; "), off: wrong };
}

/** The stored mistakes whose values the student's match at every row (nearest's), each with
 * its largest distance in tolerances. */
function matches(check, got, candidates) {
  const n = got.length;
  const out = [];
  for (const [key, other] of Object.entries(candidates)) {
    if (other.length !== 2 * n) continue;
    let worst = 0;
    for (let k = 0; k < n; k++) {
      const g = Number.isNaN(got[k]) ? Infinity : got[k];
      const d = Math.abs(g - other[k]) / (check.atol + check.rtol * Math.abs(other[k]));
      worst = Number.isNaN(d) ? Infinity : Math.max(worst, d);
    }
    if (worst <= 1) out.push({ key, off: worst });
  }
  return out;
}

// Two stored mistakes that give the same values on a model (Lambert's albedo cannot tell a
// missing sin θ from a missing cos θ) are told apart by the grader at distance 0 against
// about 1e-5: the same program on the same GPU. The page's values differ from the grader's
// by float rounding, so within NOISE it takes the one that matches at the most checks.
const NOISE = 1e-3;

const spread = (xs) => Math.max(...xs) - Math.min(...xs); // np.ptp (NaN when any is)

/** A test that gives one value whatever it measures, or values its definition rules out
 * (explain()): a phrase, or "". */
function explainValues(check, got, truth) {
  const W = check.words;
  const n = check.options.albedo_rows;
  const said = [];
  for (const [what, part, real] of [["directional_albedo", got.slice(0, n), truth.slice(0, n)],
    ["reciprocity_error", got.slice(n), truth.slice(n)]]) {
    const tol = Math.max(...real.map((t) => check.atol + check.rtol * Math.abs(t)));
    if (part.length > 1 && spread(part) === 0 && spread(real) > tol) said.push(fill(W.same_value, { what, value: part[0] }));
  }
  if (said.length) return fill(W.constant, { said: said.join("; ") });
  const errors = got.slice(n).map(finite);
  if (errors.some((e) => e < -1e-6)) return W.negative_error;
  if (errors.some((e) => e > 1 + 1e-4)) {
    return fill(W.error_above_one, { value: Math.max(...errors.map((e) => (e === Infinity ? Number.MAX_VALUE : e))) });
  }
  if (got.slice(0, n).map(finite).some((a) => a < -1e-6)) return W.negative_albedo;
  return check.channels ? reduction(check, n, got, check.channels) : "";
}

// properties.REDUCTIONS: the ways a test may reduce its channels besides the largest
// (luminance with the check's `luma`, the lab's one copy of the weights).
const REDUCTIONS = {
  smallest: (c) => Math.min(...c),
  mean: (c) => (c[0] + c[1] + c[2]) / 3,
  red: (c) => c[0],
  green: (c) => c[1],
  blue: (c) => c[2],
  luminance: (c, luma) => luma[0] * c[0] + luma[1] * c[1] + luma[2] * c[2],
};

/** properties.reduction: a part whose values are another reduction of the grader's
 * measurement per channel than the largest, at every row. */
function reduction(check, n, got, channels) {
  const W = check.words;
  const near = (part, values) => part.every((x, k) => Math.abs(x - values[k]) <= check.atol + check.rtol * Math.abs(values[k]));
  const said = [];
  for (const [what, part, per] of [["directional_albedo", got.slice(0, n), channels.slice(0, n)],
    ["reciprocity_error", got.slice(n), channels.slice(n)]]) {
    if (!part.length || !part.every(Number.isFinite)) continue;
    if (near(part, per.map((c) => Math.max(...c)))) continue;
    const alike = Object.entries(REDUCTIONS).filter(([, reduce]) => near(part, per.map((c) => reduce(c, check.luma))))
      .map(([name]) => W[`by_${name}`]);
    if (alike.length) said.push(fill(W.reduced, { what, reduction: alike.join(" or ") }));
  }
  return said.length ? fill(W.reduction, { said: said.join("; ") }) : "";
}

/** Does the program agree with stored mistake `key` at every other properties check where
 * that mistake fails (Explainer.elsewhere)? One subject can make two mistakes agree. */
function agreesElsewhere(r, key, results) {
  return results.every((o) => {
    const theirs = o.check.stored?.candidates?.[key];
    if (o === r || o.check.kind !== "properties" || !o.got || !theirs) return true;
    const n = o.got.length;
    const [values, truth] = [theirs.slice(0, n), theirs.slice(n)];
    const mine = verdicts(o.check, values, truth);
    const real = verdicts(o.check, truth, truth);
    const fails = off(o.check, values, truth).some(Boolean) || mine[0] !== real[0] || mine[1] !== real[1];
    if (!fails) return true; // the mistake passes there: that check cannot tell
    return matches(o.check, o.got, { [key]: theirs }).length > 0;
  });
}

/** The grader's "Likely: ..." for each failed properties check of `results` (one run of
 * every check of the exercise), from the stored mistakes (committed mode), added to its
 * message: nearest(), or explain() when no stored mistake matches. */
export function diagnoseProperties(exercise, results) {
  const hints = exercise.hints || {};
  const failed = results.filter((r) => r.check.kind === "properties" && r.got && !r.passed);
  const found = new Map(failed.map((r) => {
    const candidates = Object.entries(r.check.stored?.candidates || {}).filter(([k]) => k in hints);
    return [r, matches(r.check, r.got, Object.fromEntries(candidates))];
  }));
  const count = (key) => [...found.values()].filter((list) => list.some((m) => m.key === key)).length;
  for (const r of failed) {
    const list = found.get(r);
    const best = Math.min(...list.map((m) => m.off));
    const close = list.filter((m) => m.off <= best + NOISE);
    close.sort((a, b) => count(b.key) - count(a.key) || a.off - b.off);
    const key = close.length && agreesElsewhere(r, close[0].key, results) ? close[0].key : null;
    const likely = sentence(key ? hints[key] : explainValues(r.check, r.got, r.truth));
    if (likely) r.message += `. ${likely}`;
  }
}

/** Where row k is, in words (where()): for a loop the guard stopped there. */
function rowWords(check, k) {
  const [tl, pl, tv, pv] = check.rows[Math.min(k, check.rows.length - 1)];
  if (k < check.options.albedo_rows) return fill(check.words.albedo_at, { theta: tv });
  return fill(check.words.pair_at, { tl, pl, tv, pv });
}

/** Runs the check on `panel` with the student's `submission` linked to its model: {passed,
 * message, got, truth, off}, or {loop: where} when the loop guard stopped a loop. */
export function runProperties(panel, check, submission = panel.model) {
  const linked = linkedModel(check, submission, panel.lab.models);
  const rows = check.rows;
  const width = Math.min(rows.length, 1024);
  const height = Math.ceil(rows.length / width);
  const data = new Float32Array(4 * width * height);
  rows.forEach((row, k) => data.set(row.map((a) => a * RAD), 4 * k));
  for (let k = 0; k < check.options.albedo_rows; k++) data[4 * k] = -1;
  const gl = panel.gl;
  const texture = floatTexture(gl, width, height, data);
  const saved = [panel.model, panel.programs, panel.values];
  // The linked program is compiled once per text and check, beside the panel's own.
  if (check.linkedCode !== linked.code) [check.linkedCode, check.programs] = [linked.code, new Map()];
  panel.model = linked;
  panel.programs = check.programs;
  panel.values = { ...defaults(linked), ...check.params };
  let out;
  try {
    const [X, Y, N] = check.frame;
    out = panel.run(VIEW, width, height, { u_rows: 0, u_X: X, u_Y: Y, u_N: N }, { textures: [texture] });
  } catch (err) {
    throw fromTarget(err, linked);
  } finally {
    [panel.model, panel.programs, panel.values] = saved;
    gl.deleteTexture(texture);
  }
  if (panel.lastLoop) return { loop: rowWords(check, panel.lastLoop.y * 1024 + panel.lastLoop.x), line: panel.lastLoop.line };
  const got = rows.map((_, k) => out[4 * k]);
  const truth = check.truth;
  return { ...compareProperties(check, got, truth), got, truth }; // diagnosed by diagnoseProperties
}

const SHOWN_PAIRS = 8; // PropertiesKind.SHOWN_PAIRS: reciprocity rows shown, failing first

/** The grader's report table of a check (figures()): the albedo rows and a few reciprocity
 * pairs, yours beside the grader's, each marked in words (not colour alone). */
function valuesTable({ check, got, truth, off }) {
  const n = check.options.albedo_rows;
  let pairs = off.map((bad, k) => (bad && k >= n ? k : -1)).filter((k) => k >= 0).slice(0, SHOWN_PAIRS);
  if (!pairs.length && truth.length > n) {
    const rest = truth.slice(n);
    pairs = [n + rest.indexOf(Math.max(...rest))];
  }
  const rows = [...Array(n).keys(), ...pairs].map((k) => {
    const row = check.rows[k];
    const what = k < n ? `directional_albedo, θV = ${row[2].toFixed(1)}°`
      : `reciprocity_error, (θL, φL, θV, φV) = (${deg0(row)})`;
    return [what, g4(got[k]), g4(truth[k]), off[k] ? "✗ differs" : "✓"];
  });
  const hidden = off.filter((bad, k) => bad && k >= n).length - pairs.filter((k) => off[k]).length;
  return { head: ["row", "yours", "grader's", "within tolerance"], rows,
    caption: `your tests' values beside the grader's measurement of the same model${hidden > 0 ? ` (${hidden} more pairs differ)` : ""}` };
}

/** The table of a checked result as a figure: a labelled region of its own that scrolls (by
 * keyboard too) on a narrow screen. */
export function valuesFigure(result) {
  const table = valuesTable(result);
  const name = result.check.name;
  const cells = (tag, texts, extra = {}) => texts.map((t) => el(tag, extra, t));
  return el("figure", { class: "exercise-table", "data-check": name },
    el("div", { class: "scroll", tabindex: "0", role: "region", "aria-label": `${name}: your values and the grader's` },
      el("table", {}, el("thead", {}, el("tr", {}, ...cells("th", table.head, { scope: "col" }))),
        el("tbody", {}, ...table.rows.map((row) => el("tr", {}, ...cells("td", row)))))),
    el("figcaption", {}, `${name}: ${table.caption}`));
}

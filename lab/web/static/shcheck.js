// Practice mode of an `sh` check (exercise 15: the student's real spherical harmonics and the
// SH projection of a BRDF lobe), as lab/grading/kinds/sh.py runs it: the student's file
// linked with the check's library model after it (properties.js's linkedModel, as the grader's
// properties.linked), run in the grader's view (shaders/views/grade_sh.glsl) at the grader's
// rows, and the values compared with the lab's own (exercises.json carries them: the committed
// reference's second row, real_sh for a basis check and the lab's projection for a lobe),
// with the kind's tolerances, verdicts, messages and likely mistakes (nearest, explain).
// Why in JavaScript too: practice mode checks the student's text in the browser, which never
// reaches Python; tests/test_web_sh_practice.py holds the two to the same verdicts, words and
// rows (the rows are expanded here from the check's directions as sh.py's _rows expands them).
import { floatTexture } from "./assemble.js";
import { defaults, fill } from "./header.js";
import { sentence } from "./diagnosis.js";
import { fromTarget, linkedModel } from "./properties.js";
import { el } from "./dom.js";

const VIEW = "grade_sh";
const RAD = Math.PI / 180;

/** (n, 4) rows l, m, theta, phi (degrees): every (l, m) up to the order at each of the
 * check's directions, index l^2 + l + m within a direction (sh.py _rows, lm_pairs). */
export function shRows(check) {
  if (check.rows) return check.rows;
  const order = check.options.order;
  const out = [];
  for (const [theta, phi] of check.directions) {
    for (let l = 0; l <= order; l++) for (let m = -l; m <= l; m++) out.push([l, m, theta, phi]);
  }
  check.rows = out;
  return out;
}

/** Channels the page keeps per row: a basis check's three are one value (vec3(sh_basis)). */
const channels = (check) => (check.project ? 3 : 1);
const at = (check, values, k, c) => values[channels(check) * k + Math.min(c, channels(check) - 1)];

/** Rows where some channel of `got` is outside the tolerance of `truth` (_off): NaN is. */
function off(check, got, truth) {
  const n = shRows(check).length;
  const out = new Array(n).fill(false);
  for (let k = 0; k < n; k++) {
    for (let c = 0; c < channels(check); c++) {
      const t = at(check, truth, k, c);
      const g = Number.isNaN(at(check, got, k, c)) ? Infinity : at(check, got, k, c);
      if (!(Math.abs(g - t) <= check.atol + check.rtol * Math.abs(t))) out[k] = true;
    }
  }
  return out;
}

const clamp30 = (x) => (Number.isNaN(x) ? 1e30 : Math.max(-1e30, Math.min(1e30, x))); // nan_to_num(1e30)

/** The largest relative L2 distance over the incidences between the lobes rebuilt from `got`
 * and `truth` (lobe_error): by Parseval, the coefficients' own distance. */
function lobeError(check, got, truth) {
  if (!check.project) return 0;
  const count = (check.options.order + 1) ** 2;
  const n = shRows(check).length;
  let worst = 0;
  for (let start = 0; start < n; start += count) {
    let a = 0;
    let b = 0;
    for (let i = 3 * start; i < 3 * Math.min(start + count, n); i++) {
      a += (clamp30(got[i]) - truth[i]) ** 2;
      b += truth[i] ** 2;
    }
    worst = Math.max(worst, Math.sqrt(a) / Math.max(Math.sqrt(b), 1e-30));
  }
  return Math.min(worst, 10);
}

/** The verdict on the student's values `got` (compare()): {passed, message, off}. */
export function compareSh(check, got, truth) {
  const W = check.words; // lab/grading/words.py SH
  const rows = shRows(check);
  const wrong = off(check, got, truth);
  const error = lobeError(check, got, truth);
  const k = wrong.indexOf(true);
  if (k < 0) {
    if (check.project) return { passed: true, message: fill(W.coefficients_pass, { error }), off: wrong };
    const largest = Math.max(...truth.map(Math.abs));
    return { passed: true, message: fill(W.basis_passes, { n: rows.length, largest }), off: wrong };
  }
  let c = 0; // np.argmax of |got - truth| over the channels: the first NaN, else the largest
  for (let i = 0, best = -1; i < channels(check); i++) {
    const d = Math.abs(at(check, got, k, i) - at(check, truth, k, i));
    if (Number.isNaN(d)) { c = i; break; }
    if (d > best) [best, c] = [d, i];
  }
  const [l, m, theta, phi] = rows[k];
  const said = { count: wrong.filter(Boolean).length, n: rows.length, l, m, theta, phi,
    got: at(check, got, k, c), truth: at(check, truth, k, c), error };
  return { passed: false, message: fill(W[check.project ? "coefficients_off" : "basis_off"], said), off: wrong };
}

/** The stored mistake whose values the student's match at every row, the closest (nearest):
 * one that moves a single harmonic alone is no evidence of which mistake it is. */
function nearest(check, got, candidates, truth) {
  const rows = shRows(check);
  let best = null;
  let bestOff = Infinity;
  for (const [key, other] of Object.entries(candidates)) {
    if (other.length !== got.length) continue;
    const moved = new Set(off(check, other, truth).flatMap((bad, k) => (bad ? [`${rows[k][0]},${rows[k][1]}`] : [])));
    if (moved.size < 2) continue;
    let worst = 0;
    for (let i = 0; i < got.length; i++) {
      const g = Number.isNaN(got[i]) ? Infinity : got[i];
      const d = Math.abs(g - other[i]) / (check.atol + check.rtol * Math.abs(other[i]));
      worst = Number.isNaN(d) ? Infinity : Math.max(worst, d);
    }
    if (worst <= 1 && worst < bestOff) [best, bestOff] = [key, worst];
  }
  return best;
}

/** Values the lab's up to a sign on a family of (l, m), or up to one factor (explain()). */
function explainValues(check, got, truth) {
  const W = check.words;
  const rows = shRows(check);
  // np.nan_to_num: NaN is 0, the infinities the largest floats
  const mine = Array.from(got, (x) => (Number.isNaN(x) ? 0 : Math.max(-Number.MAX_VALUE, Math.min(Number.MAX_VALUE, x))));
  const tol = truth.map((t) => check.atol + check.rtol * Math.abs(t));
  const bad = off(check, mine, truth);
  const sameSize = mine.every((x, i) => Math.abs(Math.abs(x) - Math.abs(truth[i])) <= tol[i]);
  const n = channels(check);
  if (sameSize && bad.some(Boolean)) {
    const families = {
      "m is odd": ([, m]) => m % 2 !== 0,
      "m < 0": ([, m]) => m < 0,
      "m > 0": ([, m]) => m > 0,
      "l is odd": ([l]) => l % 2 !== 0,
      "l + |m| is odd": ([l, m]) => (l + Math.abs(m)) % 2 !== 0,
    };
    const flipped = bad.map((b, k) => b && truth.slice(n * k, n * k + n).some((t, c) => Math.abs(t) > tol[n * k + c]));
    for (const [where, family] of Object.entries(families)) {
      if (flipped.some(Boolean) && !flipped.some((f, k) => f && !family(rows[k]))) return fill(W.sign_only, { where });
    }
  }
  const big = truth.flatMap((t, i) => (Math.abs(t) > 10 * tol[i] ? [i] : []));
  if (big.length >= 3) {
    const ratios = big.map((i) => mine[i] / truth[i]).sort((a, b) => a - b);
    const h = ratios.length >> 1;
    const factor = ratios.length % 2 ? ratios[h] : (ratios[h - 1] + ratios[h]) / 2; // np.median
    const close = mine.every((x, i) => Math.abs(x - factor * truth[i]) <= 2 * tol[i] * Math.max(1, Math.abs(factor)));
    // a factor near 0 is values that are all but zero (a stub's): no factor to name
    if (Math.abs(factor - 1) > 0.01 && Math.abs(factor) > 0.01 && close) return fill(W.scaled, { factor });
  }
  return "";
}

/** The grader's "Likely: ..." for each failed sh check of `results`, from the stored mistakes
 * (committed mode), added to its message: nearest(), or explain() when none matches. The
 * grader also reads where in the code the fault is (its trace), which the page cannot. */
export function diagnoseSh(exercise, results) {
  const hints = exercise.hints || {};
  for (const r of results.filter((x) => x.check.kind === "sh" && x.got && !x.passed)) {
    const stored = Object.entries(r.check.stored?.candidates || {}).filter(([key]) => key in hints);
    const key = nearest(r.check, r.got, Object.fromEntries(stored), r.truth);
    const likely = sentence(key ? hints[key] : explainValues(r.check, r.got, r.truth));
    if (likely) r.message += `. ${likely}`;
  }
}

/** Where row k is, in words (where()): for a loop the guard stopped there. */
function rowWords(check, k) {
  const rows = shRows(check);
  const [l, m, theta, phi] = rows[Math.min(k, rows.length - 1)];
  return fill(check.words[check.project ? "coefficient_at" : "basis_at"], { l, m, theta, phi });
}

/** Runs the check on `panel` with the student's `submission` linked to its model: {passed,
 * message, got, truth, off}, or {loop: where} when the loop guard stopped a loop. */
export function runSh(panel, check, submission = panel.model) {
  const linked = linkedModel(check, submission, panel.lab.models);
  const rows = shRows(check);
  const width = Math.min(rows.length, 1024);
  const height = Math.ceil(rows.length / width);
  const data = new Float32Array(4 * width * height);
  rows.forEach(([l, m, theta, phi], k) => data.set([l, m, theta * RAD, phi * RAD], 4 * k));
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
    out = panel.run(VIEW, width, height, { u_rows: 0, u_project: check.project ? 1 : 0 }, { textures: [texture] });
  } catch (err) {
    throw fromTarget(err, linked);
  } finally {
    [panel.model, panel.programs, panel.values] = saved;
    gl.deleteTexture(texture);
  }
  if (panel.lastLoop) return { loop: rowWords(check, panel.lastLoop.y * 1024 + panel.lastLoop.x), line: panel.lastLoop.line };
  const n = channels(check);
  const got = new Float32Array(n * rows.length);
  rows.forEach((_, k) => { for (let c = 0; c < n; c++) got[n * k + c] = out[4 * k + c]; });
  const truth = check.truth;
  return { ...compareSh(check, got, truth), got, truth }; // diagnosed by diagnoseSh
}

const SHOWN = 12; // SHKind.SHOWN: rows in the report's table, the failing ones first
const largest = (check, values, k) => Math.max(...Array.from({ length: channels(check) }, (_, c) => at(check, values, k, c)));

/** The grader's report table of a failed check (figures()): a few rows, yours beside the
 * lab's (largest channel), each marked in words (not colour alone), in a labelled region of
 * its own that scrolls (by keyboard too) on a narrow screen. */
export function shFigure({ check, got, truth, off: wrong }) {
  const failing = wrong.flatMap((bad, k) => (bad ? [k] : []));
  const shown = (failing.length ? failing : [...wrong.keys()]).slice(0, SHOWN);
  const g4 = (x) => fill("{x:.4g}", { x });
  const rows = shown.map((k) => {
    const [l, m, theta, phi] = shRows(check)[k];
    return [fill("({l}, {m}) at ({theta:.1f}°, {phi:.1f}°)", { l, m, theta, phi }), g4(largest(check, got, k)),
      g4(largest(check, truth, k)), wrong[k] ? "✗ differs" : "✓"];
  });
  const more = failing.length > shown.length ? ` (${failing.length - shown.length} more rows differ)` : "";
  const cells = (tag, texts, extra = {}) => texts.map((t) => el(tag, extra, t));
  const name = check.name;
  return el("figure", { class: "exercise-table", "data-check": name },
    el("div", { class: "scroll", tabindex: "0", role: "region", "aria-label": `${name}: your values and the lab's` },
      el("table", {}, el("thead", {}, el("tr", {}, ...cells("th", ["(l, m) at (θ, φ)", "yours", "lab's",
        "within tolerance"], { scope: "col" }))),
      el("tbody", {}, ...rows.map((row) => el("tr", {}, ...cells("td", row)))))),
    el("figcaption", {}, `${name}: your values beside the lab's (largest channel)${more}`));
}

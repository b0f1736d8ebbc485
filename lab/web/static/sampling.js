// Exercise 10's sampling checks in the page (practice): the chi-square test of the student's
// samples against their own pdf, and the pdf's integral over the sphere, computed as
// lab/grading/sampling.py and lab/ibl/chisquare.py compute them. The samples come from the
// same view template (shaders/views/ibl_sample.glsl) with the same random numbers (the
// PCG of terms/sampling.glsl, seeded by texel and seed), in the same turned frames
// (exercises.json carries them from the grader's code); the pdf is integrated per bin by
// the same adaptive quadrature over ibl_pdf.glsl. The IBL render check is iblcheck.js's.
// The bins, thresholds and sentences are the grader's (lab/ibl/chisquare.py,
// lab/grading/sampling.py, lab/grading/words.py SAMPLING), sent with each check as data
// (check.rules: lab/grading/kinds/sampled.py page_rules); this file carries the mechanisms.
// Why in JavaScript too: practice mode checks the student's text in the browser, which never
// reaches Python.
import { floatTexture } from "./assemble.js";
import { sentence } from "./diagnosis.js";
import { fill } from "./header.js";

export const SAMPLED_KINDS = ["chi_square", "pdf_integral"];

// The grader's numbers, from the check being run (useRules): bins in cos θ and φ, the
// expected count below which bins are pooled, the quadrature's cells per bin side, its
// tolerance and limits, the second draw's seed offset, the p-value that needs no second
// draw, the usable share of samples and the z of the integral's allowance.
let THETA_BINS, PHI_BINS, BINS, MIN_EXPECTED, SUB, TOLERANCE, MAX_LEVELS, MAX_CELLS;
let REDRAW, DECISIVE, USABLE, Z_INTEGRAL, WORDS;

function useRules(rules) {
  [THETA_BINS, PHI_BINS] = rules.bins;
  BINS = THETA_BINS * PHI_BINS;
  ({ min_expected: MIN_EXPECTED, sub: SUB, tolerance: TOLERANCE, max_levels: MAX_LEVELS, max_cells: MAX_CELLS } = rules);
  ({ redraw: REDRAW, decisive: DECISIVE, usable: USABLE, z_integral: Z_INTEGRAL, words: WORDS } = rules);
}

/** The sentence `key` of lab/grading/words.py SAMPLING, filled as Python fills it. */
const say = (key, values = {}) => fill(WORDS[key], values);

const WIDTH = 1024; // texels per row of a pass, as the grader's _texel_pass
const CHUNK_ROWS = 256; // rows of one pdf pass (one render target size for all of them)
const TAU = 2 * Math.PI;
const mod = (a, n) => ((a % n) + n) % n; // Python's %

/** A pass in which the loop guard stopped a loop of the student's code (its first texel). */
class LoopStopped extends Error {
  constructor(stop) {
    super(`the loop at line ${stop.line} did not end`);
    this.stop = stop;
  }
}

/** A view of one value per texel: `inputs` are (n, 3) directions as flat arrays, bound to
 * units 0, 1, ...; returns the n RGBA results (row by row, as the grader reads them). */
function texelPass(panel, view, inputs, uniforms, rows) {
  const gl = panel.gl;
  const n = inputs[0].length / 3;
  const height = rows ?? Math.max(Math.ceil(n / WIDTH), 1);
  const textures = inputs.map((flat) => {
    const padded = new Float32Array(WIDTH * height * 4);
    for (let i = 0; i < n; i++) padded.set(flat.subarray(3 * i, 3 * i + 3), 4 * i);
    return floatTexture(gl, WIDTH, height, padded);
  });
  try {
    const out = panel.run(view, WIDTH, height, uniforms, { textures }).subarray(0, 4 * n);
    if (panel.lastLoop) throw new LoopStopped(panel.lastLoop); // the next pass would forget it
    return out;
  } finally {
    textures.forEach((t) => gl.deleteTexture(t));
  }
}

const frameUniforms = (frame) => ({ u_X: frame[0], u_Y: frame[1], u_N: frame[2] });

/** PDF_BRDF at the local directions (cos θ, φ) for one V: the grader's _pdf. */
function pdfAt(panel, c, p, V, frame) {
  const out = new Float64Array(c.length);
  const chunk = WIDTH * CHUNK_ROWS;
  for (let start = 0; start < c.length; start += chunk) {
    const n = Math.min(chunk, c.length - start);
    const L = new Float64Array(3 * n);
    const Vs = new Float64Array(3 * n);
    for (let i = 0; i < n; i++) {
      const cos = c[start + i];
      const s = Math.sqrt(Math.min(Math.max(1 - cos * cos, 0), 1));
      L[3 * i] = s * Math.cos(p[start + i]);
      L[3 * i + 1] = s * Math.sin(p[start + i]);
      L[3 * i + 2] = cos;
      Vs.set(V, 3 * i);
    }
    const got = texelPass(panel, "ibl_pdf", [new Float32Array(L), new Float32Array(Vs)],
      { u_L: 0, u_V: 1, ...frameUniforms(frame) }, CHUNK_ROWS);
    for (let i = 0; i < n; i++) out[start + i] = Number.isFinite(got[4 * i]) ? got[4 * i] : 0;
  }
  return out;
}

/** The pdf integrated over each (cos θ, φ) bin, adaptively: chisquare.bin_probabilities. */
export function binProbabilities(panel, V, frame) {
  const dc0 = 2 / (THETA_BINS * SUB);
  const dp0 = TAU / (PHI_BINS * SUB);
  const cells = THETA_BINS * SUB * PHI_BINS * SUB;
  let c0 = new Float64Array(cells);
  let p0 = new Float64Array(cells);
  let which = new Int32Array(cells);
  for (let i = 0, k = 0; i < THETA_BINS * SUB; i++) {
    for (let j = 0; j < PHI_BINS * SUB; j++, k++) {
      c0[k] = -1 + i * dc0;
      p0[k] = j * dp0;
      which[k] = Math.floor(i / SUB) * PHI_BINS + Math.floor(j / SUB);
    }
  }
  let [dc, dp] = [dc0, dp0];
  let mid = pdfAt(panel, c0.map((c) => c + dc / 2), p0.map((p) => p + dp / 2), V, frame);
  const apex = [-V[2], mod(Math.atan2(-V[1], -V[0]), TAU)];
  const total = new Float64Array(BINS);
  const offsets = [[0.25, 0.25], [0.75, 0.25], [0.25, 0.75], [0.75, 0.75]];
  for (let level = 0; level <= MAX_LEVELS; level++) {
    const m = c0.length;
    const cc = new Float64Array(4 * m);
    const pp = new Float64Array(4 * m);
    for (let k = 0; k < m; k++) {
      offsets.forEach(([oc, op], o) => {
        cc[4 * k + o] = c0[k] + oc * dc;
        pp[4 * k + o] = p0[k] + op * dp;
      });
    }
    const kids = pdfAt(panel, cc, pp, V, frame);
    const area = dc * dp;
    const fine = new Float64Array(m);
    const done = new Uint8Array(m);
    let open = 0;
    // Cells near L = -V (a half-vector pdf's singularity) are always refined (_near).
    const nearOn = Math.abs(apex[0]) <= 0.999;
    for (let k = 0; k < m; k++) {
      fine[k] = ((kids[4 * k] + kids[4 * k + 1] + kids[4 * k + 2] + kids[4 * k + 3]) * area) / 4;
      const near = nearOn && Math.abs(c0[k] + dc / 2 - apex[0]) < 2.5 * dc &&
        Math.abs(mod(p0[k] + dp / 2 - apex[1] + Math.PI, TAU) - Math.PI) < 2.5 * dp;
      done[k] = Math.abs(fine[k] - mid[k] * area) <= TOLERANCE && !near ? 1 : 0;
      if (!done[k]) open++;
    }
    if (level === MAX_LEVELS || open * 4 > MAX_CELLS) {
      done.fill(1);
      open = 0;
    }
    // Richardson, as chisquare.bin_probabilities: fine + (fine - coarse) / 3.
    for (let k = 0; k < m; k++) if (done[k]) total[which[k]] += fine[k] + (fine[k] - mid[k] * area) / 3;
    if (!open) break;
    const [nc, np_, nw, nm] = [new Float64Array(4 * open), new Float64Array(4 * open), new Int32Array(4 * open),
      new Float64Array(4 * open)];
    for (let k = 0, q = 0; k < m; k++) {
      if (done[k]) continue;
      offsets.forEach(([oc, op], o) => {
        nc[q] = c0[k] + (oc - 0.25) * dc;
        np_[q] = p0[k] + (op - 0.25) * dp;
        nw[q] = which[k];
        nm[q++] = kids[4 * k + o];
      });
    }
    [c0, p0, which, mid] = [nc, np_, nw, nm];
    dc /= 2;
    dp /= 2;
  }
  return total;
}

/** P(X >= statistic) for X chi-square with `dof` degrees of freedom (chisquare.chi2_sf). */
export function chi2Sf(statistic, dof) {
  const a = dof / 2;
  const x = statistic / 2;
  if (x <= 0) return 1;
  const scale = Math.exp(-x + a * Math.log(x) - logGamma(a));
  if (x < a + 1) {
    let term = 1 / a;
    let total = term;
    let n = a;
    for (let i = 0; i < 100_000; i++) {
      n += 1;
      term *= x / n;
      total += term;
      if (Math.abs(term) < Math.abs(total) * 1e-15) break;
    }
    return Math.min(Math.max(1 - total * scale, 0), 1);
  }
  const tiny = 1e-300;
  let b = x + 1 - a;
  let c = 1 / tiny;
  let d = 1 / b;
  let h = d;
  for (let i = 1; i < 100_000; i++) {
    const an = -i * (i - a);
    b += 2;
    d = an * d + b;
    if (Math.abs(d) < tiny) d = tiny;
    c = b + an / c;
    if (Math.abs(c) < tiny) c = tiny;
    d = 1 / d;
    h *= d * c;
    if (Math.abs(d * c - 1) < 1e-15) break;
  }
  return Math.min(Math.max(h * scale, 0), 1);
}

/** ln Γ(x) for x > 0 (Lanczos, g = 7, n = 9: about 15 digits, as math.lgamma). */
function logGamma(x) {
  const g = [0.99999999999980993, 676.5203681218851, -1259.1392167224028, 771.32342877765313,
    -176.61502916214059, 12.507343278686905, -0.13857109526572012, 9.9843695780195716e-6,
    1.5056327351493116e-7];
  if (x < 0.5) return Math.log(Math.PI / Math.sin(Math.PI * x)) - logGamma(1 - x);
  x -= 1;
  let sum = g[0];
  for (let i = 1; i < 9; i++) sum += g[i] / (x + i);
  const t = x + 7.5;
  return 0.5 * Math.log(TAU) + (x + 0.5) * Math.log(t) - t + Math.log(sum);
}

/** Pearson's statistic, degrees of freedom and p-value, low bins pooled with the failed
 * samples (chisquare.pearson). */
export function pearson(observed, expected, failed, missing) {
  const obs = [];
  const exp = [];
  let poolO = failed;
  let poolE = Math.max(missing, 0);
  for (let i = 0; i < observed.length; i++) {
    if (expected[i] < MIN_EXPECTED) {
      poolO += observed[i];
      poolE += expected[i];
    } else {
      obs.push(observed[i]);
      exp.push(expected[i]);
    }
  }
  if (poolE > 0 || poolO > 0) {
    obs.push(poolO);
    exp.push(Math.max(poolE, 1e-9));
  }
  let statistic = 0;
  for (let i = 0; i < obs.length; i++) statistic += (obs[i] - exp[i]) ** 2 / exp[i];
  const dof = Math.max(obs.length - 1, 1);
  return { statistic, dof, p: chi2Sf(statistic, dof) };
}

/** The student's samples at one view: observed counts per bin and the failure counts. */
function sampleCounts(panel, check, index, seed = check.seed) {
  const n = check.options.samples;
  const V = new Float32Array(3 * n);
  for (let i = 0; i < n; i++) V.set(check.V[index], 3 * i);
  const out = texelPass(panel, "ibl_sample", [V], { u_V: 0, u_seed: seed + index, ...frameUniforms(check.frames[index]) });
  const observed = new Float64Array(BINS);
  let [valid, unit, finite] = [0, 0, 0];
  for (let i = 0; i < n; i++) {
    const [x, y, z, pdf] = out.subarray(4 * i, 4 * i + 4);
    if (![x, y, z, pdf].every(Number.isFinite)) continue;
    finite++;
    const length = Math.hypot(x, y, z);
    if (Math.abs(length - 1) >= 1e-3) continue;
    unit++;
    if (!(pdf > 0)) continue;
    valid++;
    const cos = Math.min(Math.max(z / length, -1), 1);
    const phi = mod(Math.atan2(y / length, x / length), TAU);
    const ti = Math.min(Math.max(Math.floor(((cos + 1) / 2) * THETA_BINS), 0), THETA_BINS - 1);
    const pi = Math.min(Math.max(Math.floor((phi / TAU) * PHI_BINS), 0), PHI_BINS - 1);
    observed[ti * PHI_BINS + pi]++;
  }
  return { observed, failed: n - valid, notUnit: n - unit, notFinite: n - finite };
}

function binWords(index) {
  const ti = Math.floor(index / PHI_BINS);
  const pi = index % PHI_BINS;
  const c0 = -1 + (2 * ti) / THETA_BINS;
  const c1 = c0 + 2 / THETA_BINS;
  const deg = (r) => (r * 180) / Math.PI;
  const p0 = (360 * pi) / PHI_BINS;
  return say("bin", { t0: deg(Math.acos(Math.min(c1, 1))), t1: deg(Math.acos(Math.max(c0, -1))), p0, p1: p0 + 360 / PHI_BINS });
}

const where = ([theta, phi]) => say("view", { theta, phi });

// Per view: observed, expected, then failed, not unit, not finite and the draw (0 or 1).
const row = () => 2 * BINS + 4;
const SCALE = 6; // pixels per bin side of a histogram picture

/** A (cos θ, φ) histogram as an RGBA picture, θ down, φ across (sampling.histogram_image). */
function histogramImage(counts, peak) {
  const [width, height] = [PHI_BINS * SCALE, THETA_BINS * SCALE];
  const rgba = new Uint8ClampedArray(4 * width * height);
  for (let y = 0; y < height; y++) {
    for (let x = 0; x < width; x++) {
      const bin = (THETA_BINS - 1 - Math.floor(y / SCALE)) * PHI_BINS + Math.floor(x / SCALE);
      const v = Math.sqrt(Math.min(Math.max(counts[bin] / Math.max(peak, 1e-9), 0), 1));
      const at = 4 * (y * width + x);
      [v, v ** 0.7, v ** 0.4].forEach((c, k) => (rgba[at + k] = Math.floor(c * 255 + 0.5)));
      rgba[at + 3] = 255;
    }
  }
  return { width, height, rgba };
}

/** The grader's three pictures of a chi-square check, at its worst view (or the first). */
function histogramFigures(check, raw, view) {
  const start = row() * view;
  const mine = raw.subarray(start, start + BINS);
  const pdf = raw.subarray(start + BINS, start + 2 * BINS);
  const peak = Math.max(...pdf, ...mine, 1);
  const figures = [
    { title: check.captions["your pdf"], ...histogramImage(pdf, peak) },
    { title: check.captions["your samples"], ...histogramImage(mine, peak) },
  ];
  const solution = solutionValues(check);
  if (solution.length === raw.length) {
    figures.push({ title: check.captions["solution's pdf"],
      ...histogramImage(solution.subarray(start + BINS, start + 2 * BINS), peak) });
  }
  return figures;
}

/** The solution's numbers of a chi-square check (exercises.json, float32). */
function solutionValues(check) {
  check.solutionValues ??= new Float32Array(Uint8Array.from(atob(check.solution), (c) => c.charCodeAt(0)).buffer);
  return check.solutionValues;
}

/** Two samplers alike (sampling.same_chi_square): rows of row() numbers per view. */
function sameChiSquare(a, b, samples) {
  if (a.length !== b.length) return false;
  for (let start = 0; start < a.length; start += row()) {
    let pdfOff = 0;
    for (let i = BINS; i < 2 * BINS; i++) pdfOff += Math.abs(a[start + i] - b[start + i]);
    if (pdfOff > 0.02 * samples || Math.abs(a[start + 2 * BINS + 1] - b[start + 2 * BINS + 1]) > 0.01 * samples) return false;
    let statistic = 0;
    let used = 0;
    for (let i = 0; i < BINS; i++) {
      const sum = a[start + i] + b[start + i];
      if (sum <= 0) continue;
      statistic += (a[start + i] - b[start + i]) ** 2 / sum;
      used++;
    }
    if (chi2Sf(statistic, Math.max(used - 1, 1)) < 1e-4) return false;
  }
  return true;
}

/** The grader's likely mistake for a failed chi-square check: a stored mistake whose
 * samples and pdf are alike, else which half differs from the solution's (kinds/chi_square). */
function explainChiSquare(check, exercise, raw) {
  const samples = check.options.samples;
  const hints = exercise.hints || {};
  for (const [key, values] of Object.entries(check.stored?.candidates || {})) {
    if (key in hints && sameChiSquare(raw, values, samples)) return sentence(hints[key]);
  }
  const expected = solutionValues(check);
  if (expected.length !== raw.length) return "";
  let pdfOff = false;
  const mineOnly = Float64Array.from(raw);
  for (let start = 0; start < raw.length; start += row()) {
    let off = 0;
    for (let i = BINS; i < 2 * BINS; i++) {
      off += Math.abs(raw[start + i] - expected[start + i]);
      mineOnly[start + i] = expected[start + i];
    }
    pdfOff ||= off > 0.02 * samples;
  }
  const samplesLike = sameChiSquare(mineOnly, expected, samples);
  if (pdfOff && samplesLike) return sentence(say("pdf_wrong"));
  if (!pdfOff && !samplesLike) return sentence(say("sampler_wrong"));
  return "";
}

/** One draw of the chi-square check (sampling.chi_square_draw and chi_square_views): the
 * raw rows and, per view, null (passes) or [what is wrong, decisive]. */
function chiSquareDraw(panel, check, seed, draw, expectedOf) {
  const samples = check.options.samples;
  const level = 1 - (1 - check.options.alpha) ** (1 / Math.max(check.views.length, 1)); // Šidák
  const raw = new Float64Array(row() * check.views.length);
  const verdicts = check.views.map((view, index) => {
    const { observed, failed, notUnit, notFinite } = sampleCounts(panel, check, index, seed);
    const expected = expectedOf(index);
    const mass = expected.reduce((s, v) => s + v, 0);
    raw.set(observed, row() * index);
    raw.set(expected, row() * index + BINS);
    raw.set([failed, notUnit, notFinite, draw], row() * index + 2 * BINS);
    if (notFinite) return [say("not_finite", { where: where(view), count: notFinite, samples }), true];
    if (notUnit > 0.001 * samples) return [say("not_unit", { where: where(view), count: notUnit, samples }), true];
    if (mass < 0.5 * samples) return [say("no_mass", { where: where(view), mass: mass / samples }), true];
    const { statistic, dof, p } = pearson(observed, expected, failed, samples - mass);
    if (p >= level) return null;
    let off = 0;
    let worst = -1;
    for (let i = 0; i < BINS; i++) {
      const score = (observed[i] - expected[i]) ** 2 / Math.max(expected[i], 1);
      if (score > worst) [worst, off] = [score, i];
    }
    return [say("not_following", { where: where(view), statistic, dof, p, level, bin: binWords(off),
      observed: observed[off], expected: expected[off] }), p < DECISIVE];
  });
  return { raw, verdicts, level };
}

/** The chi-square check (sampling.chi_square_raw and judge_chi_square): a first draw that
 * fails within chance is drawn again, independently, and only the second counts. */
function chiSquare(panel, check, exercise) {
  const samples = check.options.samples;
  const expected = [];
  const expectedOf = (index) =>
    (expected[index] ??= binProbabilities(panel, check.V[index], check.frames[index]).map((v) => v * samples));
  let { raw, verdicts, level } = chiSquareDraw(panel, check, check.seed, 0, expectedOf);
  let again = false;
  if (!verdicts.every((v) => v === null || v[1])) {
    ({ raw, verdicts, level } = chiSquareDraw(panel, check, check.seed + REDRAW, 1, expectedOf));
    again = true;
  }
  const lines = verdicts.filter((v) => v !== null).map((v) => v[0]);
  if (lines.length) {
    const worstView = verdicts.findIndex((v) => v !== null); // its histograms are shown
    const more = lines.length - 1;
    let message = more ? say(more > 1 ? "more" : "one_more", { text: lines[0], more }) : lines[0];
    if (again) message = say("again", { text: message });
    const likely = explainChiSquare(check, exercise, raw);
    return { passed: false, message: likely ? `${message}. ${likely}` : message,
      figures: histogramFigures(check, raw, worstView) };
  }
  const tested = check.views.map(([theta]) => say("angle", { theta })).join(", ");
  return { passed: true, message: say("follows", { tested, level }), figures: histogramFigures(check, raw, 0) };
}

/** The pdf integral check (sampling.pdf_integral_raw and judge_pdf_integral): the pdf over
 * the sphere against 1 less the share of the student's own draws that fail. */
function pdfIntegral(panel, check, exercise) {
  const { tolerance, samples } = check.options;
  const raw = check.views.map((_, index) => {
    const sum = binProbabilities(panel, check.V[index], check.frames[index]).reduce((s, v) => s + v, 0);
    const { failed } = sampleCounts(panel, check, index);
    return [Number.isNaN(sum) ? Infinity : sum, failed / samples];
  });
  const allowed = raw.map(([, f]) => {
    const share = Math.min(Math.max(f, 1 / samples), 1 - 1 / samples);
    return tolerance + Z_INTEGRAL * Math.sqrt((share * (1 - share)) / samples);
  });
  const off = raw.map(([v, f]) => Math.abs(v - (1 - f)));
  const usable = raw.map(([, f]) => 1 - f >= USABLE);
  if (off.every((d, i) => d <= allowed[i]) && usable.every(Boolean)) {
    const values = raw.map(([value]) => say("integral", { value })).join(", ");
    const wasted = raw.map(([, f]) => say("share", { percent: 100 * f })).join(", ");
    return { passed: true, message: say("integrates", { values, wasted }) };
  }
  const worst = usable.every(Boolean) ? off.reduce((b, d, i) => (d - allowed[i] > off[b] - allowed[b] ? i : b), 0)
    : usable.indexOf(false);
  const [theta, phi] = check.views[worst];
  const [value, failed] = raw[worst];
  const said = { at: say("at_view", { theta, phi }), percent: 100 * failed };
  // A stored mistake within half the tolerance everywhere (kinds/pdf_integral nearest).
  let likely = "";
  let best = tolerance / 2;
  for (const [key, values] of Object.entries(check.stored?.candidates || {})) {
    if (!(key in (exercise.hints || {})) || values.length !== 2 * raw.length) continue;
    const distance = Math.max(...raw.map(([v], i) => Math.abs(v - values[2 * i])));
    if (distance <= best) [likely, best] = [sentence(exercise.hints[key]), distance];
  }
  const tail = likely ? `. ${likely}` : "";
  if (!usable[worst]) return { passed: false, message: say("unusable", { ...said, usable: 100 * USABLE }) + tail };
  return { passed: false, message: say("integral_off", { ...said, value, density: 1 - failed, allowed: allowed[worst] }) + tail };
}

/** Loads what a check needs from the server before it runs: nothing for these kinds. */
export async function prepareSampled(check) {}

/** Runs a sampling check on the panel (its values already the check's); `{ loop }` where
 * the loop guard stopped a loop, with the sample it stopped at as the grader counts them. */
export async function runSampled(panel, check, exercise) {
  useRules(check.rules);
  try {
    return await (check.kind === "chi_square" ? chiSquare(panel, check, exercise) : pdfIntegral(panel, check, exercise));
  } catch (err) {
    if (!(err instanceof LoopStopped)) throw err;
    return { loop: { ...err.stop, sample: err.stop.y * WIDTH + err.stop.x } };
  }
}

// The grader's diagnosis of a failed check, in the page (practice mode): the same evidence
// in the same order as lab/grading/explain.py with the stored references (never live), and
// the same tests and sentences as lab/grading/diagnosis.py. exercises.json carries the
// stored values of the known mistakes and mutants and of each declared term alone.
// Why in JavaScript too: practice mode explains the student's values in the browser; its words
// come as data.
import { fill, formatDigits as g } from "./header.js";

// The rules' words and thresholds are lab/grading/diagnosis.py's, sent as data in
// exercises.json ("diagnosis": named factors with their sentences, channel names, the share
// of rows a pattern must hold on, the grazing angle, and every sentence as a str.format
// template of lab/grading/words.py): useRules() before any diagnosis.
let RULES = null;

/** Takes exercises.json's "diagnosis" (lab/web/exercises.py diagnosis_rules). */
export function useRules(rules) {
  RULES = rules;
}

const rules = () => {
  if (!RULES) throw new Error("diagnosis.js: no rules yet (useRules with exercises.json's diagnosis)");
  return RULES;
};

/** The sentence `key` of lab/grading/words.py DIAGNOSIS, filled as Python fills it. */
const say = (key, values = {}) => fill(rules().words[key], values);

/** The grader's sentence for a loop its guard stopped (words.py DIAGNOSIS loop_stopped), or
 * for loops that together ran out of the guard's total (loops_total, flagged in the line). */
export function loopStopped(file, line, limit, where, constants) {
  const together = line >= constants.LOOP_TOTAL_FLAG;
  return say(together ? "loops_total" : "loop_stopped", { file, line: together ? line - constants.LOOP_TOTAL_FLAG : line,
    limit: Number(limit).toLocaleString("en-US"), total: constants.LOOP_TOTAL.toLocaleString("en-US"), where });
}

/** 'D', 'D and G', 'diffuse, D and G' (words.joined). */
const joined = (names) => (names.length === 1 ? names[0] : say("listed", { most: names.slice(0, -1).join(", "), last: names.at(-1) }));

// -- rows of (n, 3) values, as flat Float32/Float64 arrays with a stride -----------------
/** Rows (n x 3 numbers) from a flat array of `stride` numbers per row. */
export function rows(flat, n, stride = 3) {
  const out = [];
  for (let i = 0; i < n; i++) out.push([flat[stride * i], flat[stride * i + 1], flat[stride * i + 2]]);
  return out;
}

/** diagnosis.within: rows where got is within slack x the tolerance of want. */
export function within(check, got, want, slack = 2) {
  return got.map((row, i) => row.every((x, c) => {
    const w = want[i][c];
    const tol = slack * (check.atol + check.rtol * Math.abs(w));
    return Math.abs(x - w) <= tol || x === w || (Number.isNaN(x) && Number.isNaN(w));
  }));
}

const mean = (bools) => bools.reduce((s, b) => s + (b ? 1 : 0), 0) / Math.max(bools.length, 1);

export function same(check, got, want) {
  return mean(within(check, got, want)) >= rules().match_share;
}

/** diagnosis.nearest: the candidate the student agrees with nearly everywhere. */
export function nearest(check, got, candidates, wrong) {
  let best = null;
  let bestShare = rules().match_share;
  const anyWrong = wrong.some(Boolean);
  for (const [key, values] of Object.entries(candidates)) {
    if (values.length !== got.length) continue;
    const agree = within(check, got, values);
    if (anyWrong) {
      const onWrong = agree.filter((_, i) => wrong[i]);
      if (mean(onWrong) < 0.9) continue;
    }
    const share = mean(agree);
    if (share >= bestShare && (best === null || share > bestShare)) {
      best = key;
      bestShare = share;
    }
  }
  return best;
}

function median(values) {
  const s = [...values].sort((a, b) => a - b);
  const n = s.length;
  if (!n) return NaN;
  return n % 2 ? s[(n - 1) / 2] : (s[n / 2 - 1] + s[n / 2]) / 2;
}

/** numpy's percentile (linear interpolation). */
function percentile(values, q) {
  const s = [...values].sort((a, b) => a - b);
  if (!s.length) return NaN;
  const pos = ((s.length - 1) * q) / 100;
  const lo = Math.floor(pos);
  const hi = Math.min(lo + 1, s.length - 1);
  return s[lo] + (s[hi] - s[lo]) * (pos - lo);
}

function spread(ratio) {
  const med = median(ratio);
  if (!Number.isFinite(med) || med <= 0) return [med, Infinity];
  return [med, percentile(ratio.map((r) => Math.abs(r / med - 1)), 90)];
}

function factorName(value) {
  for (const [constant, name, cause] of rules().constants) if (Math.abs(value / constant - 1) < 0.02) return [name, cause];
  return null;
}

function ratioPhrase(value) {
  const named = factorName(value);
  if (named && value > 1) return say("named_large", { name: named[0], cause: named[1] });
  const inverse = factorName(1 / value);
  if (inverse && value < 1) return say("named_small", { name: inverse[0], cause: named ? named[1] : "" }).replace(/[ —]+$/, "");
  return value > 1 ? say("large", { times: value }) : say("small", { times: 1 / value });
}

const cosDeg = (d) => Math.cos((d * Math.PI) / 180);

/** diagnosis.shape: the pattern of the error in a few words, or "". */
export function shape(check, angles, expected, got) {
  const wrong = within(check, got, expected, 1).map((ok) => !ok);
  if (!wrong.some(Boolean)) return "";
  if (!got.every((row) => row.every(Number.isFinite))) return say("not_finite");
  const negative = got.map((row) => row.some((x) => x < 0));
  const nNegative = negative.filter(Boolean).length;
  if (nNegative) {
    const atZero = expected.every((row, i) => !negative[i] || row.every((x) => x <= 0));
    return say("negative", { count: nNegative, where: say(atZero ? "negative_at_zero" : "negative_in_places") });
  }
  const zero = expected.map((row) => row.every((x) => x <= 0));
  if (wrong.every((w, i) => !w || zero[i])) {
    const below = angles.map((a) => Math.max(a[0], a[2]) >= 90);
    return say(wrong.every((w, i) => !w || below[i]) ? "wrong_below" : "wrong_above");
  }
  const nothing = got.map((row) => row.every((x) => Math.abs(x) <= check.atol));
  if (wrong.every((w, i) => !w || (nothing[i] && !zero[i]))) {
    // Not "grey where the solution is coloured": zero is no colour at all.
    return say("zero", { where: say(nothing.every(Boolean) ? "zero_everywhere" : "zero_where_wrong") });
  }
  return ratioShape(check, angles, expected, got) || oneChannel(check, expected, got, wrong) ||
    grazing(angles, wrong, zero, Boolean(check.table?.length)) || seam(check, wrong, zero);
}

function std(values) {
  const m = values.reduce((s, x) => s + x, 0) / values.length;
  return Math.sqrt(values.reduce((s, x) => s + (x - m) * (x - m), 0) / values.length);
}

function ratioShape(check, angles, expected, got) {
  const floor = 20 * check.atol;
  const use = expected.map((row, i) => row.every((e, c) => e > floor && got[i][c] > 0));
  const count = use.filter(Boolean).length;
  if (count < Math.max(8, 0.3 * use.length)) return "";
  const idx = use.map((u, i) => (u ? i : -1)).filter((i) => i >= 0);
  const ratio = idx.map((i) => got[i].map((x, c) => x / expected[i][c]));
  const flat = ratio.flat();
  let [med, sp] = spread(flat);
  if (sp < 0.01 && Math.abs(med - 1) > 3 * check.rtol) return ratioPhrase(med);
  const cosI = idx.map((i) => cosDeg(angles[i][0]));
  const cosO = idx.map((i) => cosDeg(angles[i][2]));
  const factors = [
    [cosI, "factor_cos_i"],
    [cosO, "factor_cos_o"],
    [cosI.map((c) => 1 / c), "factor_over_cos_i"],
    [cosO.map((c) => 1 / c), "factor_over_cos_o"],
    [cosI.map((c, k) => Math.sqrt(c * cosO[k])), "factor_sqrt"],
    [cosI.map((c, k) => 1 / Math.sqrt(c * cosO[k])), "factor_over_sqrt"],
  ];
  for (const [factor, key] of factors) {
    if (std(factor) < 0.05) continue;
    [med, sp] = spread(ratio.flatMap((row, k) => row.map((r) => r / factor[k])));
    if (sp < 0.01) {
      if (Math.abs(med - 1) < 0.02) return say("off_by", { factor: say(key) });
      return say("off_by_scaled", { factor: say(key), scale: med });
    }
  }
  return "";
}

function ptp(row) {
  return Math.max(...row) - Math.min(...row);
}

function oneChannel(check, expected, got, wrong) {
  const coloured = expected.map((row) => ptp(row) > 0.05 * Math.max(...row) + check.atol);
  const grey = got.map((row) => ptp(row) <= 1e-6 * (1 + Math.max(...row.map(Math.abs))));
  const wrongColoured = wrong.map((w, i) => w && coloured[i]);
  if (wrongColoured.some(Boolean) && wrongColoured.every((w, i) => !w || grey[i]) && mean(grey) > 0.9) {
    return say("grey");
  }
  const channels = [0, 1, 2].map((c) => got.some((row, i) =>
    Math.abs(row[c] - expected[i][c]) > check.atol + check.rtol * Math.abs(expected[i][c])));
  if (channels.filter(Boolean).length === 1) return say("one_channel", { channel: rules().channels[channels.indexOf(true)] });
  return "";
}

function grazing(angles, wrong, zero, table) {
  const limit = rules().grazing;
  const steep = angles.map((a) => Math.max(a[0], a[2]) > limit);
  const elsewhere = steep.map((s, i) => !s && !zero[i]);
  const nElsewhere = elsewhere.filter(Boolean).length;
  if (nElsewhere >= 8 && !wrong.some((w, i) => w && elsewhere[i]) && wrong.some((w, i) => w && steep[i])) {
    return say(table ? "grazing_table" : "grazing", { grazing: limit });
  }
  return "";
}

/** diagnosis._seam: wrong only across a table's periodic seam (rows sent as "seam"). */
function seam(check, wrong, zero) {
  const rowsAt = check.diagnosis?.seam;
  if (!rowsAt) return "";
  const across = new Set(rowsAt);
  const elsewhere = wrong.map((_, i) => !across.has(i) && !zero[i]);
  if (elsewhere.filter(Boolean).length >= 8 && !wrong.some((w, i) => w && elsewhere[i]) &&
    wrong.some((w, i) => w && across.has(i))) {
    return say("seam");
  }
  return "";
}

function halfWidth(theta, values) {
  const floor = Math.min(...values);
  const half = floor + 0.5 * (Math.max(...values) - floor);
  const above = values.map((v, i) => (v >= half ? i : -1)).filter((i) => i >= 0);
  if (above.length < 2 || above.length === values.length) return 0;
  return theta[above[above.length - 1]] - theta[above[0]] || 1;
}

const argmax = (values) => values.reduce((best, v, i) => (v > values[best] ? i : best), 0);

/**
 * diagnosis.lobe: the polar curve's peak in the wrong place, or a lobe too wide or too
 * narrow, with the width parameter fitted from `table` (diagnosis.width_table, computed by
 * the grader's code when exercises.json is made: the same table the grader reads).
 */
export function lobe(check, theta, expected, got, params, table = null) {
  const side = theta.map((t) => t >= 0);
  const e = expected.filter((_, i) => side[i]);
  const gv = got.filter((_, i) => side[i]);
  const t = theta.filter((_, i) => side[i]);
  if (!gv.every(Number.isFinite) || Math.max(...e) <= 0 || Math.max(...gv) <= 0) return "";
  const ePeak = t[argmax(e)];
  const gPeak = t[argmax(gv)];
  const peaked = Math.max(...gv) > 1.5 * Math.min(gv[0], gv[gv.length - 1]) + check.atol &&
    Math.max(...e) > 1.5 * Math.min(e[0], e[e.length - 1]);
  if (!peaked) return "";
  if (Math.max(ePeak, gPeak) >= Math.max(...t) - 2) return ""; // the rise toward grazing
  const eWidth = halfWidth(t, e);
  const gWidth = halfWidth(t, gv);
  const moved = Math.abs(ePeak - gPeak) >= 3 && gPeak > 0;
  const wider = Boolean(eWidth && gWidth) && Math.abs(gWidth / eWidth - 1) >= 0.2;
  let fit = wider ? fitWidth(table, eWidth, gWidth) : null;
  if (fit && Math.abs(fit[3] - gPeak) > 2) fit = null;
  if (moved && !fit) {
    // Beckmann's or Cook-Torrance's peak moves with the roughness at an equal width.
    const peak = fitPeak(table, eWidth, gWidth, gPeak);
    if (peak) {
      const [what, value, actual] = peak;
      return say("peak_fit", { got: gPeak, want: ePeak, what, value: Number(g(value, 2)), actual });
    }
    return say("peak", { got: gPeak, want: ePeak });
  }
  if (!wider) return "";
  let text = say(gWidth > eWidth ? "too_wide" : "too_narrow", { ratio: Math.max(gWidth, eWidth) / Math.min(gWidth, eWidth) });
  if (moved) text = say("and_peaks", { text, got: gPeak, want: ePeak });
  if (fit) {
    const [what, value, actual] = fit;
    text = say("as_wide", { text, what, value: Number(g(value, 2)), actual });
  }
  return text;
}

/** diagnosis.fit_width: [words, value, the check's value, peak θo] or null. */
export function fitWidth(table, eWidth, gWidth) {
  if (!table || Math.abs(table.solution_width / eWidth - 1) > 0.15) return null;
  let best = 0;
  for (let i = 1; i < table.widths.length; i++) {
    if (Math.abs(table.widths[i] - gWidth) < Math.abs(table.widths[best] - gWidth)) best = i;
  }
  if (best <= 0 || best >= table.widths.length - 1) return null;
  if (Math.abs(table.widths[best] / gWidth - 1) > 0.1) return null;
  return [table.words, table.values[best], table.actual, table.peaks[best]];
}

/** diagnosis.fit_peak: the width parameter whose lobe peaks where the student's does. */
export function fitPeak(table, eWidth, gWidth, gPeak) {
  if (!table || !gWidth || Math.abs(table.solution_width / eWidth - 1) > 0.15) return null;
  let best = -1;
  let bestCost = Infinity;
  for (let i = 1; i < table.widths.length - 1; i++) {
    const offPeak = Math.abs(table.peaks[i] - gPeak);
    if (offPeak > 2 || Math.abs(table.widths[i] / gWidth - 1) > 0.1) continue;
    const cost = offPeak + Math.abs(table.widths[i] - gWidth);
    if (cost < bestCost) [best, bestCost] = [i, cost];
  }
  return best < 0 ? null : [table.words, table.values[best], table.actual, table.peaks[best]];
}

export function termsSentence(wrong, right, detail) {
  let text = say(wrong.length > 1 ? "terms_wrong" : "term_wrong", { names: joined(wrong) });
  if (right.length) text = say(right.length > 1 ? "terms_right" : "term_right", { text, names: joined(right) });
  return detail ? say("detail", { text, detail }) : text;
}

export function sentence(text) {
  text = text.trim().replace(/\.+$/, "");
  return text ? say("likely", { text }) : "";
}

// -- stored references: inflated once per exercise ---------------------------------------
/** Base64 of zlib-deflated bytes (lab/web/exercises.py _packed) as a `Type` array. */
export async function inflate(base64, Type) {
  const bytes = Uint8Array.from(atob(base64), (c) => c.charCodeAt(0));
  const stream = new Blob([bytes]).stream().pipeThrough(new DecompressionStream("deflate"));
  return new Type(await new Response(stream).arrayBuffer());
}

/** Inflates every check's stored candidates and term values (check.stored). */
export async function prepare(exercise) {
  for (const check of exercise.checks) {
    if (check.stored || !check.diagnosis) continue;
    const image = ["sphere", "object"].includes(check.kind); // uint8 RGBA images
    const stored = { candidates: {}, terms: {} };
    for (const [key, text] of Object.entries(check.diagnosis.candidates)) {
      const data = await inflate(text, image ? Uint8Array : Float32Array);
      // A sampling, properties or sh check's values stay as the grader stores them (flat).
      const flat = image || ["chi_square", "pdf_integral", "ibl_render", "properties", "sh"].includes(check.kind);
      stored.candidates[key] = flat ? data : rows(data, check.count);
    }
    for (const [name, text] of Object.entries(check.diagnosis.terms)) {
      stored.terms[name] = rows(await inflate(text, Float32Array), check.count);
    }
    check.stored = stored;
  }
}

function sphereShare(check, image8, other8) {
  let covered = 0;
  let over = 0;
  for (let i = 0; i < image8.length / 4; i++) {
    if (image8[4 * i + 3] <= 127) continue;
    covered++;
    let diff = 0;
    for (let c = 0; c < 3; c++) diff = Math.max(diff, Math.abs(image8[4 * i + c] - other8[4 * i + c]));
    if (diff > check.threshold) over++;
  }
  return covered ? over / covered : 0;
}

function nearestImage(check, image8, candidates) {
  let best = null;
  let bestShare = 1;
  for (const [key, other] of Object.entries(candidates)) {
    if (other.length !== image8.length) continue;
    const share = sphereShare(check, other, image8);
    if (share <= Math.max(check.max_fraction, 0.002) && share < bestShare) {
      best = key;
      bestShare = share;
    }
  }
  return best;
}

/**
 * explain.Explainer.explain in practice mode. `got`: the student's values (rows of 3) or,
 * for a sphere, the tone-mapped uint8 RGBA image; `evaluate(params, angles)` renders the
 * student's model at other parameters or direction pairs (rows of 4 degrees) -> rows;
 * `luma`: the lab's luminance weights (the manifest's LUMA).
 */
export function explain(exercise, check, expected, got, angles, evaluate, luma) {
  const hints = exercise.hints || {};
  const stored = check.stored || { candidates: {}, terms: {} };
  const candidates = Object.fromEntries(Object.entries(stored.candidates).filter(([k]) => k in hints));
  if (check.kind === "sphere" || check.kind === "object") {
    const key = nearestImage(check, got, candidates);
    return key ? sentence(hints[key]) : "";
  }
  const wrong = within(check, got, expected, 1).map((ok) => !ok);
  const key = nearest(check, got, candidates, wrong);
  if (key) return sentence(hints[key]);
  let text = terms(exercise, check, angles, stored, evaluate, luma);
  text ||= shape(check, angles, expected, got);
  text ||= swaps(check, angles, expected, evaluate);
  if (!text && check.kind === "polar") {
    text = polarLobe(check, expected, got, check.params, luma, check.lobe_fit?.[""]);
  }
  return sentence(text);
}

function terms(exercise, check, angles, stored, evaluate, luma) {
  const declared = Object.entries(exercise.terms || {});
  if (declared.length < 2) return "";
  const wrong = [];
  const right = [];
  let detail = "";
  for (const [name, overrides] of declared) {
    const want = stored.terms[name];
    if (!want) return "";
    const params = { ...check.params, ...overrides };
    const mine = evaluate(params, null);
    if (within(check, mine, want, 1).every(Boolean)) right.push(name);
    else {
      wrong.push(name);
      const termCheck = { ...check, params };
      detail ||= shape(termCheck, angles, want, mine);
      if (!detail && check.kind === "polar") {
        detail = polarLobe(termCheck, want, mine, params, luma, check.lobe_fit?.[name]);
      }
    }
  }
  if (!wrong.length || !right.length) return "";
  return termsSentence(wrong, right, wrong.length === 1 ? detail : "");
}

function swaps(check, angles, expected, evaluate) {
  const got = evaluate(check.params, angles);
  if (same(check, got, expected)) return "";
  const swapped = evaluate(check.params, angles.map((a) => [a[2], a[3], a[0], a[1]]));
  if (same(check, swapped, expected) && !same(check, swapped, got)) return say("swapped_lv");
  const wrap = (d) => (((90 - d) % 360) + 360) % 360;
  const mirrored = angles.map((a) => [a[0], wrap(a[1]), a[2], wrap(a[3])]);
  const axes = evaluate(check.params, mirrored);
  if (same(check, axes, expected) && !same(check, axes, got)) return say("swapped_xy");
  return "";
}

function polarLobe(check, expected, got, params, luma, table) {
  const lum = (row) => row.reduce((s, x, c) => s + (Number.isNaN(x) ? 0 : x === Infinity ? 1.7976931348623157e308 : x) * luma[c], 0);
  return lobe(check, check.lobe_theta, expected.map(lum), got.map(lum), params, table);
}

// Practice mode of an `ibl_render` check (lab/grading/kinds/ibl_render.py): the lit sphere
// under the check's environment with the student's sampler alone (the IBL view's BRDF
// strategy), in `converged / samples` passes of `samples` per pixel, judged against the
// solution's estimator (the committed reference) by the grader's statistics, mirrored here
// from lab/grading/sampling.py: a z-test of the two means per ring of equal view angle and
// over the sphere with both estimators' own variances (judge_render, bias_z, t_limit) and
// the RMS error at `samples` per pixel against `factor` times the solution's
// (render_errors); the likely mistake by the converged ring means (ring_deviation; the
// grader's further z-test against each stored mistake's render, kinds/ibl_render.py
// converge_distance, needs those renders, which the page is not sent: its note says so).
// Why in JavaScript too: practice mode judges the student's text in the browser, which
// never reaches Python. What can be data is data: exercises.json carries the reference,
// each pixel's group and ring (from the grader's local_view), the group names, the normal
// quantile of the Bonferroni limit, each stored mistake's ring means, the sentences
// (lab/grading/words.py) and the captions; the statistics themselves are mirrored, and
// tests/test_web_practice.py holds them to sampling.py's on the same arrays.
// Where the page differs: the grader seeds its passes with the check's seed salted by the
// SHA-1 of its preprocessed sampler text (sampling.program_seed), which the page does not
// have; it salts the seed with a hash of the student's text instead. Its passes are then
// other random draws of the same estimator: the figures differ from the grader's by noise,
// and the verdict is the grader's but for chance (alpha) or a noise ratio at the limit.
import { environmentTextures, insertBeforeView, loadEnvironment, STRATEGIES } from "./iblsource.js";
import { fill } from "./header.js";
import { topFirst } from "./viewkit.js";
import { sentence } from "./diagnosis.js";

const fromBase64 = (text, Type) => new Type(Uint8Array.from(atob(text), (c) => c.charCodeAt(0)).buffer);
const OFF = 255; // a pixel off the sphere (its group and ring)

/** Student's t quantile of the Bonferroni limit for a statistic with `dof` degrees of
 * freedom, by the Cornish-Fisher expansion around the normal quantile `z` (t_limit). */
export function tLimit(z, dof) {
  const n = Math.max(dof, 3);
  return z + (z ** 3 + z) / (4 * n) + (5 * z ** 5 + 16 * z ** 3 + 3 * z) / (96 * n ** 2) +
    (3 * z ** 7 + 19 * z ** 5 + 17 * z ** 3 - 15 * z) / (384 * n ** 3);
}

/** The check's per-pixel data, decoded once. */
function prepared(check) {
  check.iblData ??= {
    reference: fromBase64(check.reference, Float32Array),
    zones: fromBase64(check.zones, Uint8Array),
    rings: fromBase64(check.rings, Uint8Array),
  };
  return check.iblData;
}

/** Luminance of image `k` (0 one pass, 1 the mean, 2 the variance) of a stacked render
 * (3, size, size, 3), per pixel: _luminance. */
function luminance(raw, k, pixels, luma) {
  const out = new Float64Array(pixels);
  for (let i = 0, at = 3 * k * pixels; i < pixels; i++, at += 3) {
    out[i] = raw[at] * luma[0] + raw[at + 1] * luma[1] + raw[at + 2] * luma[2];
  }
  return out;
}

const variance = (raw, pixels, i) => raw[3 * (2 * pixels + i)]; // channel 0 of image 2

/** judge_render on a stacked render `raw` and the reference: {passed, message, stats}. */
export function judgeRender(check, raw, luma) {
  const { reference, zones } = prepared(check);
  const { samples, factor } = check.options;
  const passes = check.passes;
  const pixels = check.size * check.size;
  let bad = 0;
  for (let i = 0; i < pixels; i++) {
    if (zones[i] === OFF) continue;
    let wrong = false;
    for (let k = 0; k < 3; k++) {
      for (let c = 0; c < 3; c++) {
        const x = raw[3 * (k * pixels + i) + c];
        if (!Number.isFinite(x) || x < 0) wrong = true;
      }
    }
    bad += wrong;
  }
  const words = check.words; // lab/grading/words.py SAMPLING's render_* templates
  if (bad) return { passed: false, message: fill(words.render_bad, { count: bad }), stats: {} };
  const mine = luminance(raw, 1, pixels, luma);
  const ref = luminance(reference, 1, pixels, luma);
  // render_errors: over the sphere.
  let [sumMine, sumRefVar, sumRef, count] = [0, 0, 0, 0];
  for (let i = 0; i < pixels; i++) {
    if (zones[i] === OFF) continue;
    const d = mine[i] - ref[i];
    sumMine += variance(raw, pixels, i) * (1 - 1 / passes) + d * d - variance(reference, pixels, i) / passes;
    sumRefVar += variance(reference, pixels, i);
    sumRef += ref[i];
    count++;
  }
  const scale = Math.max(sumRef / count, 1e-12);
  const errorMine = Math.sqrt(Math.max(sumMine / count, 0)) / scale;
  const errorTheirs = Math.sqrt(sumRefVar / count) / scale;
  // bias_z: per group (the rings, then the whole sphere).
  const groups = check.groups.map(() => ({ d: 0, v: 0, v2: 0, ref: 0, n: 0 }));
  const whole = groups.length - 1;
  for (let i = 0; i < pixels; i++) {
    if (zones[i] === OFF) continue;
    const d = mine[i] - ref[i];
    const v = (variance(raw, pixels, i) + variance(reference, pixels, i)) / passes;
    for (const g of [groups[zones[i]], groups[whole]]) {
      g.d += d;
      g.v += v;
      g.v2 += v * v;
      g.ref += ref[i];
      g.n++;
    }
  }
  const z = groups.map((g) => g.d / Math.sqrt(Math.max(g.v, 1e-30)));
  const limits = groups.map((g) => tLimit(check.z_normal, ((passes - 1) * g.v ** 2) / Math.max(g.v2, 1e-300)));
  let worst = 0;
  z.forEach((value, k) => {
    if (Math.abs(value) / limits[k] > Math.abs(z[worst]) / limits[worst]) worst = k;
  });
  const limit = limits[worst];
  const g = groups[worst];
  const rel = g.d / g.n / Math.max(Math.abs(g.ref / g.n), 1e-12);
  const ratio = errorMine / Math.max(errorTheirs, 1e-12);
  const stats = { noise_ratio: ratio, largest_z: Math.abs(z[worst]), z_limit: limit };
  const noise = fill(words.render_noise, { samples, mine: 100 * errorMine, theirs: 100 * errorTheirs, factor });
  if (Math.abs(z[worst]) > limit) {
    const said = { total: samples * passes, group: check.groups[worst], rel: 100 * rel, z: z[worst], limit, noise };
    return { passed: false, stats, message: fill(words.render_biased, said) };
  }
  if (errorMine > factor * errorTheirs) {
    return { passed: false, stats, message: fill(words.render_noisy, { noise, ratio }) };
  }
  return { passed: true, stats, message: fill(words.render_passes, { noise, z: Math.abs(z[worst]), limit }) };
}

/** Mean luminance per ring of equal view angle of the converged image (ring_means). */
export function ringMeans(check, raw, luma) {
  const { rings } = prepared(check);
  const pixels = check.size * check.size;
  const count = check.ring_count;
  const sum = new Float64Array(count);
  const n = new Float64Array(count);
  // As the grader stores a render (IBLRenderKind.stored): NaN and infinities as ±3e38.
  const clean = (x) => (Number.isNaN(x) ? 3e38 : Math.min(Math.max(x, -3e38), 3e38));
  for (let i = 0; i < pixels; i++) {
    if (rings[i] === OFF) continue;
    const at = 3 * (pixels + i);
    sum[rings[i]] += clean(raw[at]) * luma[0] + clean(raw[at + 1]) * luma[1] + clean(raw[at + 2]) * luma[2];
    n[rings[i]]++;
  }
  return Array.from(sum, (s, r) => (n[r] ? s / n[r] : 0));
}

/** The stored mistake whose estimator converges like the student's, the closest (nearest,
 * ring_deviation), as a "Likely: ..." sentence, or "". */
export function nearestRender(check, exercise, raw, luma) {
  const mine = ringMeans(check, raw, luma);
  let [best, bestOff] = [null, check.same_render];
  for (const [key, theirs] of Object.entries(check.ring_means)) {
    const mean = theirs.reduce((s, t) => s + Math.abs(t), 0) / theirs.length;
    const off = Math.max(...theirs.map((t, r) => Math.abs(mine[r] - t) / Math.max(Math.abs(t), 0.2 * mean + 1e-12)));
    if (off <= bestOff) [best, bestOff] = [key, off];
  }
  return best ? sentence(exercise.hints[best]) : "";
}

/** A small hash of the student's text (FNV-1a, 24 bits): the page's salt of the seed. */
function salt(text) {
  let h = 0x811c9dc5;
  for (let i = 0; i < text.length; i++) h = Math.imul(h ^ text.charCodeAt(i), 0x01000193) >>> 0;
  return h & 0xffffff;
}

const ENV_TERMS = "terms/environment.glsl";

/** Renders the check's passes with the student's sampler (sampling.render_raw): the stacked
 * (3, size, size, 3) float32 render, top row first; or {loop} where the guard stopped one. */
export async function renderPasses(panel, check, exercise = {}) {
  const lab = panel.lab;
  const { samples, environment } = check.options;
  const size = check.size;
  const map = await loadEnvironment(environment, lab.environments, lab.constants.LUMA);
  const gl = panel.gl;
  const env = environmentTextures(gl, map);
  const brdf = STRATEGIES.indexOf("brdf");
  // The environment terms before the view, as the grader's IBL renderer puts them; an
  // estimator's stand-in map (the page's other views lack one) leaves, its line kept blank.
  const standIn = exercise.estimator?.stand_in.trim();
  const transform = (source) => {
    if (standIn) source.lines = source.lines.map((line) => (line.trim() === standIn ? "" : line));
    insertBeforeView(source, [[lab.files[ENV_TERMS], `shaders/${ENV_TERMS}`]]);
  };
  const seed = (check.seed + salt(panel.model.code)) % 2 ** 30;
  const pixels = size * size;
  const raw = new Float32Array(9 * pixels);
  const total = new Float64Array(3 * pixels);
  const lum = Array.from({ length: check.passes }, () => new Float64Array(pixels));
  const luma = lab.constants.LUMA;
  try {
    for (let p = 0; p < check.passes; p++) {
      const out = topFirst(panel.run("ibl", size, size, {
        u_env: 0, u_density: 1, u_marginal: 2, u_conditional: 3, u_env_size: env.size, u_resolution: [size, size],
        u_rotation: (check.rotation * Math.PI) / 180, u_strategy: brdf, u_spp: samples, u_frame: p, u_sample0: p * samples, u_seed: seed,
      }, { preamble: `#define LAB_STRATEGY ${brdf}`, transform, textures: env.list, tag: "ibl_check" }), size, size);
      if (panel.lastLoop) return { loop: panel.lastLoop };
      for (let i = 0; i < pixels; i++) {
        let y = 0;
        for (let c = 0; c < 3; c++) {
          const one = out[4 * i + c] / samples; // this pass's mean
          if (p === 0) raw[3 * i + c] = one;
          total[3 * i + c] += one;
          y += one * luma[c];
        }
        lum[p][i] = y;
      }
    }
  } finally {
    env.list.forEach((t) => gl.deleteTexture(t));
  }
  for (let i = 0; i < pixels; i++) {
    for (let c = 0; c < 3; c++) raw[3 * (pixels + i) + c] = total[3 * i + c] / check.passes;
    let mean = 0;
    for (const l of lum) mean += l[i] / check.passes;
    let sq = 0;
    for (const l of lum) sq += (l[i] - mean) ** 2;
    raw[3 * (2 * pixels + i)] = sq / (check.passes - 1); // ddof = 1
  }
  return { raw };
}

/** Runs the check on the panel (its values already the check's): {passed, message,
 * renders} as the grader judges and pictures it, or {loop} (a loop the guard stopped). */
export async function runIblRender(panel, check, exercise) {
  const { raw, loop } = await renderPasses(panel, check, exercise);
  if (loop) return { loop }; // exercise.js says where, as the grader
  const luma = panel.lab.constants.LUMA;
  const result = judgeRender(check, raw, luma);
  if (!result.passed) {
    const likely = nearestRender(check, exercise, raw, luma);
    if (likely) result.message += `. ${likely}`;
  }
  const { reference } = prepared(check);
  const size = check.size;
  const image = (stack, k) => stack.subarray(3 * k * size * size, 3 * (k + 1) * size * size);
  // What the page does not do as the grader does, said plainly beside the pictures.
  result.note = "The page draws other random numbers than brdf-lab grade (the grader salts the seed with its " +
    "preprocessed text of your file): the figures differ from the grader's by noise, and a verdict at the " +
    "limit may differ. The page names a likely mistake only by how its render converges (ring means); the " +
    "grader also tests your render against each stored mistake's. brdf-lab grade decides.";
  const caption = check.captions; // the grader's report captions (IBLRenderKind.captions)
  result.renders = [[caption["converged reference"], reference, 1], [caption.solution, reference, 0],
    [caption.yours, raw, 0], [caption["yours, converged"], raw, 1]].map(([title, stack, k]) => ({ title, size, rgb: image(stack, k) }));
  return result;
}

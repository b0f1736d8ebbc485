// Exercise 10's IBL render check in the page (practice): the sphere under the environment
// with the student's sampler alone (views/ibl.glsl before terms/environment.glsl, BRDF
// sampling, the grader's seeds), at equal samples and converged, judged against the
// committed reference as lab/grading/sampling.py judge_render does (sampling.js runs it).
import { sentence } from "./diagnosis.js";
import { formatDigits as gFormat } from "./header.js";
import { STRATEGIES, environmentTextures, insertBeforeView, loadEnvironment } from "./iblsource.js";
import { topFirst } from "./views.js";

const ENV_UNIT = 8; // texture units of the environment, as the IBL view's
const RINGS = 16;
const SAME_RENDER = 0.05;

/** The sphere's pixels (row 0 at the top): the mask and the view angle θ (local_view). */
function sphereView(size) {
  const mask = new Uint8Array(size * size);
  const theta = new Float64Array(size * size);
  for (let row = 0; row < size; row++) {
    for (let col = 0; col < size; col++) {
      const x = ((col + 0.5) / size) * 2 - 1;
      const y = -(((row + 0.5) / size) * 2 - 1);
      const r2 = x * x + y * y;
      mask[row * size + col] = r2 <= 1 ? 1 : 0;
      const z = Math.sqrt(Math.min(Math.max(1 - r2, 0), 1));
      theta[row * size + col] = (Math.acos(Math.min(Math.max(z, -1), 1)) * 180) / Math.PI;
    }
  }
  return { mask, theta };
}

/** The student's estimator at `spp` samples per pixel: RGB per pixel, row 0 at the top. */
async function renderPass(panel, check, env, spp, seed) {
  const { lab, C } = env;
  const map = await loadEnvironment(check.options.environment, lab.environments, C.LUMA);
  const gl = panel.gl;
  const { list, size: envSize } = environmentTextures(gl, map);
  const textures = [];
  list.forEach((t, k) => (textures[ENV_UNIT + k] = t));
  const size = check.size;
  try {
    const out = panel.run("ibl", size, size, { u_resolution: [size, size], u_rotation: 0,
      u_strategy: STRATEGIES.indexOf("brdf"), u_spp: spp, u_frame: 0, u_seed: seed, u_env: ENV_UNIT,
      u_density: ENV_UNIT + 1, u_marginal: ENV_UNIT + 2, u_conditional: ENV_UNIT + 3, u_env_size: envSize },
    { preamble: "// the ibl_render check", transform: withEstimator(lab.files), textures });
    const image = topFirst(out, size, size);
    const rgb = new Float64Array(3 * size * size);
    for (let i = 0; i < size * size; i++) {
      for (let c = 0; c < 3; c++) rgb[3 * i + c] = image[4 * i + c] / spp;
    }
    return rgb;
  } finally {
    list.forEach((t) => gl.deleteTexture(t));
  }
}

/** terms/environment.glsl (the estimator) before the view; the sampler is the model's. */
function withEstimator(files) {
  return (source) => insertBeforeView(source, [[files["terms/environment.glsl"], "shaders/terms/environment.glsl"]]);
}

const luminance = (rgb, i, luma, clean) => {
  let sum = 0;
  for (let c = 0; c < 3; c++) sum += luma[c] * clean(rgb[3 * i + c]);
  return sum;
};
const asIs = (v) => v;
const finite = (big) => (v) => (Number.isNaN(v) ? big : v === Infinity ? big : v === -Infinity ? -big : v);

function relativeRms(image, reference, mask, luma) {
  let mean = 0;
  let count = 0;
  let squares = 0;
  for (let i = 0; i < mask.length; i++) {
    if (!mask[i]) continue;
    const ref = luminance(reference, i, luma, asIs);
    mean += ref;
    count++;
    squares += (luminance(image, i, luma, finite(1e9)) - ref) ** 2;
  }
  return Math.sqrt(squares / count) / Math.max(mean / count, 1e-9);
}

function ringMeans(image, view, luma) {
  const sum = new Float64Array(RINGS);
  const count = new Float64Array(RINGS);
  for (let i = 0; i < view.mask.length; i++) {
    if (!view.mask[i]) continue;
    const ring = Math.min(Math.floor((view.theta[i] / 90) * RINGS), RINGS - 1);
    sum[ring] += luminance(image, i, luma, (v) => (Number.isNaN(v) ? 0 : finite(1e6)(v)));
    count[ring]++;
  }
  return Array.from(sum, (s, r) => (count[r] ? s / count[r] : 0));
}

function ringDeviation(image, reference, view, luma) {
  const mine = ringMeans(image, view, luma);
  const theirs = ringMeans(reference, view, luma);
  const mean = theirs.reduce((s, v) => s + Math.abs(v), 0) / RINGS;
  return Math.max(...mine.map((m, r) => Math.abs(m - theirs[r]) / Math.max(Math.abs(theirs[r]), 0.2 * mean + 1e-12)));
}

/** The committed reference: the solution's render at equal samples and converged (RGB
 * half floats, row 0 at the top). */
function referenceImages(check) {
  const bytes = Uint8Array.from(atob(check.reference), (c) => c.charCodeAt(0));
  const halves = new Uint16Array(bytes.buffer);
  const half = (h) => {
    const e = (h >> 10) & 31;
    const f = h & 1023;
    const v = e === 0 ? f * 2 ** -24 : e === 31 ? (f ? NaN : Infinity) : (1 + f / 1024) * 2 ** (e - 15);
    return h & 0x8000 ? -v : v;
  };
  const n = halves.length / 2;
  return [0, 1].map((k) => Float64Array.from(halves.subarray(k * n, (k + 1) * n), half));
}

export async function iblRender(panel, check, exercise, env) {
  const o = check.options;
  const luma = env.C.LUMA;
  const view = sphereView(check.size);
  const raw = [await renderPass(panel, check, env, o.samples, check.seed),
    await renderPass(panel, check, env, o.converged, check.seed + 1000)];
  check.referenceImages ??= referenceImages(check);
  const [atSamples, converged] = check.referenceImages;
  let bad = 0;
  for (let i = 0; i < view.mask.length; i++) {
    if (view.mask[i] && raw.some((img) => [0, 1, 2].some((c) => !(img[3 * i + c] >= 0) || img[3 * i + c] === Infinity))) bad++;
  }
  if (bad) return { passed: false, message: `${bad} pixels of the sphere are NaN, infinite or negative` };
  const mine = relativeRms(raw[0], converged, view.mask, luma);
  const theirs = relativeRms(atSamples, converged, view.mask, luma);
  const limit = ringDeviation(raw[1], converged, view, luma);
  let message = `at ${o.samples} samples per pixel your render is ${(100 * mine).toFixed(1)}% RMS off the converged ` +
    `reference, the solution's ${(100 * theirs).toFixed(1)}% (allowed ${gFormat(o.factor, 6)}×); your estimator ` +
    `converges to within ${(100 * limit).toFixed(1)}% of it (allowed ${gFormat(100 * o.bias, 6)}%)`;
  let passed = true;
  if (limit > o.bias) [passed, message] = [false, `${message}: it is biased — the pdf does not match what the sampler draws`];
  else if (mine > o.factor * theirs) [passed, message] = [false, `${message}: more noise than the solution's sampler`];
  if (!passed) {
    // The known mistake whose estimator converges like the student's (kinds/ibl_render nearest).
    let likely = "";
    let best = SAME_RENDER;
    for (const [key, images] of Object.entries(check.stored?.candidates || {})) {
      if (!(key in (exercise.hints || {}))) continue;
      const other = Float64Array.from(images.subarray(images.length / 2));
      if (other.length !== raw[1].length) continue;
      const off = ringDeviation(raw[1], other, view, luma);
      if (off <= best) [likely, best] = [sentence(exercise.hints[key]), off];
    }
    if (likely) message += `. ${likely}`;
  }
  const size = check.size;
  const renders = [["the solution's estimator, converged", converged], ["the solution's sampler at the same samples", atSamples],
    ["your sampler at the same samples", raw[0]], ["your estimator run longer: what it converges to", raw[1]]];
  return { passed, message, renders: renders.map(([title, rgb]) => ({ title, size, rgb })) };
}

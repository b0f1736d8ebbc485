// Exercise mode: open an exercise, edit its stub in the page, and run the grader's checks
// in WebGL as a practice check (not a grade: `brdf-lab grade` decides). exercises.json
// (lab/web/exercises.py) carries each check's inputs, computed by the grader's own code,
// and the committed references; the comparisons here follow lab/grading/checks.py
// (compare_values, compare_image) with the same tolerances and messages.
import { floatTexture } from "./assemble.js";
import { ModelError, defaults, formatG } from "./header.js";
import { buildSubmission } from "./submission.js";
import { topFirst } from "./viewkit.js";
import { el } from "./dom.js";
import { direction } from "./geometry.js";
import { addPanel, removePanel } from "./panels.js";
import { explain, loopStopped, prepare, rows, useRules } from "./diagnosis.js";
import { meanFlip } from "./flip.js";
import { SAMPLED_KINDS, prepareSampled, runSampled } from "./sampling.js";
import { diagnoseProperties, runProperties, valuesFigure } from "./properties.js";
import { objectInputs, prepareObject, unreadTextures } from "./objectcheck.js";
import { Tables } from "./tables.js";
import { diagnoseSh, runSh, shFigure } from "./shcheck.js";

const fromBase64 = (text, Type) => {
  const bytes = Uint8Array.from(atob(text), (c) => c.charCodeAt(0));
  return new Type(bytes.buffer);
};

const PENDING = "not run for this version: press “run the sampling checks” (they take seconds)";
// Checks that run on request (seconds, not every keystroke): sampling.js's and iblcheck.js's.
const ON_REQUEST = [...SAMPLED_KINDS, "ibl_render"];
// Checks judged as images (compare_image): the sphere's and the textured object's.
const IMAGE_KINDS = ["sphere", "object"];

// -- comparisons (lab/grading/checks.py) -----------------------------------------------------
const tonemap = (x) => {
  x = Number.isNaN(x) ? 0 : x === Infinity ? 1e30 : Math.max(x, 0);
  return Math.pow(x / (1 + x), 1 / 2.2);
};

/** compare_values: within atol + rtol |expected| (or the row's own tolerance, grown where
 * the exact answer is ill-conditioned), NaN/Inf/negative always wrong. */
export function compareValues(check, expected, got) {
  const n = check.count;
  if (check.tolerance && !check.toleranceValues) {
    check.toleranceValues = fromBase64(check.tolerance, Float32Array);
  }
  const tolerance = check.toleranceValues;
  let bad = 0;
  let wrong = 0;
  for (let i = 0; i < n; i++) {
    let isBad = false;
    let isWrong = false;
    for (let c = 0; c < 3; c++) {
      const g = got[4 * i + c];
      const e = expected[3 * i + c];
      if (!Number.isFinite(g) || g < 0) isBad = true;
      const error = Number.isNaN(g) ? Infinity : Math.abs(g - e);
      const allowed = tolerance ? tolerance[3 * i + c] : check.atol + check.rtol * Math.abs(e);
      if (error > allowed) isWrong = true;
    }
    bad += isBad;
    wrong += isBad || isWrong;
  }
  if (bad) {
    return { passed: false, message: `${bad} of ${n} ${check.what} are NaN, infinite or negative; ` +
      "a BRDF is finite and >= 0 (guard divisions and pow of negatives)" };
  }
  if (wrong) {
    return { passed: false, message: `${wrong} of ${n} ${check.what} differ from the solution by more than ` +
      `${formatG(check.rtol)} x value + ${formatG(check.atol)}` };
  }
  return { passed: true, message: `all ${n} ${check.what} match` };
}

/** compare_image: tone-mapped per-channel threshold, a largest failing fraction and the
 * mean FLIP of the tone-mapped image (`student8`, RGBA bytes) against the reference;
 * returns the signed difference (student - reference) too. */
export function compareImage(check, reference, raw, student8) {
  const size = check.size;
  const signed = new Float32Array(size * size);
  const covered = new Uint8Array(size * size);
  let nCovered = 0;
  let failing = 0;
  let bad = 0;
  let largest = 0;
  for (let i = 0; i < size * size; i++) {
    if (reference[4 * i + 3] <= 127) continue;
    covered[i] = 1;
    nCovered++;
    let pick = 0;
    let isBad = false;
    for (let c = 0; c < 3; c++) {
      const x = raw[4 * i + c];
      if (!Number.isFinite(x) || x < 0) isBad = true;
      const delta = (tonemap(x) - reference[4 * i + c] / 255) * 255;
      if (Math.abs(delta) > Math.abs(pick)) pick = delta;
    }
    if (isBad) {
      bad++;
      pick = 255;
    }
    signed[i] = pick;
    largest = Math.max(largest, Math.abs(pick));
    if (Math.abs(pick) > check.threshold) failing++;
  }
  // As the grader: FLIP only where some pixel differs at all.
  const flip = failing || largest >= 1 ? meanFlip(reference, student8, size) : 0;
  const fraction = failing / Math.max(nCovered, 1);
  const summary = `${(100 * fraction).toFixed(2)}% of pixels off by more than ${formatG(check.threshold)}/255 ` +
    `(allowed ${(100 * check.max_fraction).toFixed(2)}%), mean FLIP ${flip.toFixed(4)}`;
  const out = { signed, covered, fraction, flip };
  if (bad) return { ...out, passed: false, message: `${bad} pixels are NaN, infinite or negative (magenta); ${summary}` };
  return { ...out, passed: fraction <= check.max_fraction, message: summary };
}

// The report's colours (lab/grading/visuals.py): red too bright, blue too dark.
const TOO_BRIGHT = [0.85, 0.15, 0.1];
const TOO_DARK = [0.1, 0.35, 0.95];
const SCALE = 8;

export function signedDifferenceImage(signed, covered, size, threshold) {
  const image = new ImageData(size, size);
  for (let i = 0; i < size * size; i++) {
    const d = signed[i];
    let rgb = [1, 1, 1];
    if (covered[i]) {
      const amount0 = Math.min(Math.max(Math.abs(d) / (SCALE * threshold), 0), 1);
      const amount = Math.abs(d) > threshold ? 0.25 + 0.75 * amount0 : 0.25 * amount0;
      const colour = d >= 0 ? TOO_BRIGHT : TOO_DARK;
      rgb = colour.map((c) => 0.93 * (1 - amount) + c * amount);
    }
    for (let c = 0; c < 3; c++) image.data[4 * i + c] = Math.round(rgb[c] * 255);
    image.data[4 * i + 3] = 255;
  }
  return image;
}

function toneImage(raw, size) {
  const image = new ImageData(size, size);
  for (let i = 0; i < size * size; i++) {
    for (let c = 0; c < 3; c++) image.data[4 * i + c] = Math.floor(Math.min(Math.max(tonemap(raw[4 * i + c]), 0), 1) * 255 + 0.5);
    image.data[4 * i + 3] = Math.round(Math.min(Math.max(raw[4 * i + 3], 0), 1) * 255);
  }
  return image;
}

/** The grader's message for a loop its guard stopped (lab/grading/checks.py). */
function loopFailure(check, panel, where) {
  const line = panel.lastLoop.line;
  const file = panel.model.path.split("/").pop();
  const limit = panel.model.loopLimit ?? panel.lab.constants.LOOP_LIMIT;
  return { passed: false, message: loopStopped(file, line, limit, where, panel.lab.constants) };
}

/** stopped_where for a sphere pixel (x, y from the bottom, as read back). */
function sphereWhere(check, stop) {
  const px = ((stop.x + 0.5) / check.size) * 2 - 1;
  const py = ((stop.y + 0.5) / check.size) * 2 - 1;
  const n = [px, py, Math.sqrt(Math.max(1 - px * px - py * py, 0))];
  const light = check.lights[0] || [45, 0];
  const l = direction(light[0], light[1]);
  const deg = (c) => ((Math.acos(Math.min(Math.max(c, -1), 1)) * 180) / Math.PI).toFixed(1);
  const thetaI = deg(n[0] * l[0] + n[1] * l[1] + n[2] * l[2]);
  return `pixel (${stop.x}, ${check.size - 1 - stop.y}) of the sphere (θi = ${thetaI}°, θo = ${deg(n[2])}°)`;
}

/** The panel's model at direction pairs (flat degrees: θi, φi, θo, φo per row) as RGBA
 * floats. The directions are made here in double precision (the probe view): built-in sin
 * and cos are coarse on some GPUs (SwiftShader), the grader's llvmpipe's are not. */
function probeValues(panel, degrees, n) {
  const gl = panel.gl;
  const L = new Float32Array(4 * n);
  const V = new Float32Array(4 * n);
  for (let i = 0; i < n; i++) {
    L.set(direction(degrees[4 * i], degrees[4 * i + 1]), 4 * i);
    V.set(direction(degrees[4 * i + 2], degrees[4 * i + 3]), 4 * i);
  }
  const textures = [floatTexture(gl, n, 1, L), floatTexture(gl, n, 1, V)];
  try {
    return panel.run("probe", n, 1, { u_L: 0, u_V: 1 }, { textures });
  } finally {
    textures.forEach((t) => gl.deleteTexture(t));
  }
}

/** The grader's diagnosis of a failed check ('Likely: ...' or ''), from the stored
 * references as `brdf-lab grade` reads them; the student's model renders what it needs. */
function diagnose(panel, exercise, check, result) {
  const C = panel.lab.constants;
  if (IMAGE_KINDS.includes(check.kind)) {
    const said = explain(exercise, check, null, result.student.data, null, null, C.LUMA);
    return said || check.kind !== "object" ? said : unreadTextures(panel, check);
  }
  const degrees = fromBase64(check.angles, Float32Array);
  const angles = rows4(degrees, check.count);
  const evaluate = (params, at) => {
    const saved = panel.values;
    panel.values = checkValues(panel.model, params);
    try {
      const flat = at ? Float32Array.from(at.flat()) : degrees;
      return rows(probeValues(panel, flat, check.count), check.count, 4);
    } finally {
      panel.values = saved;
    }
  };
  const expected = rows(check.expectedValues, check.count);
  return explain(exercise, check, expected, rows(result.got, check.count, 4), angles, evaluate, C.LUMA);
}

const rows4 = (flat, n) => Array.from({ length: n }, (_, i) => Array.from(flat.subarray(4 * i, 4 * i + 4)));

/** Check parameters as the panel holds values (colours as arrays). */
function checkValues(model, params) {
  return { ...defaults(model), ...params };
}

/** Runs one check on the panel (its model is the submission); {passed, message, ...}. */
export function runCheck(panel, check, submission = panel.model) {
  if (check.kind === "properties" || check.kind === "sh") {
    // The student's file linked with the check's model, judged and diagnosed (properties.js, shcheck.js).
    const result = (check.kind === "sh" ? runSh : runProperties)(panel, check, submission);
    return result.loop ? loopFailure(check, panel, result.loop) : result;
  }
  const saved = panel.values;
  panel.values = checkValues(panel.model, check.params);
  try {
    if (IMAGE_KINDS.includes(check.kind)) {
      const C = panel.lab.constants;
      const dirs = [];
      const rgb = [];
      for (let i = 0; i < C.MAX_LIGHTS; i++) {
        const light = check.lights[i];
        dirs.push(light ? direction(light[0], light[1]) : [0, 0, 1]);
        rgb.push(light ? light[2] : [0, 0, 0]);
      }
      const size = check.size;
      // An object check also binds its textures and sets its shape and turn (objectcheck.js).
      const object = check.kind === "object" ? objectInputs(panel.gl, check) : { uniforms: {}, textures: [] };
      const raw = topFirst(panel.run(check.view, size, size, { u_resolution: [size, size], u_light_dir: dirs,
        u_light_rgb: rgb, u_ambient: check.ambient, u_multiply_cos: true, ...object.uniforms },
      { preamble: `const int LIGHT_COUNT = ${check.lights.length};`, textures: object.textures }), size, size);
      check.referencePixels ??= fromBase64(check.reference, Uint8Array);
      if (panel.lastLoop) {
        const stop = panel.lastLoop;
        const where = check.kind === "object" ? `pixel (${stop.x}, ${size - 1 - stop.y}) of the object` : sphereWhere(check, stop);
        return loopFailure(check, panel, where);
      }
      const student = toneImage(raw, size);
      const result = compareImage(check, check.referencePixels, raw, student.data);
      return { ...result, student, compared: true };
    }
    const degrees = fromBase64(check.angles, Float32Array);
    const got = probeValues(panel, degrees, check.count);
    if (panel.lastLoop) {
      const k = Math.min(panel.lastLoop.x, check.count - 1);
      const row = degrees.slice(4 * k, 4 * k + 4);
      const where = `(θi, φi, θo, φo) = (${[...row].map((d) => `${d.toFixed(1)}°`).join(", ")})`;
      return loopFailure(check, panel, where);
    }
    check.expectedValues ??= fromBase64(check.expected, Float32Array);
    return { ...compareValues(check, check.expectedValues, got), compared: true, got };
  } finally {
    panel.values = saved;
  }
}

// -- the page's exercise section -----------------------------------------------------------
export class ExerciseMode {
  /** Practice mode in `root` for the page's `lab` (state.js); `openEditor(panel, stub,
   * options)` opens the editor on the exercise's panel (editing.js). */
  constructor(root, lab, openEditor) {
    this.root = root;
    this.lab = lab;
    this.openEditor = openEditor;
    this.data = null;
    this.exercise = null;
    this.panel = null;
    this.results = [];
    this.runs = 0;
  }

  async load() {
    if (!this.data) {
      const response = await fetch("exercises.json");
      if (!response.ok) throw new Error(`cannot load exercises.json (HTTP ${response.status})`);
      this.data = await response.json();
      useRules(this.data.diagnosis);
    }
    return this.data.exercises;
  }

  /** Opens exercise `name`: its stub in the editor, its model in a panel, the checks run. */
  async open(name) {
    const lab = this.lab;
    const exercise = (await this.load()).find((e) => e.name === name);
    if (!exercise) throw new Error(`no exercise ${name}`);
    await prepare(exercise); // the stored mistakes' values, inflated once
    for (const check of exercise.checks) await prepareObject(check); // its textures
    this.exercise = exercise;
    const path = exercise.student_file;
    const tables = new Tables(null, exercise.checks); // made once the panel is (its GPU's)
    lab.models[exercise.name] = tables.bindTo(buildSubmission(exercise, exercise.stub, path, lab.models));
    if (!lab.order.includes(exercise.name)) lab.order.push(exercise.name);
    // One exercise at a time: the last one's panel goes (else, exercise after exercise, the
    // page runs out of panels and the next one cannot open).
    this.tables?.release(); // the last exercise's tables, while their panel is there
    if (this.panel && this.panel.name !== exercise.name && lab.panels.includes(this.panel)) {
      removePanel(lab, this.panel);
    }
    this.panel = lab.panels.find((p) => p.name === exercise.name) || addPanel(lab, exercise.name);
    this.tables = Object.assign(tables, { panel: this.panel });
    if (tables.needed) { // exercise 12: its checks' tables, made here (tables.js), the tab busy for a moment
      this.root.replaceChildren(el("p", { class: "practice-note", role: "status" }, "building table…"));
      this.root.hidden = false;
      await new Promise((resolve) => setTimeout(resolve, 30)); // the words show first
      tables.build();
    }
    lab.requestRender();
    await this.openEditor(this.panel, exercise.stub, {
      path,
      text: exercise.stub,
      // The last text's model even when the panel's compile of it fails: checks that link it
      // with models of their own compile it their way (properties.js).
      build: (text) => {
        this.built = null;
        this.built = tables.bindTo(buildSubmission(exercise, text, path, lab.models));
        return this.built;
      },
      onResult: (errors) => this.run(errors),
    });
  }

  /** Runs every check (or reports the compile errors on each, as the grader does). */
  run(errors = []) {
    const exercise = this.exercise;
    if (!exercise || !this.panel?.model) return [];
    this.errors = errors;
    // A file the panel cannot compile alone may still link (the grader links it with each
    // check's model, never compiles it alone): those checks compile it their way.
    const built = this.built ?? this.panel.model;
    this.results = exercise.checks.map((check) => {
      if (errors.length && !(check.linked_with && built)) {
        const first = errors[0];
        return { check, passed: false, message: `the shader does not compile: ${exercise.student_file}:${first.line}: ${first.message}` };
      }
      // The sampling checks run on request (seconds, not every keystroke).
      if (ON_REQUEST.includes(check.kind)) return { check, passed: false, pending: true, message: PENDING };
      if (!this.tables.use(check)) return { check, passed: false, message: this.tables.error ?? "building table…" };
      try {
        const result = runCheck(this.panel, check, built);
        if (result.compared && !result.passed) {
          // As the grader: the likely mistake ends the message (a diagnosis never breaks a check).
          try {
            result.diagnosis = diagnose(this.panel, exercise, check, result);
          } catch (err) {
            if (err.errors === undefined && !(err instanceof ModelError)) console.warn(err);
            result.diagnosis = "";
          }
          if (result.diagnosis) result.message += `. ${result.diagnosis}`;
        }
        return { check, ...result };
      } catch (err) {
        if (!err.errors && !(err instanceof ModelError)) throw err;
        return { check, passed: false, message: `the shader does not compile: ${err.message.split("\n")[0]}` };
      }
    });
    diagnoseProperties(exercise, this.results); // across its checks
    diagnoseSh(exercise, this.results);
    this.runs++;
    this.show();
    return this.results;
  }

  /** Runs the sampling checks (chi-square, pdf integral, IBL render) of this version. */
  async runSampling() {
    const waiting = this.results.filter((r) => r.pending);
    for (const result of waiting) await prepareSampled(result.check);
    for (const result of waiting) {
      const panel = this.panel;
      const saved = panel.values;
      panel.values = checkValues(panel.model, result.check.params);
      try {
        if (result.check.kind === "ibl_render") {
          // Loaded when first asked for (it brings the IBL sources), not with the page.
          const { runIblRender } = await import("./iblcheck.js");
          const out = await runIblRender(panel, result.check, this.exercise);
          const { x, y } = out.loop ?? {};
          Object.assign(result, out.loop ? loopFailure(result.check, panel, `pixel (${x}, ${y}) of the render (row 0 at ` +
            "the bottom)") : out, { pending: false });
          continue;
        }
        const out = await runSampled(panel, result.check, this.exercise);
        const limit = panel.model.loopLimit ?? panel.lab.constants.LOOP_LIMIT;
        Object.assign(result, out.loop ? { passed: false, message: loopStopped(this.exercise.student_file,
          out.loop.line, limit, `sample ${out.loop.sample}`, panel.lab.constants) } : out, { pending: false });
      } catch (err) {
        if (!err.errors && !(err instanceof ModelError)) throw err;
        Object.assign(result, { passed: false, pending: false, message: `the shader does not compile: ${err.message.split("\n")[0]}` });
      } finally {
        panel.values = saved;
      }
    }
    this.sampled = (this.sampled || 0) + 1;
    this.show();
    return this.results;
  }

  show() {
    const exercise = this.exercise;
    const points = this.results.reduce((s, r) => s + (r.passed ? r.check.points : 0), 0);
    const rows = this.results.map((r) => el("li", { class: r.pending ? "pending" : r.passed ? "pass" : "fail",
      "data-check": r.check.name },
      el("span", { class: "mark" }, r.pending ? "…" : r.passed ? "✓" : "✗"), " ",
      el("strong", {}, r.check.name), ` (${formatG(r.passed ? r.check.points : 0)}/${formatG(r.check.points)}): `,
      r.message));
    const pictures = [];
    for (const r of this.results) {
      if (!IMAGE_KINDS.includes(r.check.kind) || !r.signed) continue;
      const size = r.check.size;
      const canvas = (image, title) => {
        const c = el("canvas", { width: size, height: size, title, role: "img", "aria-label": title });
        c.getContext("2d").putImageData(image, 0, 0);
        return el("figure", {}, c, el("figcaption", {}, title));
      };
      const ref = r.check.referencePixels;
      const reference = new ImageData(new Uint8ClampedArray(ref.buffer.slice(0)), size, size);
      pictures.push(el("div", { class: "exercise-images", "data-check": r.check.name },
        canvas(reference, `reference: ${r.check.name}`), canvas(r.student, "yours"),
        canvas(signedDifferenceImage(r.signed, r.covered, size, r.check.threshold),
          `yours − reference (red: too bright, blue: too dark; ±${formatG(r.check.threshold)}/255 allowed)`)));
    }
    // A sampling check's pictures, as the grader's report shows them: histograms over
    // (cos θ, φ) of a chi-square test, the renders of the IBL check (tone mapped).
    for (const r of this.results) {
      const figures = [...(r.figures || []), ...(r.renders || []).map(({ title, size, rgb }) => {
        const rgba = new Uint8ClampedArray(4 * size * size);
        for (let i = 0; i < size * size; i++) {
          for (let c = 0; c < 3; c++) rgba[4 * i + c] = Math.floor(Math.min(Math.max(tonemap(rgb[3 * i + c]), 0), 1) * 255 + 0.5);
          rgba[4 * i + 3] = 255;
        }
        return { title, width: size, height: size, rgba };
      })];
      if (!figures.length) continue;
      pictures.push(el("div", { class: "exercise-images", "data-check": r.check.name }, ...figures.map((f) => {
        const c = el("canvas", { width: f.width, height: f.height, title: f.title, role: "img", "aria-label": f.title });
        c.getContext("2d").putImageData(new ImageData(f.rgba, f.width, f.height), 0, 0);
        return el("figure", {}, c, el("figcaption", {}, `${r.check.name}: ${f.title}`));
      })));
      if (r.note) pictures.push(el("p", { class: "practice-note", "data-check": r.check.name }, r.note));
    }
    // A failed properties or sh check's values beside the grader's, as its report's table.
    for (const r of this.results) {
      if (r.check.kind === "properties" && !r.passed && r.got) pictures.push(valuesFigure(r));
      if (r.check.kind === "sh" && !r.passed && r.got) pictures.push(shFigure(r)); // shcheck.js
    }
    // The checks only the grader runs, named with their points and why.
    const others = exercise.grader_only || [];
    const otherPoints = others.reduce((s, c) => s + c.points, 0);
    if (!exercise.checks.length) {
      // Nothing to compare here: the page says at least whether the file compiles.
      const first = this.errors?.[0];
      rows.push(el("li", { class: first ? "fail" : "pass", "data-check": "compile" },
        el("span", { class: "mark" }, first ? "✗" : "✓"), " ", el("strong", {}, "compile"), ": ",
        first ? `the shader does not compile: ${exercise.student_file}:${first.line}: ${first.message}`
          : "your functions compile in WebGL (GLSL ES 3.00) with the signatures the grader calls"));
    }
    const pending = this.results.some((r) => r.pending);
    const sampling = pending ? [el("button", { type: "button", class: "run-sampling",
      title: "run the chi-square, pdf integral and IBL render checks on this version (seconds)",
      onclick: (e) => {
        e.target.disabled = true;
        e.target.textContent = "running…";
        setTimeout(() => this.runSampling(), 30); // the button shows it is busy first
      } }, "run the sampling checks")] : [];
    const graded = others.map((c) => el("li", { class: "graded", "data-check": c.name },
      el("span", { class: "mark" }, "·"), " ", el("strong", {}, c.name), ` (${formatG(c.points)} points): ${c.why}`));
    const tally = exercise.checks.length ? `${formatG(points)} / ${formatG(exercise.max_points)} points` : "a compile check";
    this.root.replaceChildren(
      el("header", {}, el("strong", {}, exercise.title),
        el("span", { class: "practice" }, `practice check in the browser, not a grade (brdf-lab grade decides): ${tally}` +
          (others.length ? ` here; ${formatG(otherPoints)} more points in checks only the grader runs` : ""))),
      el("ul", { class: "checks" }, ...rows),
      // What the grader checks besides, which the page does not: said, not implied.
      el("p", { class: "practice-note" }, "Not checked here: brdf-lab grade also refuses a file that names the " +
        `lab's library beyond what the handout gives (${(exercise.api || []).join(", ") || "nothing"}).`),
      ...sampling, ...pictures,
      ...(others.length ? [el("p", { class: "grader-only" }, "Only brdf-lab grade runs these checks: ",
        el("code", {}, `brdf-lab grade exercises/${exercise.name} --submission ${exercise.student_file}`)),
      el("ul", { class: "checks" }, ...graded)] : []));
    this.root.hidden = false;
  }
}

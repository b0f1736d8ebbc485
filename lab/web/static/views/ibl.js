// The IBL view of the web lab: the lit sphere under an environment map, by progressive
// Monte Carlo integration of the reflection equation, from the desktop's own template
// (shaders/views/ibl.glsl) with the same samplers (shaders/samplers/, terms/sampling.glsl)
// and the same procedural environments (lab/ibl/environments.py, served as float data).
// Passes of samples add up in a float target (additive blending); the view shows the mean
// and the sample count, and starts again when anything it depends on changes.
import { floatTexture } from "../assemble.js";
import { toImage, topFirst } from "../viewkit.js";
import { el, viewBox } from "../dom.js";
import { STRATEGIES, STRATEGY_TITLES, chosenStrategy, environmentTextures, loadEnvironment, samplerText, withSampler } from "../iblsource.js";

export { STRATEGIES, STRATEGY_TITLES, samplerText, samplingTables } from "../iblsource.js";

const ENV_UNIT = 8; // texture units 8..11 hold the environment, as on the desktop
export const IBL_SIZE = 256; // render size (the desktop's), at most the page's sphere size
export const MAX_SAMPLES = 1024; // per pixel: the render stops there
const PASS_MS = 30; // aim of one pass, so that the page stays responsive
const RINGS = 24; // rings of equal view angle for the furnace's reflectance peak
const GAIN_SAMPLES = 64; // the furnace names an energy gain from this many samples on

/** The IBL settings of `lab` (the registry's ibl_env, ibl_strategy, ibl_sequence and
 * ibl_rotation, shared by every panel) as names: {environment, strategy, sobol, rotation}. */
export function iblSettings(lab) {
  const { settings, specs } = lab;
  return { environment: specs.ibl_env.choices[settings.ibl_env], strategy: specs.ibl_strategy.choices[settings.ibl_strategy],
    sobol: settings.ibl_sequence === 1, rotation: settings.ibl_rotation };
}

/** An older address's `ibl=ENVIRONMENT,STRATEGY,ROTATION` (any may be left out) into the
 * settings; a bad value is named in the notes and keeps its default. */
function readOldAddress(value, lab) {
  if (value === null) return;
  const [environment, strategy, rotation] = value.split(",");
  const names = lab.specs.ibl_env.choices;
  if (environment && names.includes(environment)) lab.set("ibl_env", names.indexOf(environment));
  else if (environment) lab.notes.push(`ibl=${value}: the environment is one of ${names.join(", ")}`);
  const strategies = lab.specs.ibl_strategy.choices;
  if (strategy && strategies.includes(strategy)) lab.set("ibl_strategy", strategies.indexOf(strategy));
  else if (strategy) lab.notes.push(`ibl=${value}: the strategy is one of ${strategies.join(", ")}`);
  const turn = Number(rotation);
  if (rotation && Number.isFinite(turn) && turn >= 0 && turn <= 360) lab.set("ibl_rotation", turn);
  else if (rotation) lab.notes.push(`ibl=${value}: the rotation is a number of degrees from 0 to 360`);
}

/** What the view says when the strategy needs a sampler the model lacks (integrator.fallback). */
export function fallback(model, strategy, files) {
  if (!["brdf", "mis_balance", "mis_power", "auto"].includes(strategy) || samplerText(model, files) !== null) return null;
  if (model.delta) return null;
  const used = strategy === "brdf" ? "cosine-weighted" : "MIS of cosine-weighted and environment";
  return `${model.name} has no BRDF sampler: ${used} sampling instead`;
}

/** The largest mean luminance over rings of equal view angle of a mean image (RGBA, any
 * row order): in the white furnace, the most a ring reflects (integrator.ring_peak). */
export function ringPeak(data, size, luma) {
  return Math.max(0, ...ringMeans(data, size, luma).means.filter((m) => m !== null));
}

/** Each pixel's ring of equal view angle (-1 off the sphere) and each ring's mean luminance
 * (null for a ring without pixels). */
function ringMeans(data, size, luma) {
  const sum = new Float64Array(RINGS);
  const count = new Float64Array(RINGS);
  const rings = new Int8Array(size * size).fill(-1);
  for (let y = 0; y < size; y++) {
    for (let x = 0; x < size; x++) {
      const px = ((x + 0.5) / size) * 2 - 1;
      const py = ((y + 0.5) / size) * 2 - 1;
      const r2 = px * px + py * py;
      if (r2 > 1) continue;
      const theta = (Math.acos(Math.sqrt(1 - r2)) * 180) / Math.PI;
      const ring = Math.min(Math.floor((theta / 90) * RINGS), RINGS - 1);
      const i = 4 * (y * size + x);
      rings[y * size + x] = ring;
      sum[ring] += luma[0] * data[i] + luma[1] * data[i + 1] + luma[2] * data[i + 2];
      count[ring]++;
    }
  }
  const means = Array.from(sum, (s, r) => (count[r] ? s / count[r] : null));
  return { rings, means };
}

/** Tint red (in place) the rings reflecting more than the light they receive: in the white
 * furnace they would vanish into the white background (the desktop's IBLView.mark_gain). */
export function markGain(data, size, luma) {
  const { rings, means } = ringMeans(data, size, luma);
  for (let p = 0; p < rings.length; p++) {
    if (rings[p] < 0 || !(means[rings[p]] > 1.01)) continue;
    const i = 4 * p;
    data[i] = Math.min(data[i], 1) * 0.3 + 0.7;
    data[i + 1] = Math.min(data[i + 1], 1) * 0.3;
    data[i + 2] = Math.min(data[i + 2], 1) * 0.3;
  }
}

/** The IBL view of one panel. */
export class IblView {
  constructor(panel) {
    this.panel = panel;
    this.lab = panel.lab;
    const lab = this.lab;
    this.size = Math.min(lab.size, IBL_SIZE);
    this.canvas = el("canvas", { class: "ibl", width: this.size, height: this.size });
    this.root = viewBox(this.canvas, "ibl", () => `${panel.name}_ibl_${this.ibl().environment}.png`);
    this.samples = 0;
    this.passes = 0;
    this.key = "";
    this.textures = new Map(); // environment name -> its four textures on this context
    this.status = el("div", { class: "view-note ibl-status", role: "status" });
    // A menu of a setting's choices (their names as values), shown with `titles`.
    const select = (name, titles, title) => {
      const choices = lab.specs[name].choices;
      const box = el("select", { title }, ...choices.map((c) => el("option", { value: c }, titles[c] ?? c.replace("_", " "))));
      box.addEventListener("change", () => {
        lab.set(name, choices.indexOf(box.value));
        lab.requestRender();
      });
      return box;
    };
    this.envBox = select("ibl_env", {}, "the environment: procedural maps the lab makes itself (lab/ibl/environments.py)");
    this.strategyBox = select("ibl_strategy", STRATEGY_TITLES, "how each sample's direction is drawn");
    this.sequenceBox = select("ibl_sequence", {},
      "the numbers each pixel's samples come from: random (PCG) or its own scrambled Sobol' sequence, stratified at every count");
    const turn = lab.specs.ibl_rotation;
    this.rotation = el("input", { type: "range", min: turn.min, max: turn.max, step: turn.step,
      title: "turn the environment about the vertical axis (degrees)" });
    this.rotation.addEventListener("input", () => {
      lab.set("ibl_rotation", Number(this.rotation.value));
      lab.requestRender();
    });
    this.root.append(el("div", { class: "ibl-controls" }, this.envBox, this.strategyBox, this.sequenceBox,
      el("label", { title: this.rotation.title }, "turn ", this.rotation)), this.status);
    this.tick = this.tick.bind(this);
  }

  /** The IBL settings by name (iblSettings). */
  ibl() {
    return iblSettings(this.lab);
  }

  /** A setting changed somewhere on the page: start again if it touches this render. */
  render() {
    const IBL = this.ibl();
    const lab = this.lab;
    this.envBox.value = IBL.environment;
    this.strategyBox.value = IBL.strategy;
    this.sequenceBox.value = lab.specs.ibl_sequence.choices[IBL.sobol ? 1 : 0];
    this.rotation.value = IBL.rotation;
    const panel = this.panel;
    const key = JSON.stringify([panel.name, panel.model?.code, panel.values, IBL, this.size, lab.lights.length]);
    if (key === this.key) {
      this.draw(); // the exposure may have changed
      this.schedule(); // and go on if it waited off screen
      return;
    }
    this.key = key;
    this.restart();
  }

  restart() {
    const IBL = this.ibl();
    const gl = this.panel.gl;
    this.samples = 0;
    this.passes = 0;
    this.error = "";
    this.peak = null;
    if (!this.target) this.makeTarget(gl);
    gl.bindFramebuffer(gl.FRAMEBUFFER, this.target.fbo);
    gl.clearColor(0, 0, 0, 0);
    gl.clear(gl.COLOR_BUFFER_BIT);
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    this.spp = 1;
    this.ready = this.environment(IBL.environment).then(() => {
      this.schedule();
    }, (err) => {
      this.error = err.message;
      this.showStatus();
    });
    this.showStatus();
  }

  makeTarget(gl) {
    if (!gl.getExtension("EXT_float_blend")) throw new Error("this browser cannot add up float images (EXT_float_blend)");
    const t = floatTexture(gl, this.size, this.size);
    const fbo = gl.createFramebuffer();
    gl.bindFramebuffer(gl.FRAMEBUFFER, fbo);
    gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.TEXTURE_2D, t, 0);
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    this.target = { texture: t, fbo };
  }

  /** This context's textures of the environment (loaded once per page). */
  async environment(name) {
    if (!this.textures.has(name)) {
      const lab = this.lab;
    const C = lab.constants;
      const map = await loadEnvironment(name, lab.environments, C.LUMA);
      const gl = this.panel.gl;
      if (!gl) return null;
      this.textures.set(name, environmentTextures(gl, map));
    }
    return this.textures.get(name);
  }

  schedule() {
    if (!this.pending && this.samples < MAX_SAMPLES && !this.root.classList.contains("paused")) this.pending = requestAnimationFrame(this.tick);
  }

  tick() {
    this.pending = 0;
    if (!this.panel.gl || !this.root.isConnected) return;
    if (this.offscreen) {
      this.stale = true; // resumes when scrolled into sight (lab.js)
      return;
    }
    const start = performance.now();
    try {
      this.pass(Math.min(this.spp, MAX_SAMPLES - this.samples));
    } catch (err) {
      // The panel shows a compile error of the model itself; this names the view.
      this.error = `the IBL view cannot run: ${err.message.split("\n")[0]}`;
      this.showStatus();
      return;
    }
    this.draw();
    // Samples per pass follow the time a pass takes, so that the page keeps responding.
    const ms = performance.now() - start;
    this.spp = Math.max(1, Math.min(64, Math.round(this.spp * Math.min(2, PASS_MS / Math.max(ms, 1)))));
    this.schedule();
  }

  /** One pass of `spp` samples per pixel, added to the target. */
  pass(spp) {
    const IBL = this.ibl();
    const lab = this.lab;
    const gl = this.panel.gl;
    const textures = this.textures.get(IBL.environment);
    if (!textures || spp <= 0) return;
    const view = STRATEGIES.indexOf(chosenStrategy(IBL.strategy, IBL.environment, lab.environments));
    // The sequence is compiled in, as on the desktop (terms/environment.glsl LAB_SOBOL).
    const preamble = `const int LIGHT_COUNT = ${lab.lights.length};${IBL.sobol ? "\n#define LAB_SOBOL" : ""}`;
    const compiled = this.panel.program("ibl", preamble, withSampler(lab.files));
    gl.useProgram(compiled.program);
    gl.bindVertexArray(this.panel.vao);
    this.panel.setParams(gl, compiled);
    textures.list.forEach((t, k) => {
      gl.activeTexture(gl.TEXTURE0 + ENV_UNIT + k);
      gl.bindTexture(gl.TEXTURE_2D, t);
    });
    gl.activeTexture(gl.TEXTURE0);
    const u = compiled.uniforms;
    const set = (name, fn, ...v) => u[name] !== undefined && gl[fn](u[name], ...v);
    ["u_env", "u_density", "u_marginal", "u_conditional"].forEach((name, k) => set(name, "uniform1i", ENV_UNIT + k));
    set("u_env_size", "uniform2f", ...textures.size);
    set("u_resolution", "uniform2f", this.size, this.size);
    set("u_rotation", "uniform1f", (IBL.rotation * Math.PI) / 180);
    set("u_strategy", "uniform1i", view);
    set("u_spp", "uniform1i", spp);
    set("u_frame", "uniform1i", this.passes);
    set("u_sample0", "uniform1i", this.samples); // where each pixel's Sobol' sequence goes on
    set("u_seed", "uniform1i", 0);
    gl.bindFramebuffer(gl.FRAMEBUFFER, this.target.fbo);
    gl.viewport(0, 0, this.size, this.size);
    gl.enable(gl.BLEND);
    gl.blendFunc(gl.ONE, gl.ONE);
    gl.drawArrays(gl.TRIANGLES, 0, 3);
    gl.disable(gl.BLEND);
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    this.samples += spp;
    this.passes++;
  }

  /** Runs passes until `samples` per pixel now (tests, benchmarks); resolves to the count. */
  async converge(samples = MAX_SAMPLES, spp = 16) {
    if (!this.ready) this.render(); // never drawn yet (off screen from the start)
    await this.ready;
    cancelAnimationFrame(this.pending);
    this.pending = 0;
    while (this.samples < samples) {
      const before = this.samples;
      this.pass(Math.min(spp, samples - this.samples));
      if (this.samples === before) break; // no environment (it failed to load): say so below
    }
    this.stale = false;
    this.draw();
    return this.samples;
  }

  /** The running sums, read back (rows from the bottom). */
  sums() {
    const gl = this.panel.gl;
    const out = new Float32Array(4 * this.size * this.size);
    gl.bindFramebuffer(gl.FRAMEBUFFER, this.target.fbo);
    gl.readPixels(0, 0, this.size, this.size, gl.RGBA, gl.FLOAT, out);
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    return out;
  }

  draw() {
    const IBL = this.ibl();
    this.showStatus();
    if (!this.samples) return;
    const lab = this.lab;
    const data = this.sums();
    // The mean; the environment shows behind the sphere (alpha 0 there in the sums).
    for (let i = 0; i < data.length; i += 4) {
      for (let c = 0; c < 3; c++) data[i + c] /= this.samples;
      data[i + 3] = 1;
    }
    // The furnace test: under radiance 1 no ring may reflect more than 1 (beyond the noise).
    const furnace = IBL.environment === "furnace" && this.samples >= GAIN_SAMPLES;
    this.peak = furnace ? ringPeak(data, this.size, this.lab.constants.LUMA) : null;
    if (this.peak > 1.01) markGain(data, this.size, this.lab.constants.LUMA); // colour and text
    this.showStatus();
    this.canvas.getContext("2d").putImageData(toImage(data, this.size, this.size, lab.settings.exposure), 0, 0);
  }

  showStatus() {
    const IBL = this.ibl();
    const model = this.panel.model;
    const chosen = chosenStrategy(IBL.strategy, IBL.environment, this.lab.environments);
    const note = model ? fallback(model, chosen, this.lab.files) : null;
    const done = this.samples >= MAX_SAMPLES ? " (done)" : "";
    const gain = this.peak > 1.01 ? ` · ENERGY GAIN (red): a ring reflects ${this.peak.toFixed(2)}× the light that arrives` : "";
    const runs = IBL.strategy === "auto" ? `, here ${STRATEGY_TITLES[chosen]}` : "";
    const numbers = IBL.sobol ? "Sobol'" : "random";
    const text = this.error || `${this.samples} samples per pixel${done} · ${STRATEGY_TITLES[IBL.strategy]}${runs} · ${numbers}` +
      (note ? ` · ${note}` : "") + gain;
    this.status.textContent = text;
    this.status.classList.toggle("bad", Boolean(this.error || note || gain));
  }

  /** The running mean as the desktop's Progressive.image(): rows from the top, alpha 1 on
   * the sphere and 0 behind it. */
  read() {
    const data = this.sums();
    const n = this.samples || 1;
    for (let i = 0; i < data.length; i++) data[i] /= n;
    return { width: this.size, height: this.size, samples: this.samples, data: topFirst(data, this.size, this.size) };
  }
}


export const VIEW = {
  name: "ibl",
  queue: 70,
  create: (panel) => new IblView(panel),
  // Older addresses' ibl=ENVIRONMENT,STRATEGY,ROTATION (now ibl_env=, ibl_strategy=, ibl_rotation=).
  address: { key: "ibl", read: readOldAddress, write: () => "" },
};

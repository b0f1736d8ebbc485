// The deck's reflection equation by Monte Carlo, live: the lab's IBL template
// (shaders/views/ibl.glsl after terms/sampling.glsl, the model's sampler and
// terms/environment.glsl, as lab/ibl/integrator.py assembles it) in
// WebGL2, accumulated pass after pass into a float target and restarted when a control
// moves. One panel per strategy in the hash (#model=ggx&alpha=0.1&strategy=uniform&
// strategy=mis_power&env=sky), at equal samples. The program and the environment (its
// sampling tables and textures) are the web lab's IBL view's own (iblsource.js).
import { finishProgram, floatTexture, startProgram, vertexSource } from "./assemble.js";
import { defaults, parseModel } from "./header.js";
import { STRATEGIES, environmentTextures, iblSource, loadEnvironment } from "./iblsource.js";

// Short labels for a slide (ibl.js's STRATEGY_TITLES are the lab's longer ones).
const TITLES = { uniform: "uniform", cosine: "cosine-weighted", environment: "environment CDF",
  brdf: "BRDF sampling", mis_balance: "MIS, balance", mis_power: "MIS, power" };
const MODELS = ["ggx", "blinn_phong", "phong", "cook_torrance", "ward", "lambert"];
const ENVIRONMENTS = ["sky", "studio"];
const SLIDE_KEYS = { PageDown: "next", PageUp: "prev", ArrowRight: "next", ArrowLeft: "prev", " ": "next" };

const demo = {
  state: { model: "ggx", params: {}, strategies: ["uniform", "mis_power"], env: "sky", rotation: 0,
    exposure: 0, size: 256, spp: 4, target: 4096, samples: [], firstRenderMs: null, error: "" },
  panels: [],
};
window.iblDemo = demo;
const $ = (id) => document.getElementById(id);
const files = {};
const envs = {};
const started = performance.now();
let gl, manifest;

async function text(path) {
  const response = await fetch(path);
  if (!response.ok) throw new Error(`${path}: ${response.status} ${response.statusText}`);
  return response.text();
}

/** The map's textures (iblsource.js, as the web lab's IBL view makes them). */
async function environment(name) {
  envs[name] ??= environmentTextures(gl, await loadEnvironment(name, manifest.environments, manifest.constants.LUMA));
  return envs[name];
}

/** The linked program of a fragment shader (the lab's full-screen vertex stage); throws
 * the driver's log where it does not compile. */
function link(fragment) {
  const logs = {};
  const compiled = finishProgram(startProgram(gl, vertexSource("300es"), fragment), logs);
  if (!compiled) throw new Error(logs.vertex + logs.fragment + logs.link);
  return compiled.program;
}

/** The IBL program for a model, assembled as the web lab's IBL view does (iblsource.js). */
async function iblProgram(name) {
  const path = `brdfs/${name}.glsl`;
  const model = parseModel(files[path], `shaders/${path}`, name);
  return { model, program: link(iblSource(model, files, { constants: manifest.constants }).text) };
}

const DISPLAY = `#version 300 es
precision highp float;
uniform sampler2D u_sum;
uniform float u_samples;
uniform float u_exposure;
out vec4 color;
void main() {
    vec3 c = texelFetch(u_sum, ivec2(gl_FragCoord.xy), 0).rgb / max(u_samples, 1.0);
    c = max(c * exp2(u_exposure), 0.0);
    vec3 s = mix(12.92 * c, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(0.0031308, c));
    color = vec4(clamp(s, 0.0, 1.0), 1.0);
}`;

class Panel {
  constructor(strategy) {
    this.strategy = strategy;
    this.samples = 0;
    this.passes = 0;
    const size = demo.state.size;
    this.figure = document.createElement("figure");
    this.canvas = document.createElement("canvas");
    this.canvas.width = this.canvas.height = size;
    this.caption = document.createElement("figcaption");
    this.caption.id = `caption-${strategy}`;
    this.canvas.setAttribute("role", "img"); // named by its caption: the strategy and samples so far
    this.canvas.setAttribute("aria-labelledby", this.caption.id);
    this.figure.append(this.canvas, this.caption);
    $("panels").append(this.figure);
    this.ctx2d = this.canvas.getContext("2d");
    this.sum = floatTexture(gl, size, size);
    this.fbo = gl.createFramebuffer();
    gl.bindFramebuffer(gl.FRAMEBUFFER, this.fbo);
    gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.TEXTURE_2D, this.sum, 0);
    this.reset();
  }

  reset() {
    gl.bindFramebuffer(gl.FRAMEBUFFER, this.fbo);
    gl.clearColor(0, 0, 0, 0);
    gl.clear(gl.COLOR_BUFFER_BIT);
    this.samples = this.passes = 0;
  }

  /** One pass of `spp` samples per pixel, added to the float sum by blending. */
  add(spp) {
    const { program, model } = demo.compiled;
    const s = demo.state;
    const env = demo.env;
    gl.useProgram(program);
    const at = (name) => gl.getUniformLocation(program, name);
    const values = { ...defaults(model), ...s.params };
    for (const p of model.params) {
      const v = values[p.name];
      if (p.kind === "float") gl.uniform1f(at(p.name), v);
      else if (p.kind === "color") gl.uniform3fv(at(p.name), v);
      else if (p.kind === "bool") gl.uniform1i(at(p.name), v ? 1 : 0);
    }
    env.list.forEach((t, i) => { gl.activeTexture(gl.TEXTURE8 + i); gl.bindTexture(gl.TEXTURE_2D, t); });
    ["u_env", "u_density", "u_marginal", "u_conditional"].forEach((n, i) => gl.uniform1i(at(n), 8 + i));
    gl.uniform2f(at("u_env_size"), env.size[0], env.size[1]);
    gl.uniform2f(at("u_resolution"), s.size, s.size);
    gl.uniform1f(at("u_rotation"), (s.rotation * Math.PI) / 180);
    gl.uniform1i(at("u_strategy"), STRATEGIES.indexOf(this.strategy));
    gl.uniform1i(at("u_spp"), spp);
    gl.uniform1i(at("u_frame"), this.passes);
    gl.uniform1i(at("u_seed"), 0);
    gl.bindFramebuffer(gl.FRAMEBUFFER, this.fbo);
    gl.viewport(0, 0, s.size, s.size);
    gl.enable(gl.BLEND);
    gl.blendFunc(gl.ONE, gl.ONE);
    gl.drawArrays(gl.TRIANGLES, 0, 3);
    gl.disable(gl.BLEND);
    this.samples += spp;
    this.passes += 1;
  }

  show() {
    const s = demo.state;
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    gl.useProgram(demo.display);
    gl.activeTexture(gl.TEXTURE0);
    gl.bindTexture(gl.TEXTURE_2D, this.sum);
    gl.uniform1i(gl.getUniformLocation(demo.display, "u_sum"), 0);
    gl.uniform1f(gl.getUniformLocation(demo.display, "u_samples"), this.samples);
    gl.uniform1f(gl.getUniformLocation(demo.display, "u_exposure"), s.exposure);
    gl.viewport(0, 0, s.size, s.size);
    gl.drawArrays(gl.TRIANGLES, 0, 3);
    this.ctx2d.drawImage(gl.canvas, 0, 0);
    this.caption.textContent = `${TITLES[this.strategy]}: ${this.samples} spp`;
  }

  /** The running mean (float RGBA, rows from the bottom) and its mean luminance on the sphere. */
  read() {
    const n = demo.state.size;
    const data = new Float32Array(n * n * 4);
    gl.bindFramebuffer(gl.FRAMEBUFFER, this.fbo);
    gl.readPixels(0, 0, n, n, gl.RGBA, gl.FLOAT, data);
    let sum = 0, count = 0;
    const luma = manifest.constants.LUMA;
    for (let k = 0; k < data.length; k += 4) {
      if (data[k + 3] <= 0) continue;
      sum += (luma[0] * data[k] + luma[1] * data[k + 1] + luma[2] * data[k + 2]) / this.samples;
      count++;
    }
    return { samples: this.samples, mean: count ? sum / count : 0, covered: count / (n * n) };
  }
}

demo.read = (i) => demo.panels[i].read();

function restart() {
  for (const panel of demo.panels) panel.reset();
  schedule();
}

let pending = false;
function schedule() {
  if (pending || demo.paused) return;
  pending = true;
  requestAnimationFrame(frame);
}

function frame() {
  pending = false;
  const s = demo.state;
  for (const panel of demo.panels) {
    if (panel.samples < s.target) panel.add(Math.min(s.spp, s.target - panel.samples));
    panel.show();
  }
  s.samples = demo.panels.map((p) => p.samples);
  if (s.firstRenderMs === null) s.firstRenderMs = performance.now() - started;
  if (demo.panels.some((p) => p.samples < s.target)) schedule();
}

function roughParam(model) {
  return model.params.find((p) => p.kind === "float") || null;
}

function sliderOf(param, value) {
  if (param.scale === "log") {
    return Math.log(value / param.minimum) / Math.log(param.maximum / param.minimum);
  }
  return (value - param.minimum) / (param.maximum - param.minimum);
}

function valueOf(param, t) {
  if (param.scale === "log") return param.minimum * Math.pow(param.maximum / param.minimum, t);
  return param.minimum + t * (param.maximum - param.minimum);
}

async function useModel(name) {
  demo.state.model = name;
  demo.compiled = await iblProgram(name);
  const param = roughParam(demo.compiled.model);
  $("rough-label").hidden = !param;
  if (param) {
    const value = demo.state.params[param.name] ?? param.default;
    demo.state.params[param.name] = value;
    $("rough-name").textContent = param.name;
    $("rough").value = sliderOf(param, value);
    $("rough-text").textContent = value.toPrecision(3);
  }
}

function readHash() {
  const s = demo.state;
  const strategies = [];
  for (const part of location.hash.replace(/^#/, "").split("&")) {
    const [key, raw] = part.split("=");
    if (!key) continue;
    const value = decodeURIComponent(raw ?? "");
    if (key === "model" && MODELS.includes(value)) s.model = value;
    else if (key === "strategy" && STRATEGIES.includes(value)) strategies.push(value);
    else if (key === "env" && ENVIRONMENTS.includes(value)) s.env = value;
    else if (key === "size") s.size = Math.max(64, Math.min(512, Number(value) || 256));
    else if (key === "shown") document.documentElement.style.setProperty("--shown", `${Number(value)}px`);
    else if (["rotation", "exposure", "spp", "target"].includes(key)) s[key] = Number(value);
    else if (key === "embed") document.body.classList.toggle("embed", value !== "0");
    else if (!Number.isNaN(Number(value))) s.params[key] = Number(value);
  }
  if (strategies.length) s.strategies = strategies;
}

function fail(message) {
  demo.state.error = message;
  $("error").hidden = false;
  $("error").textContent = message;
}

async function main() {
  readHash();
  const s = demo.state;
  const canvas = document.createElement("canvas");
  canvas.width = canvas.height = s.size;
  gl = canvas.getContext("webgl2", { preserveDrawingBuffer: true, antialias: false });
  if (!gl || !gl.getExtension("EXT_color_buffer_float") || !gl.getExtension("EXT_float_blend")) {
    fail("This demo needs WebGL2 with float render targets and float blending " +
      "(EXT_color_buffer_float, EXT_float_blend).");
    return;
  }
  manifest = JSON.parse(await text("manifest.json"));
  const wanted = ["terms/common.glsl", "terms/sampling.glsl", "terms/environment.glsl", "views/ibl.glsl",
    ...MODELS.map((m) => `brdfs/${m}.glsl`), ...MODELS.map((m) => `samplers/${m}.glsl`),
    ...manifest.files.filter((f) => f.startsWith("terms/"))];
  await Promise.all([...new Set(wanted)].filter((f) => manifest.files.includes(f)).map(async (f) => {
    files[f] = await text(`shaders/${f}`);
  }));
  demo.display = link(DISPLAY);
  demo.env = await environment(s.env);
  for (const m of MODELS) $("model").append(new Option(m, m));
  for (const e of ENVIRONMENTS) $("env").append(new Option(e, e));
  $("model").value = s.model;
  $("env").value = s.env;
  $("rotation").value = s.rotation;
  $("exposure").value = s.exposure;
  await useModel(s.model);
  demo.panels = s.strategies.map((strategy) => new Panel(strategy));
  $("model").onchange = async () => { await useModel($("model").value); restart(); };
  $("env").onchange = async () => { s.env = $("env").value; demo.env = await environment(s.env); restart(); };
  $("rotation").oninput = () => { s.rotation = Number($("rotation").value); restart(); };
  $("exposure").oninput = () => { s.exposure = Number($("exposure").value); demo.panels.forEach((p) => p.show()); };
  $("rough").oninput = () => {
    const param = roughParam(demo.compiled.model);
    const value = valueOf(param, Number($("rough").value));
    s.params[param.name] = value;
    $("rough-text").textContent = value.toPrecision(3);
    restart();
  };
  addEventListener("keydown", (e) => {
    const step = SLIDE_KEYS[e.key];
    if (!step || e.altKey || e.ctrlKey || e.metaKey || window.parent === window) return;
    const t = e.target;
    const slider = t instanceof HTMLInputElement && t.type === "range";
    if (t instanceof HTMLSelectElement || (slider && e.key.startsWith("Arrow"))) return;
    if (e.key === " " && t instanceof HTMLButtonElement) return; // Space presses the button
    e.preventDefault();
    window.parent.postMessage({ brdfLab: "slide", step }, "*");
  });
  // A pause for the running estimate; with reduced motion it waits after the first image.
  const pause = (paused) => {
    demo.paused = paused;
    $("pause").setAttribute("aria-pressed", String(paused));
    $("pause").textContent = paused ? "continue" : "pause";
    if (!paused) schedule();
  };
  $("pause").onclick = () => pause(!demo.paused);
  schedule();
  if (matchMedia("(prefers-reduced-motion: reduce)").matches) requestAnimationFrame(() => pause(true));
}

main().catch((err) => fail(String(err && err.message ? err.message : err)));

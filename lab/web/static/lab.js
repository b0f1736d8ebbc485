// The web lab: model files from shaders/, headers parsed in the page, one WebGL2 program
// per model, view and enum choice, assembled exactly as the desktop lab assembles them.
import { ModelError, defaults, formatG, parseModel } from "./header.js";
import { direction, planeOfIncidence } from "./geometry.js";
import { SLIDER_STEPS, parseRgb, parseValue, sliderToValue, valueToSlider } from "./values.js";
import { assembleFragment, finishProgram, floatTexture, startProgram, translateLog, vertexSource } from "./assemble.js";
import { MODES, SHAPES, VIEWS, VIEW_TITLES } from "./views.js";
import { IBL_TITLE, IblView, iblHash, readIblHash } from "./ibl.js";
import { ExerciseMode } from "./exercise.js";
import { drawCurve, fitPlotAspect, pageFontPx, sharedRange, showOnly } from "./deck.js";
import { openModelFile, putModel } from "./measured.js";
import { draft, draftNames, forgetFile, keepDraft, keepFile, keptFiles, storeProblem } from "./store.js";
import { peakValue, polarRadius as scaleRadius } from "./plotscale.js";

const C = {}; // the lab's constants (lab/constants.py), from the manifest
VIEWS.ibl = IblView; // its own module (ibl.js)
VIEW_TITLES.ibl = IBL_TITLE;
const MAX_PANELS = 6;
const POLAR_STEPS = 181; // theta_o from -90 to 90 degrees in 1-degree steps
const EMBED_PLOT = 1.5; // embedded in a slide: the plot's width over the sphere's
const SPHERE_FAST_MIN = 384; // spheres this large draw at half resolution while a slider moves
// The order the views queue their GPU work in, and make their pictures in, within a frame
// (Panel.render): cheap programs first, so that each picture's JS overlaps the GPU's work
// on the views after it (the 3D lobe's picture comes last: its mesh is a second round).
const FRAME_ORDER = ["terms", "sh", "lobe3d", "slice", "albedo", "object"];
// One colour per panel, in every view that overlays models (the desktop's first colours).
const PALETTE = ["#56b4e9", "#e69f00", "#009e73", "#f0e442", "#cc79a7", "#d55e00"]; // Okabe-Ito: apart under colour blindness (tests/test_a11y_colour.py)
// Page settings beyond the lights, with their defaults (the desktop's, lab/presets.py).
// The 3D lobe's camera and the harmonics' order as the desktop's (lab/views/lobe3d.py, sh.py).
const SETTINGS = { phiD: 90, shape: 0, mode: 1, yaw: 0.6, pitch: 0.5, polarLog: false, phiO: 0,
  lobeYaw: -0.6, lobePitch: 0.35, lobeZoom: 1, shOrder: 8 };

const DISPLAY_SHADER = `#version 300 es
precision highp float;
uniform highp sampler2D u_image;
uniform float u_scale;
uniform int u_step; // 2: a half-resolution render (while a slider moves), each texel 2x2
out vec4 frag_color;
// Linear radiance -> sRGB, as lab/plots.py writes PNGs (clamped, no tone curve).
vec3 srgb(vec3 c) {
    c = clamp(c, 0.0, 1.0);
    return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(0.0031308, c));
}
void main() {
    // A shift, not a division (SwiftShader divides integers lane by lane).
    vec4 v = texelFetch(u_image, ivec2(gl_FragCoord.xy) >> (u_step == 2 ? 1 : 0), 0);
    if (v.a == 0.0) {  // off the sphere: nothing to convert (the output is 0 either way)
        frag_color = vec4(0.0);
        return;
    }
    frag_color = vec4(srgb(v.rgb * u_scale) * v.a, v.a);
}
`;

// -- shared state -------------------------------------------------------------------------
const lab = {
  files: {}, // path under shaders/ -> text
  models: {}, // name -> parsed model
  modelErrors: {}, // name -> header error text
  order: [],
  panels: [],
  // Directional lights in camera space (theta 0: at the eye); the polar plot shows the
  // plane of incidence of the first. Ambient is radiance added everywhere on the sphere.
  lights: [{ theta: 45, phi: 0, rgb: [1, 1, 1] }], // DEFAULT_LIGHT
  ambient: [0, 0, 0],
  active: 0, // the light that dragging on a sphere moves
  get light() {
    return { theta: this.lights[0].theta, phi: this.lights[0].phi };
  },
  exposure: 0,
  size: 384,
  cosWeighted: false,
  embed: false,
  // Slides: only these controls (null: all), the lobe against θo, each plot on its own scale.
  show: null,
  plot: "polar",
  scaleEach: false,
  notes: [],
  views: [], // shown besides the sphere and the polar plot: keys of VIEWS, in that order
  ...SETTINGS,
  fast: false, // a slider is moving: the costly views draw a coarse version
  presets: [], // the desktop lab's presets (lab/app/presets/*.toml), from the manifest
  firstRenderMs: null, // every view drawn, the costly ones coarse (ms since navigation start)
  fullRenderMs: null, // every view at full quality
};
const DEFAULT_LIGHT = { theta: 45, phi: 0, rgb: [1, 1, 1] };

const $ = (selector, root = document) => root.querySelector(selector);
function el(tag, attrs = {}, ...children) {
  const node = document.createElement(tag);
  for (const [key, value] of Object.entries(attrs)) {
    if (key === "class") node.className = value;
    else if (key.startsWith("on")) node.addEventListener(key.slice(2), value);
    else node.setAttribute(key, value);
  }
  for (const child of children) node.append(child);
  return node;
}

// -- values <-> text ----------------------------------------------------------------------
const round = (x) => Number(x.toPrecision(4));
function valueText(p, value) {
  if (p.kind === "color") return value.map((c) => formatG(c)).join(",");
  if (p.kind === "bool") return value ? "1" : "0";
  if (p.kind === "float") return formatG(value);
  return String(value);
}
const toHex = (rgb) => "#" + rgb.map((c) => Math.round(Math.min(Math.max(c, 0), 1) * 255).toString(16).padStart(2, "0")).join("");
const fromHex = (hex) => [1, 3, 5].map((i) => round(parseInt(hex.slice(i, i + 2), 16) / 255));

/** Downloads a canvas as a PNG file (what is on screen: exposure and sRGB applied). */
function savePng(canvas, filename) {
  canvas.toBlob((blob) => {
    const a = el("a", { href: URL.createObjectURL(blob), download: filename });
    document.body.append(a);
    a.click();
    a.remove();
    setTimeout(() => URL.revokeObjectURL(a.href), 1000);
  }, "image/png");
}

/** A canvas in a box with its own "PNG" button. */
function viewBox(canvas, what, filename) {
  const button = el("button", { type: "button", class: "png", title: `save the ${what} as a PNG image` }, "PNG");
  button.addEventListener("click", () => savePng(canvas, filename()));
  return el("div", { class: "view", "data-view": what }, canvas, button);
}

/** The short name of a model for pickers: its title up to the first colon. */
const shortTitle = (model, name) => (model?.title ? model.title.split(":")[0].trim() : name);

// -- GL helpers ---------------------------------------------------------------------------
class CompileFailure extends Error {
  constructor(errors, log) {
    super(errors.length ? errors.map((e) => `${e.file}:${e.line}: ${e.message}`).join("\n") : log);
    this.errors = errors;
  }
}

/** A model's program from its assembled fragment source (throws CompileFailure). */
function finishModelProgram(pending, source) {
  const logs = {};
  const compiled = finishProgram(pending, logs);
  if (!compiled) {
    const log = logs.fragment + logs.link;
    throw new CompileFailure(source ? translateLog(log, source) : [], log);
  }
  // Guarded loops of the model (unknown: null); with none, no loop can be stopped.
  return { ...compiled, loops: source ? (source.loops ?? null) : 0 };
}

function compile(gl, fragmentText, source) {
  return finishModelProgram(startProgram(gl, vertexSource("300es"), fragmentText), source);
}

/** Sets a uniform the program uses (others the driver dropped are skipped), by its type. */
function setUniform(gl, compiled, name, value) {
  const location = compiled.uniforms[name];
  if (location === undefined) return;
  const flat = Array.isArray(value) ? value.flat() : value;
  switch (compiled.types[name]) {
    case gl.FLOAT: Array.isArray(flat) ? gl.uniform1fv(location, flat) : gl.uniform1f(location, flat); break;
    case gl.FLOAT_VEC2: gl.uniform2fv(location, flat); break;
    case gl.FLOAT_VEC3: gl.uniform3fv(location, flat); break;
    case gl.FLOAT_VEC4: gl.uniform4fv(location, flat); break;
    case gl.INT_VEC2: gl.uniform2iv(location, flat); break;
    default: gl.uniform1i(location, Number(flat)); // int, bool, samplers
  }
}

/** A float render target; with `flag`, a second one at location 1 for the loop guard's
 * flag (the line of a loop it stopped, per pixel; assemble.js). */
function floatTarget(gl, width, height, flag = false) {
  const make = () => floatTexture(gl, width, height);
  const texture = make();
  const fbo = gl.createFramebuffer();
  gl.bindFramebuffer(gl.FRAMEBUFFER, fbo);
  gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.TEXTURE_2D, texture, 0);
  if (flag) {
    gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT1, gl.TEXTURE_2D, make(), 0);
    gl.drawBuffers([gl.COLOR_ATTACHMENT0, gl.COLOR_ATTACHMENT1]);
  }
  const status = gl.checkFramebufferStatus(gl.FRAMEBUFFER);
  gl.bindFramebuffer(gl.FRAMEBUFFER, null);
  if (status !== gl.FRAMEBUFFER_COMPLETE) throw new Error("this browser cannot render to float textures");
  return { texture, fbo, width, height, flag };
}

/** Where the loop guard stopped a loop in the bound target: {line, x, y} or null (not read
 * back for a program without loops: one wait for the GPU less). */
function loopStop(gl, target, compiled) {
  if (!target.flag || compiled.loops === 0) return null;
  const flags = new Float32Array(4 * target.width * target.height);
  gl.readBuffer(gl.COLOR_ATTACHMENT1);
  gl.readPixels(0, 0, target.width, target.height, gl.RGBA, gl.FLOAT, flags);
  gl.readBuffer(gl.COLOR_ATTACHMENT0);
  for (let i = 0; i < target.width * target.height; i++) {
    if (flags[4 * i] > 0) return { line: Math.round(flags[4 * i]), x: i % target.width, y: Math.floor(i / target.width) };
  }
  return null;
}

// -- a panel: one model, its controls, sphere and polar plot -------------------------------
class Panel {
  constructor(name, values = {}) {
    this.root = el("section", { class: "panel" });
    this.programs = new Map();
    this.extra = {}; // view name -> its view object (views.js)
    this.values = {};
    this.error = "";
    this.renders = 0;
    this.build();
    this.setModel(name, values);
  }

  build() {
    this.picker = el("select", { class: "model-picker", title: "reflection model", onchange: () => {
      this.setModel(this.picker.value);
      scheduleRender();
    } });
    this.closeButton = el("button", { class: "close", title: "remove this model", onclick: () => removePanel(this) }, "×");
    this.editButton = el("button", { type: "button", class: "edit", title: "edit this model's GLSL file in the page",
      onclick: () => openEditor(this) }, "edit");
    this.canvas = el("canvas", { class: "sphere", width: lab.size, height: lab.size });
    // Embedded, the plot is wider than the sphere: its labels are large (deck.js).
    const plotWidth = Math.round(lab.size * (lab.embed ? EMBED_PLOT : 1));
    this.polar = el("canvas", { class: "polar", width: plotWidth,
      height: Math.round(lab.embed ? plotWidth * 0.62 : lab.size / 2 + 28) });
    this.displaySize(lab.size);
    this.errorBox = el("pre", { class: "errors", hidden: "" });
    this.loopBox = el("p", { class: "errors loop-warning", hidden: "" });
    this.viewsBox = el("div", { class: "views" });
    this.controls = el("div", { class: "controls" });
    this.formula = el("div", { class: "formula" });
    // Controls right under the pictures they change; the formula after them.
    const file = (what) => () => `${this.name}_${what}.png`;
    this.root.append(el("header", {}, this.picker, el("span", {}, this.editButton, this.closeButton)),
      el("div", { class: "views" }, viewBox(this.canvas, "sphere", file("sphere")),
        viewBox(this.polar, "polar plot", file("polar"))),
      this.viewsBox, this.errorBox, this.loopBox, this.controls, this.formula);
    this.gl = this.canvas.getContext("webgl2", { antialias: false, preserveDrawingBuffer: true });
    if (!this.gl) {
      this.showError("this browser has no WebGL2");
      return;
    }
    if (!this.gl.getExtension("EXT_color_buffer_float")) {
      this.showError("this browser cannot render to float textures (EXT_color_buffer_float)");
      this.gl = null;
      return;
    }
    const gl = this.gl;
    this.vao = gl.createVertexArray();
    this.targets = new Map(); // float render targets of the other views, by size
    this.target = floatTarget(gl, lab.size, lab.size);
    this.coarseTarget = null; // half resolution, while a slider moves (made on first use)
    this.probeTarget = floatTarget(gl, POLAR_STEPS, 1, true);
    this.display = compile(gl, DISPLAY_SHADER, null);
    this.canvas.addEventListener("pointerdown", (e) => {
      this.canvas.setPointerCapture(e.pointerId);
      this.dragLight(e);
    });
    this.canvas.addEventListener("pointermove", (e) => {
      if (e.buttons) this.dragLight(e);
    });
  }

  /** CSS size of the sphere (and the polar plot's width); the render keeps lab.size. */
  displaySize(px) {
    // Never wider than the panel (phones): the canvases' height follows their aspect.
    this.canvas.style.width = `${px}px`;
    this.polar.style.width = `${px}px`;
    if (lab.embed) {
      // Embedded: exact heights, so that fitting the frame converges (the grid of a slide).
      this.canvas.style.height = `${px}px`;
      this.polar.style.width = `${px * EMBED_PLOT}px`;
      this.polar.style.height = `${(px * EMBED_PLOT * this.polar.height) / this.polar.width}px`;
    }
    for (const view of Object.values(this.extra)) view.canvas.style.width = `${px}px`;
  }

  get color() {
    return PALETTE[Math.max(lab.panels.indexOf(this), 0) % PALETTE.length];
  }

  /** Makes the panel show the page's chosen views (lab.views), in their order. */
  syncViews() {
    for (const name of Object.keys(this.extra)) {
      if (!lab.views.includes(name)) delete this.extra[name];
    }
    for (const name of lab.views) {
      if (!this.extra[name] && this.gl) {
        this.extra[name] = new VIEWS[name](this, viewEnv);
        watchVisibility(this.extra[name]);
      }
    }
    this.viewsBox.replaceChildren(...lab.views.filter((n) => this.extra[n]).map((n) => this.extra[n].root));
    this.displaySize(parseFloat(this.canvas.style.width) || lab.size);
  }

  fillPicker() {
    this.picker.replaceChildren(...lab.order.map((n) => el("option", { value: n, title: lab.models[n]?.title || n },
      shortTitle(lab.models[n], n))));
    this.picker.value = this.name;
  }

  /** Gives the WebGL context back at once (browsers keep only a few alive). */
  destroy() {
    this.gl?.getExtension("WEBGL_lose_context")?.loseContext();
    this.gl = null;
    this.root.remove();
  }

  setModel(name, values = {}) {
    this.name = name;
    this.fillPicker();
    this.model = lab.models[name];
    this.programs.clear(); // compiled for the previous model
    this.controls.replaceChildren();
    this.formula.replaceChildren();
    if (!this.model) {
      this.showError(lab.modelErrors[name] || `unknown model ${name}`);
      return;
    }
    this.values = { ...defaults(this.model), ...values };
    this.formula.append(el("strong", {}, this.model.title || name),
      ...this.model.formula.map((f) => el("code", {}, f)));
    for (const p of this.model.params) this.controls.append(this.control(p));
    if (lab.embed) showOnly(lab.show);
  }

  control(p) {
    const range = p.kind === "float"
      ? ` (${formatG(p.minimum)} to ${formatG(p.maximum)}${p.scale === "log" ? ", log slider" : ""})`
      : p.kind === "color" ? " (r,g,b each 0 to 1)" : "";
    const tip = `${p.name}: ${p.doc || "no description in the model's header"}${range}`;
    const label = el("label", { title: tip }, p.name);
    const row = el("div", { class: `param param-${p.kind}`, "data-param": p.name, title: tip }, label);
    const set = (value) => {
      this.values[p.name] = value;
      if (p.kind === "enum") this.programs.clear(); // another constant: compile again
      scheduleRender();
    };
    if (p.kind === "float") {
      const slider = el("input", { type: "range", min: 0, max: SLIDER_STEPS, step: 1 });
      const box = el("input", { type: "text", class: "value", size: 6 });
      const show = () => {
        slider.value = valueToSlider(p, this.values[p.name]);
        box.value = formatG(round(this.values[p.name]));
      };
      slider.addEventListener("input", () => {
        set(round(sliderToValue(p, Number(slider.value))));
        box.value = formatG(this.values[p.name]);
      });
      box.addEventListener("change", () => {
        try {
          set(parseValue(p, box.value));
          box.classList.remove("bad");
        } catch (err) {
          box.classList.add("bad");
          box.title = err.message;
        }
        show();
      });
      show();
      row.append(slider, box);
      if (p.scale === "log") row.append(el("span", { class: "scale" }, "log"));
    } else if (p.kind === "color") {
      const picker = el("input", { type: "color", value: toHex(this.values[p.name]) });
      const box = el("input", { type: "text", class: "value", size: 12, value: valueText(p, this.values[p.name]) });
      picker.addEventListener("input", () => {
        set(fromHex(picker.value));
        box.value = valueText(p, this.values[p.name]);
      });
      box.addEventListener("change", () => {
        try {
          set(parseValue(p, box.value));
          picker.value = toHex(this.values[p.name]);
          box.classList.remove("bad");
        } catch (err) {
          box.classList.add("bad");
          box.title = err.message;
        }
      });
      row.append(picker, box);
    } else if (p.kind === "bool") {
      const box = el("input", { type: "checkbox" });
      box.checked = this.values[p.name];
      box.addEventListener("change", () => set(box.checked));
      row.append(box);
    } else {
      const select = el("select", {}, ...p.choices.map((c) => el("option", { value: c }, c)));
      select.value = this.values[p.name];
      select.addEventListener("change", () => set(select.value));
      row.append(select);
    }
    return row;
  }

  /** Moves the slider of `name` to a position (0..1000) as a user would. */
  moveSlider(name, position) {
    const slider = $(`[data-param="${name}"] input[type=range]`, this.root);
    slider.value = position;
    slider.dispatchEvent(new Event("input"));
    return this.values[name];
  }

  /** The loop guard's warning: a loop of the model did not end (seen at the polar plot's
   * directions); its values are wrong there and on a GPU it would freeze the screen. */
  showLoop(stop) {
    this.loop = stop;
    const text = stop ? `${this.model.path}:${stop.line}: the loop at line ${stop.line} did not end within ` +
      `${Number(C.LOOP_LIMIT).toLocaleString("en-US")} iterations at θo = ${stop.x - 90}° of the polar plot; ` +
      "the lab stopped it, so the pictures are wrong: check its exit condition (on a GPU such a loop freezes the screen)" : "";
    this.loopBox.textContent = text;
    this.loopBox.hidden = !text;
  }

  showError(text) {
    this.error = text;
    this.errorBox.textContent = text;
    this.errorBox.hidden = !text;
  }

  dragLight(event) {
    const rect = this.canvas.getBoundingClientRect();
    let x = ((event.clientX - rect.left) / rect.width) * 2 - 1;
    let y = 1 - ((event.clientY - rect.top) / rect.height) * 2;
    const r = Math.hypot(x, y);
    if (r > 1) [x, y] = [x / r, y / r];
    const z = Math.sqrt(Math.max(0, 1 - x * x - y * y));
    setLight((Math.acos(z) * 180) / Math.PI, (Math.atan2(y, x) * 180) / Math.PI);
  }

  /** The compiled program of `view`; `transform(source, model)` may edit the assembled
   * source first (the object view's spatially varying parameters). */
  program(view, preamble = null, transform = null, { start = false } = {}) {
    const enums = Object.fromEntries(this.model.params.filter((p) => p.kind === "enum").map((p) => [p.name, this.values[p.name]]));
    // The light count is a constant of the lit views, as on the desktop.
    if (preamble === null) preamble = view === "sphere" ? `const int LIGHT_COUNT = ${lab.lights.length};` : "";
    const key = `${view}|${preamble}|${JSON.stringify(enums)}`;
    if (!this.programs.has(key)) {
      // A .brdf file assembles by its own rules (explorer.js).
      const assemble = this.model.assemble ?? assembleFragment;
      const source = assemble(this.model, view, lab.files, { target: "300es", preamble, enums, constants: C });
      if (transform) transform(source, this.model);
      this.programs.set(key, { pending: startProgram(this.gl, vertexSource("300es"), source.text), source });
    }
    if (start) return null;
    const entry = this.programs.get(key);
    if (entry.pending) {
      this.programs.delete(key); // a program that does not compile is tried again next time
      this.programs.set(key, finishModelProgram(entry.pending, entry.source));
    }
    return this.programs.get(key);
  }

  /** Queues the compiles of the programs `views` draw (their warm(); none given: the
   * sphere's and the probe's), so that the GPU process works on them while the page goes
   * on. Errors wait for the draw that needs the program: it reports them. */
  warmPrograms(views) {
    const tries = views ? views.map((view) => () => view.warm?.()) : [() => this.program("sphere", null, null, { start: true }),
      () => this.program("probe", null, null, { start: true })];
    for (const attempt of tries) {
      try {
        attempt();
      } catch (err) {
        if (!(err instanceof CompileFailure || err instanceof ModelError)) throw err;
      }
    }
    this.gl.flush();
  }

  /** A float RGBA texture (width x height, from `data()`) kept in `slot` while `key` stays
   * the same: directions that change only with the light are not uploaded again for every
   * frame of a moving parameter. */
  heldTexture(slot, key, width, height, data) {
    const gl = this.gl;
    this.held ??= new Map();
    const held = this.held.get(slot);
    if (held?.key === key) return held.texture;
    if (held) gl.deleteTexture(held.texture);
    const texture = floatTexture(gl, width, height, data());
    this.held.set(slot, { key, texture });
    return texture;
  }

  /** Draws `view` at width x height into a float target and reads it back (RGBA floats,
   * row 0 at the bottom). `suffix` renames the parameter uniforms (NAME_base). */
  run(view, width, height, uniforms, options = {}) {
    return this.collect(this.draw(view, width, height, uniforms, options));
  }

  /** Queues the draw of run() without waiting for it: a pass for collect() to read. */
  draw(view, width, height, uniforms, { preamble = "", transform = null, suffix = "", textures = [], tag = view } = {}) {
    const gl = this.gl;
    const compiled = this.program(view, preamble, transform);
    // The target first: making one binds its textures, which must not replace the inputs.
    // One per caller (tag) and size: passes queued together are read back after each other.
    const key = `${tag}|${width}x${height}`;
    if (!this.targets.has(key)) this.targets.set(key, floatTarget(gl, width, height, true));
    const target = this.targets.get(key);
    gl.useProgram(compiled.program);
    gl.bindVertexArray(this.vao);
    this.setParams(gl, compiled, suffix);
    textures.forEach((texture, unit) => {
      gl.activeTexture(gl.TEXTURE0 + unit);
      gl.bindTexture(gl.TEXTURE_2D, texture);
    });
    for (const [name, value] of Object.entries(uniforms)) setUniform(gl, compiled, name, value);
    gl.bindFramebuffer(gl.FRAMEBUFFER, target.fbo);
    gl.viewport(0, 0, width, height);
    gl.drawArrays(gl.TRIANGLES, 0, 3);
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    gl.flush(); // to the GPU now: it works while the page's JS goes on
    return { target, compiled, width, height };
  }

  /** Waits for a pass of draw() and reads it back (RGBA floats, row 0 at the bottom). */
  collect({ target, compiled, width, height }) {
    const gl = this.gl;
    gl.bindFramebuffer(gl.FRAMEBUFFER, target.fbo);
    const out = new Float32Array(width * height * 4);
    gl.readPixels(0, 0, width, height, gl.RGBA, gl.FLOAT, out);
    this.lastLoop = loopStop(gl, target, compiled);
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    return out;
  }

  setParams(gl, compiled, suffix = "") {
    this.model.bind?.(gl, compiled); // a measured table (measured.js)
    for (const p of this.model.params) {
      const location = compiled.uniforms[p.name + suffix] ?? compiled.uniforms[p.name];
      if (location === undefined || p.kind === "enum") continue;
      const v = this.values[p.name];
      if (p.kind === "float") gl.uniform1f(location, v);
      else if (p.kind === "color") gl.uniform3fv(location, v);
      else gl.uniform1i(location, v ? 1 : 0);
    }
  }

  render() {
    if (!this.gl || !this.model) return;
    const gl = this.gl;
    try {
      this.warmPrograms();
      this.renderSphere(gl);
      // Every view's GPU work is queued before the first read back (SwiftShader compiles
      // a program at its first draw: the GPU process does that for the next view while the
      // page draws the last one's picture). A view in rounds: submit queues its GPU work,
      // collect waits for it (and may queue a second round: the 3D lobe's mesh, once the
      // scale is known), process makes its picture in JS; a view with a second round is
      // processed last. The page shows the views in lab.views' order.
      const order = [...FRAME_ORDER.filter((n) => lab.views.includes(n)), ...lab.views.filter((n) => !FRAME_ORDER.includes(n))];
      const views = [];
      for (const name of order) {
        const view = this.extra[name];
        // Off screen a view waits: it draws when scrolled into sight (watchVisibility).
        if (view) view.stale = view.offscreen === true;
        if (view && !view.stale) views.push(view);
      }
      const polar = this.submitPolar(gl);
      this.warmPrograms(views);
      for (const view of views) view.submit?.();
      gl.flush();
      this.collectPolar(gl, polar);
      const late = [];
      for (const view of views) {
        if (!view.submit) view.render();
        else if (view.collect() === "later") late.push(view);
        else view.process();
      }
      for (const view of late) view.process();
      this.showError("");
    } catch (err) {
      if (!(err instanceof CompileFailure || err instanceof ModelError)) throw err;
      this.showError(err instanceof CompileFailure ? `the shader does not compile:\n${err.message}` : err.message);
    }
    this.renders++;
  }

  renderSphere(gl) {
    const compiled = this.program("sphere");
    const u = compiled.uniforms;
    gl.useProgram(compiled.program);
    gl.bindVertexArray(this.vao);
    this.setParams(gl, compiled);
    const dirs = new Float32Array(3 * C.MAX_LIGHTS);
    const rgb = new Float32Array(3 * C.MAX_LIGHTS);
    lab.lights.forEach((light, i) => {
      dirs.set(direction(light.theta, light.phi), 3 * i);
      rgb.set(light.rgb, 3 * i);
    });
    // While the hand moves, half the resolution: a quarter of the cost at 512 px.
    const step = lab.fast && lab.size >= SPHERE_FAST_MIN ? 2 : 1;
    let target = this.target;
    if (step === 2) {
      const half = Math.ceil(lab.size / 2);
      this.coarseTarget ??= floatTarget(gl, half, half);
      target = this.coarseTarget;
    }
    this.sphereStep = step;
    gl.uniform2f(u.u_resolution, target.width, target.height);
    if (u.u_light_dir) gl.uniform3fv(u.u_light_dir, dirs);
    if (u.u_light_rgb) gl.uniform3fv(u.u_light_rgb, rgb);
    if (u.u_ambient) gl.uniform3fv(u.u_ambient, lab.ambient);
    if (u.u_multiply_cos) gl.uniform1i(u.u_multiply_cos, 1);
    gl.bindFramebuffer(gl.FRAMEBUFFER, target.fbo);
    gl.viewport(0, 0, target.width, target.height);
    gl.drawArrays(gl.TRIANGLES, 0, 3);
    // Show it: exposure and the sRGB curve, on the canvas.
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    gl.useProgram(this.display.program);
    gl.activeTexture(gl.TEXTURE0);
    gl.bindTexture(gl.TEXTURE_2D, target.texture);
    gl.uniform1i(this.display.uniforms.u_step, step);
    gl.viewport(0, 0, lab.size, lab.size);
    gl.uniform1i(this.display.uniforms.u_image, 0);
    gl.uniform1f(this.display.uniforms.u_scale, Math.pow(2, lab.exposure));
    gl.drawArrays(gl.TRIANGLES, 0, 3);
  }

  /** Queues the lobe in the plane of incidence (probe values, read back as floats). */
  submitPolar(gl) {
    const { theta, phi } = lab.light;
    const key = `${theta},${phi},${lab.phiO}`;
    const directions = (which) => () => {
      const Ld = direction(theta, phi);
      // The plane of the plot: the plane of incidence turned by phi_o about the normal.
      const plane = planeOfIncidence(phi + lab.phiO).V;
      const out = new Float32Array(4 * POLAR_STEPS);
      for (let i = 0; i < POLAR_STEPS; i++) out.set(which === "L" ? Ld : plane[i], 4 * i);
      return out;
    };
    const textures = [this.heldTexture("polar L", key, POLAR_STEPS, 1, directions("L")),
      this.heldTexture("polar V", key, POLAR_STEPS, 1, directions("V"))];
    return this.draw("probe", POLAR_STEPS, 1, { u_L: 0, u_V: 1 }, { textures, tag: "polar" });
  }

  collectPolar(gl, pass) {
    this.lobe = this.collect(pass);
    this.showLoop(this.lastLoop);
    // The spike leaves the plot's plane when it is turned.
    const { theta, phi } = lab.light;
    this.spike = this.model.delta && lab.phiO === 0 ? this.deltaReflectance(gl, theta, phi) : null;
  }

  /** The reflectance (RGB) of a delta model's spike, read back from its DELTA_REFLECTANCE:
   * the albedo view with no samples leaves only the delta's share (as lab/render.py does). */
  deltaReflectance(gl, thetaDeg, phiDeg) {
    const compiled = this.program("albedo");
    const u = compiled.uniforms;
    gl.useProgram(compiled.program);
    gl.bindVertexArray(this.vao);
    this.setParams(gl, compiled);
    gl.uniform1f(u.u_theta0, (thetaDeg * Math.PI) / 180);
    if (u.u_theta_step) gl.uniform1f(u.u_theta_step, 0);
    if (u.u_phi_i) gl.uniform1f(u.u_phi_i, (phiDeg * Math.PI) / 180);
    if (u.u_samples) gl.uniform1i(u.u_samples, 0);
    gl.uniform1i(u.u_wedges, 1);
    gl.bindFramebuffer(gl.FRAMEBUFFER, this.probeTarget.fbo);
    gl.viewport(0, 0, 1, 1);
    gl.drawArrays(gl.TRIANGLES, 0, 3);
    const out = new Float32Array(4);
    gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.FLOAT, out);
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    return Array.from(out.subarray(0, 3));
  }

  /** The float render of the sphere, rows from the top, as {width, height, data}. */
  readSphere() {
    const gl = this.gl;
    const { width, height } = this.target;
    const raw = new Float32Array(width * height * 4);
    gl.bindFramebuffer(gl.FRAMEBUFFER, this.target.fbo);
    gl.readPixels(0, 0, width, height, gl.RGBA, gl.FLOAT, raw);
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    const flipped = new Float32Array(raw.length);
    const row = width * 4;
    for (let y = 0; y < height; y++) flipped.set(raw.subarray(y * row, (y + 1) * row), (height - 1 - y) * row);
    return { width, height, data: flipped };
  }
}

const luma = (r, g, b) => C.LUMA[0] * r + C.LUMA[1] * g + C.LUMA[2] * b;

/** A panel's lobe as plotted: luminance of f_r (times cos θo when asked), its peak away from
 * grazing (where some models diverge) and its delta spike's luminance. */
function lobeLuminance(panel) {
  const values = panel.lobe;
  const lum = [];
  const thetaO = [];
  for (let i = 0; i < POLAR_STEPS; i++) {
    let f = luma(values[4 * i], values[4 * i + 1], values[4 * i + 2]);
    if (lab.cosWeighted) f *= Math.cos(((i - 90) * Math.PI) / 180);
    f = Number.isFinite(f) ? Math.max(f, 0) : 0;
    lum.push(f);
    thetaO.push(i - 90);
  }
  const peak = peakValue(thetaO, lum, C.GRAZING_DEG);
  return { lum, peak, spike: panel.spike ? luma(...panel.spike) : null, color: panel.color, name: panel.name };
}

/** Every polar plot on one scale: each panel's, and all models overlaid when there are
 * several. The outer circle is the largest peak; with a delta spike at least 1, so a
 * spike's length is its reflectance (the whole circle = all the light). */
function drawPolars() {
  const curves = lab.panels.filter((p) => p.lobe && p.model).map((p) => [p, lobeLuminance(p)]);
  const scale = Math.max(0, ...curves.map(([, c]) => (c.spike !== null ? Math.max(c.peak, 1) : c.peak)));
  const theta = lab.lights[0].theta;
  const own = (curve) => (curve.spike !== null ? Math.max(curve.peak, 1) : curve.peak);
  for (const [panel, curve] of curves) {
    const each = lab.scaleEach ? own(curve) : scale;
    panel.polarGeometry = lab.plot === "theta"
      ? drawCurve(panel.polar, curve, theta, each, { fontPx: pageFontPx(), grazingDeg: C.GRAZING_DEG,
        what: lab.cosWeighted ? "fᵣ cos θₒ" : "fᵣ", inPlane: lab.phiO === 0, range: sharedRange(curves.map(([, c]) => c.lum), theta, C.GRAZING_DEG, lab.phiO === 0) })
      : drawPolar(panel.polar, [curve], theta, each);
  }
  const overlay = $("#overlay");
  overlay.hidden = curves.length < 2;
  if (!overlay.hidden) lab.overlayGeometry = drawPolar($("#overlay canvas"), curves.map(([, c]) => c), theta, scale, true);
}

/** Radius (0..1 of the plot's) of value f on a scale whose outer circle is `scale`. */
function polarRadius(f, scale) {
  return scaleRadius(f, scale, lab.polarLog, C.PLOT_DECADES);
}

/** Lobes on a half disc, 0 deg = the normal, rings labelled with their values. */
function drawPolar(canvas, curves, thetaI, scale, legend = false) {
  const ctx = canvas.getContext("2d");
  const w = canvas.width;
  const h = canvas.height;
  // Text the same size on screen whatever the canvas is scaled to (embedded demos shrink it).
  const shown = canvas.clientWidth || w;
  const font = lab.embed ? Math.round((pageFontPx() * w) / shown) : Math.min(Math.round((12 * w) / shown), Math.round(w / 14));
  const ringFont = Math.round(font * (lab.embed ? 1 : 0.85));
  const cx = w / 2;
  // Ring values clear of the lobes: in a row below the baseline, or (where that gives the
  // larger disc: a short canvas, a slide's) only the rim's, beside the rim.
  ctx.font = `${ringFont}px system-ui, sans-serif`;
  const rimText = formatG(Number(scale.toPrecision(2)));
  const rimRoom = ctx.measureText(rimText).width + 0.3 * ringFont + 2;
  const above = (lab.embed ? 3.8 : 3.5) * font;
  const bottom = Math.round(ringFont * 1.25);
  const below = Math.min(w / 2 - 2.2 * font, h - bottom - above);
  const beside = Math.min(w / 2 - Math.max(2.2 * font, rimRoom), h - Math.round(font * 0.6) - above);
  const rowBelow = below >= beside;
  const cy = h - (rowBelow ? bottom : Math.round(font * 0.6));
  const radius = Math.max(rowBelow ? below : beside, 8);
  ctx.clearRect(0, 0, w, h);
  ctx.font = `${font}px system-ui, sans-serif`;
  ctx.lineWidth = 1.5; // a thinner line's antialiased pixels fall under 3:1
  // Rings: quarters of the scale, or one per decade on the log scale; values beside them.
  const rings = lab.polarLog
    ? Array.from({ length: C.PLOT_DECADES }, (_, k) => [(C.PLOT_DECADES - k) / C.PLOT_DECADES, scale * Math.pow(10, -k)])
    : [0.25, 0.5, 0.75, 1].map((r) => [r, r * scale]);
  ctx.strokeStyle = "#a0a6b0"; // axes and rings at 3:1 or more against the panel, antialiased (WCAG 1.4.11)
  ctx.beginPath();
  ctx.moveTo(cx - radius, cy);
  ctx.lineTo(cx + radius, cy);
  ctx.moveTo(cx, cy);
  ctx.lineTo(cx, cy - radius);
  ctx.stroke();
  // Negative angles (toward the light) on the right: the light on the same side as on the
  // spheres and the 3D lobe.
  const at = (angleDeg, r) => {
    const a = (angleDeg * Math.PI) / 180;
    return [cx - r * Math.sin(a), cy - r * Math.cos(a)];
  };
  ctx.fillStyle = "#999";
  ctx.font = `${ringFont}px system-ui, sans-serif`;
  // Each value centred under its ring, from the rim inward (the rim's always shows, kept
  // inside the canvas); one that would run into the last one drawn is left out.
  let end = w - 2;
  const ringLabels = []; // [text, left, top, right, bottom] of each value drawn
  for (const [r, value] of [...rings].sort((a, b) => b[0] - a[0])) {
    ctx.strokeStyle = r === 1 ? "#a0a6b0" : "#8a909c";
    ctx.beginPath();
    ctx.arc(cx, cy, radius * r, Math.PI, 2 * Math.PI);
    ctx.stroke();
    const text = formatG(Number(value.toPrecision(2)));
    const width = ctx.measureText(text).width;
    if (scale <= 0) continue;
    if (!rowBelow) {
      const x = cx + radius + 0.3 * ringFont;
      if (r === 1) {
        ctx.fillText(text, x, cy - 3);
        ringLabels.push([text, x, cy - 3 - ringFont, x + width, cy - 3]);
      }
      continue;
    }
    const centred = cx + radius * r - width / 2;
    const x = r === 1 ? Math.min(centred, end - width) : centred;
    if (x + width <= end) {
      ctx.textBaseline = "top";
      ctx.fillText(text, x, cy + 2);
      ctx.textBaseline = "alphabetic";
      ringLabels.push([text, x, cy + 2, x + width, cy + 2 + ringFont]);
      end = x - 0.5 * ringFont;
    }
  }
  ctx.font = `${font}px system-ui, sans-serif`;
  const ray = (angleDeg, r, color, dash) => {
    ctx.strokeStyle = color;
    ctx.setLineDash(dash);
    ctx.beginPath();
    ctx.moveTo(cx, cy);
    ctx.lineTo(...at(angleDeg, r));
    ctx.stroke();
    ctx.setLineDash([]);
  };
  const label = (text, angleDeg, r, color, dx = 0) => {
    ctx.fillStyle = color;
    ctx.textAlign = "center";
    ctx.textBaseline = "middle";
    const [x, y] = at(angleDeg, r);
    ctx.fillText(text, x + dx, y);
    ctx.textAlign = "left";
    ctx.textBaseline = "alphabetic";
  };
  const inPlane = lab.phiO === 0;
  if (inPlane) {
    ray(-thetaI, radius, "#e0a030", []); // toward the light
    ray(thetaI, radius, "#a0a6b0", [4, 4]); // mirror direction
  }
  // Near normal incidence L and R sit on N: one merged label instead of three on top of
  // each other; a little further out, L and R pushed apart either side.
  if (!inPlane) label("N", 0, radius + 0.7 * font, "#aaa");
  else if (thetaI < 4) label("N = L = R", 0, radius + 0.7 * font, "#e0a030");
  else {
    if (thetaI >= 12) label("N", 0, radius + 0.7 * font, "#aaa");
    label("L", -thetaI, radius + 0.8 * font, "#e0a030", thetaI < 12 ? 0.6 * font : 0);
    label("R", thetaI, radius + 0.8 * font, "#aaa", thetaI < 12 ? -0.6 * font : 0);
  }
  const what = lab.cosWeighted ? "fᵣ cos θₒ" : "fᵣ";
  ctx.fillStyle = "#bbb";
  const plane = inPlane ? "plane of incidence" : `plane turned φo = ${formatG(lab.phiO)}°`;
  const title = `${what}, ${plane}${lab.lights.length > 1 ? " of light 1" : ""}`;
  ctx.fillText(ctx.measureText(title).width < w - 4 ? title : `${what}, light 1`, 2, font);
  const spikes = curves.some((c) => c.spike !== null);
  const peak = Math.max(0, ...curves.map((c) => c.peak));
  const circle = spikes && peak < 1 ? "1 (all the light)" : `${formatG(round(scale))} sr⁻¹`;
  const log = lab.polarLog ? `, log: ${C.PLOT_DECADES} decades` : "";
  // The shared rule (lab/plotscale.py): grazing values beyond GRAZING_DEG stay out of the
  // scale; what exceeds it is drawn at the rim, marked, and its largest value named.
  const over = [];
  for (const curve of curves) {
    curve.lum.forEach((f, i) => scale > 0 && f > scale * (1 + 1e-6) && over.push([curve, i]));
  }
  const clippedMax = over.length ? Math.max(...over.map(([c, i]) => c.lum[i])) : 0;
  const clipped = over.length ? `; ▼ clipped: up to ${formatG(round(clippedMax))} sr⁻¹` : "";
  // The longest wording that fits (large text in a slide leaves little room).
  const fit = (...texts) => texts.find((t) => ctx.measureText(t).width <= w - 4) || texts[texts.length - 1];
  ctx.fillText(scale > 0 ? fit(`outer circle: ${circle}${log}${clipped}`, `outer circle: ${circle}${log}`,
    `outer: ${circle}`) : "fᵣ = 0 in this plane", 2, 2.2 * font);
  let spikeLength = 0;
  let spikeLabel = null; // [left, top, right, bottom] of the spike's value
  for (const curve of curves) {
    if (curve.peak > 0 || curve.lum.some((f) => f > 0)) {
      ctx.strokeStyle = curve.color;
      ctx.fillStyle = `${curve.color}33`;
      ctx.lineWidth = 2;
      ctx.beginPath();
      ctx.moveTo(cx, cy);
      curve.lum.forEach((f, i) => ctx.lineTo(...at(i - 90, radius * polarRadius(f, scale))));
      ctx.closePath();
      if (curves.length === 1) ctx.fill();
      ctx.stroke();
    }
    if (curve.spike !== null) {
      ctx.lineWidth = 4;
      spikeLength = radius * polarRadius(curve.spike, scale);
      ray(thetaI, spikeLength, curves.length === 1 ? "#ff5a5a" : curve.color, []);
      ctx.lineWidth = 1;
      ctx.fillStyle = "#ff7a7a";
      // Below the spike's middle, on its outer side: clear of the spike (it leans outward
      // above there), the normal and the light's ray; kept inside the canvas.
      const text = `δ spike, ρ = ${formatG(round(curve.spike))}`;
      const [x, y] = at(thetaI, spikeLength * 0.5);
      const width = ctx.measureText(text).width;
      const [left, base] = [Math.min(Math.max(x - 6 - width, 2), w - width - 2), Math.max(y + font, 3.2 * font)];
      ctx.fillText(text, left, base);
      spikeLabel = [left, base - font, left + width, base];
    }
  }
  ctx.fillStyle = "#dc283c";
  for (const [, i] of over) {
    const [x, y] = at(i - 90, radius);
    ctx.beginPath();
    ctx.moveTo(x - 4, y - 6);
    ctx.lineTo(x + 4, y - 6);
    ctx.lineTo(x, y);
    ctx.fill();
  }
  ctx.lineWidth = 1;
  if (legend) {
    curves.forEach((curve, k) => {
      // Names in the text colour (4.5:1), each after a bar of its curve's colour.
      const text = curve.name;
      const [x, y] = [w - ctx.measureText(text).width - 4, (k + 2.6) * 1.2 * font];
      ctx.fillStyle = "#e6e6e6";
      ctx.fillText(text, x, y);
      ctx.fillStyle = curve.color;
      ctx.fillRect(x - 1.6 * font, y - 0.45 * font, 1.2 * font, 0.3 * font);
    });
  }
  return { radius, scale, spikeLength, centre: [cx, cy], ringLabels, spikeLabel };
}

// -- the editor (edit.js) -------------------------------------------------------------------
let editor = null;
// Model or exercise name -> the text it came with (library file, opened file or stub): the
// editor's reset goes back to it, and an edited text equal to it is no draft to keep.
const originals = {};
const originalText = (name) => originals[name] ?? lab.files[`brdfs/${name}.glsl`] ?? null;

/** The editor's text of a model (or exercise), kept in this browser until it is the
 * original again (store.js). */
function keepText(panel, text) {
  if (!embedded()) keepDraft(panel.name, text === originalText(panel.name) ? null : text);
}

/** Embedded in a slide, the page shows the library as it is: the student's (or the
 * presenter's) kept files and edits of this browser stay out of the lecture's demos. */
function embedded() {
  const value = new URLSearchParams(location.hash.slice(1)).get("embed");
  return value !== null && value !== "0";
}

/** The model of an edited text, as the editor builds it: an opened file's own rules, a
 * library file's header checked against its name. */
function modelOfText(name, text) {
  const model = lab.models[name];
  if (model?.rebuild) return model.rebuild(text);
  return parseModel(text, model?.path || `shaders/brdfs/${name}.glsl`, name);
}

/** Compiles the sphere program of `model` on the panel's context (throws CompileFailure). */
function tryCompile(panel, model) {
  if (!panel.gl) return;
  const enums = Object.fromEntries(model.params.filter((p) => p.kind === "enum").map((p) => [p.name,
    p.choices.includes(panel.values[p.name]) ? panel.values[p.name] : p.default]));
  const assemble = model.assemble ?? assembleFragment; // a .brdf file assembles by its own rules
  const source = assemble(model, "sphere", lab.files, { target: "300es", enums, constants: C,
    preamble: `const int LIGHT_COUNT = ${lab.lights.length};` });
  panel.gl.deleteProgram(compile(panel.gl, source.text, source).program);
}

/** Shows an edited model that compiled in every panel of that name. A value the student
 * set is kept where the parameter is still there with the same kind and range; one at the
 * old default follows the file's new default. */
function installModel(panel, model) {
  lab.models[panel.name] = model;
  delete lab.modelErrors[panel.name];
  for (const other of lab.panels.filter((p) => p.name === panel.name)) {
    const kept = {};
    for (const p of model.params) {
      const old = other.model?.params.find((q) => q.name === p.name);
      const changed = old && JSON.stringify(other.values[p.name]) !== JSON.stringify(old.default);
      if (changed && old.kind === p.kind && JSON.stringify(old.choices) === JSON.stringify(p.choices) &&
        (p.kind !== "float" || (other.values[p.name] >= p.minimum && other.values[p.name] <= p.maximum))) {
        kept[p.name] = other.values[p.name];
      }
    }
    other.setModel(panel.name, kept);
  }
  lab.panels.forEach((p) => p.fillPicker());
  scheduleRender();
}

/** Opens the editor on a panel's model; `options` (exercise mode): {path, build(text),
 * onResult(errors)} and `original` the stub. */
async function openEditor(panel, original = null, options = {}) {
  const name = panel.name;
  if (!options.build && lab.exerciseList.some((e) => e.name === name)) return openExercise(name);
  // A table has no text; a file with a header error has no model to edit yet.
  const why = panel.model?.notText ?? (panel.model ? "" : `${name} did not open: ${lab.modelErrors[name] || "no such model"}; ` +
    "fix the file and open it again");
  if (why) {
    showTip(why);
    return;
  }
  // The editor (CodeMirror, 400 kB) loads when first opened, not with the page.
  if (!editor) {
    const { ShaderEditor } = await import("./edit.js");
    editor ??= new ShaderEditor($("#editor"), { lab, el, tryCompile, install: installModel, keepText });
  }
  originals[name] ??= original ?? originalText(name) ?? panel.model?.code ?? "";
  // The student's unsaved text of an earlier visit comes back; else what the panel shows.
  const text = draft(name) ?? options.text ?? panel.model?.text ?? panel.model?.code;
  editor.open(panel, originals[name], { build: (t) => modelOfText(name, t), path: panel.model?.opened, ...options, text });
  $("#editor").scrollIntoView({ block: "nearest" });
}

let exercises = null;
async function openExercise(name) {
  exercises ??= new ExerciseMode($("#exercise"), { lab, el, C, direction, openEditor,
    addPanel: (n) => {
      const panel = addPanel(n);
      scheduleRender();
      return panel;
    },
    removePanel });
  await exercises.open(name);
  writeHash();
}

// What views.js needs from the page.
const viewEnv = { lab, C, el, viewBox, direction, scheduleRender: () => scheduleRender() };

/** Views off screen skip their (costly) renders; one that comes into sight and missed a
 * render draws then. Until the first report a view counts as visible. */
const seen = new IntersectionObserver((entries) => {
  let missed = false;
  for (const entry of entries) {
    const view = entry.target.labView;
    view.offscreen = !entry.isIntersecting;
    missed ||= entry.isIntersecting && view.stale;
  }
  if (missed) scheduleRender();
});
function watchVisibility(view) {
  view.root.labView = view;
  seen.observe(view.root);
}

// -- page-level actions ---------------------------------------------------------------------
let pending = 0;
let settle = 0;
const SETTLE_MS = 200;
let handMoving = false; // a slider or a drag moved within SETTLE_MS

/** While the hand moves (slider input, drag) the costly views draw coarse; the full
 * version follows SETTLE_MS after the last move. */
function moving() {
  clearTimeout(settle);
  lab.fast = lab.views.length > 0;
  handMoving = true;
  settle = setTimeout(() => {
    handMoving = false;
    writeHash();
    if (!lab.fast) return;
    lab.fast = false;
    scheduleRender();
  }, SETTLE_MS);
}

let hashWritten = -Infinity; // performance.now() of the last address update
let hashTimer = 0;
const HASH_MS = 250;

/** The address follows the page: at once, but while the hand moves at most every HASH_MS
 * (and once it stops). An update per frame would cost the frame milliseconds now and
 * then, and browsers stop taking them after a few hundred in ten seconds. */
function writeHashSoon() {
  if (!handMoving) return writeHash();
  if (hashTimer) return;
  const wait = hashWritten + HASH_MS - performance.now();
  if (wait <= 0) writeHash();
  else hashTimer = setTimeout(writeHash, wait);
}
addEventListener("input", (e) => e.target.type === "range" && moving(), true);
addEventListener("pointermove", (e) => e.buttons && e.target.tagName === "CANVAS" && moving(), true);

/** Full quality now (readers want what the page shows once the hand stops). */
function settleNow() {
  if (!lab.fast) return;
  clearTimeout(settle);
  handMoving = false;
  lab.fast = false;
  renderNow();
  writeHash();
}

function scheduleRender() {
  writeHashSoon();
  if (!pending) pending = requestAnimationFrame(() => {
    pending = 0;
    renderAll();
  });
}

function renderAll() {
  for (const panel of lab.panels) panel.render();
  drawPolars();
}

const clampTheta = (theta) => round(Math.min(Math.max(theta, 0), 90));
const wrapPhi = (phi) => round(((phi % 360) + 540) % 360 - 180);

/** Moves light `index` (the active one unless given) and shows it in its row. */
function setLight(theta, phi, index = lab.active) {
  const light = lab.lights[index];
  light.theta = clampTheta(theta);
  light.phi = wrapPhi(phi);
  const row = $(`.light-row[data-light="${index}"]`);
  if (row) {
    $(".theta", row).value = light.theta;
    $(".phi", row).value = light.phi;
    $(".theta-text", row).textContent = `${formatG(light.theta)}°`;
    $(".phi-text", row).textContent = `${formatG(light.phi)}°`;
  }
  scheduleRender();
}

function setActiveLight(index) {
  lab.active = index;
  document.querySelectorAll(".light-row").forEach((row) => {
    row.classList.toggle("active", lab.lights.length > 1 && Number(row.dataset.light) === index);
  });
}

/** One row of controls per light: theta_i, phi_i (degrees), colour, remove. */
function buildLights() {
  const rows = lab.lights.map((light, i) => {
    const first = i === 0;
    const theta = el("input", { type: "range", class: "theta", min: 0, max: 90, step: 0.5,
      ...(first ? { id: "light-theta" } : {}) });
    const phi = el("input", { type: "range", class: "phi", min: -180, max: 180, step: 1,
      ...(first ? { id: "light-phi" } : {}) });
    theta.addEventListener("input", () => setLight(Number(theta.value), lab.lights[i].phi, i));
    phi.addEventListener("input", () => setLight(lab.lights[i].theta, Number(phi.value), i));
    const color = el("input", { type: "color", class: "light-color", value: toHex(light.rgb),
      title: "colour of this light (its radiance, before exposure)" });
    color.addEventListener("input", () => {
      lab.lights[i].rgb = fromHex(color.value);
      scheduleRender();
    });
    const thetaTip = "θi: angle between the light and the view direction, which is the normal at " +
      "the sphere's centre (0° = light at the eye)";
    const phiTip = "φi: azimuth of the light around the view direction (0° = from the right, " +
      "90° = from the top)";
    const row = el("span", { class: "light-row group", "data-light": i,
      title: lab.lights.length > 1 ? "dragging on a sphere moves the framed light: click a row to choose" : "" },
      el("span", { class: "light-name" }, lab.lights.length > 1 ? `light ${i + 1}` : "light"),
      el("label", { title: thetaTip }, el("span", { class: "name" }, "θi"), " ", theta),
      el("span", { class: "theta-text deg" }),
      el("label", { title: phiTip }, el("span", { class: "name" }, "φi"), " ", phi),
      el("span", { class: "phi-text deg" }), color);
    if (!first) {
      row.append(el("button", { type: "button", class: "close", title: "remove this light",
        onclick: () => {
          lab.lights.splice(i, 1);
          lab.active = 0;
          buildLights();
          fitEmbed();
          scheduleRender();
        } }, "×"));
    }
    row.addEventListener("pointerdown", () => setActiveLight(i));
    return row;
  });
  $("#lights").replaceChildren(...rows);
  lab.lights.forEach((light, i) => setLight(light.theta, light.phi, i));
  $("#add-light").disabled = lab.lights.length >= C.MAX_LIGHTS;
  setActiveLight(Math.min(lab.active, lab.lights.length - 1));
}

function addLight(light = null) {
  if (lab.lights.length >= C.MAX_LIGHTS) return;
  const first = lab.lights[0];
  lab.lights.push(light || { theta: 60, phi: wrapPhi(first.phi + 180), rgb: [1, 1, 1] });
  buildLights();
  setActiveLight(lab.lights.length - 1);
  fitEmbed();
  scheduleRender();
}

/** The ambient slider shows a grey level (an address may give any r,g,b). */
function showAmbient() {
  const [r, g, b] = lab.ambient;
  $("#ambient").value = Math.max(r, g, b);
  $("#ambient-text").textContent = r === g && g === b ? formatG(r) : lab.ambient.map(formatG).join(",");
}

/** Embedded in a slide: shrink the canvases until the page fits the frame unscrolled. */
function fitEmbed() {
  if (!lab.embed) return;
  document.body.classList.toggle("single", lab.panels.length === 1);
  showOnly(lab.show);
  lab.panels.forEach((panel) => fitPlotAspect(panel.polar, lab.panels.length));
  const root = document.documentElement;
  const apply = (px) => lab.panels.forEach((panel) => panel.displaySize(px));
  let px = lab.size;
  apply(px);
  for (let k = 0; k < 6; k++) {
    const over = Math.max(root.scrollHeight - innerHeight,
      (root.scrollWidth - innerWidth) / Math.max(1, lab.panels.length));
    if (over <= 0 || px <= 96) break;
    px = Math.max(96, Math.floor(px - over - 2));
    apply(px);
  }
}

/** "+ model" is off once the page shows as many models as it can. */
function showAddModel() {
  const button = $("#add-model");
  button.disabled = lab.panels.length >= MAX_PANELS;
  button.title = button.disabled ? `at most ${MAX_PANELS} models side by side`
    : "show another model beside the others";
}

function addPanel(name, values) {
  if (lab.panels.length >= MAX_PANELS) return null;
  const panel = new Panel(name, values);
  lab.panels.push(panel);
  $("#panels").append(panel.root);
  panel.syncViews();
  showAddModel();
  fitEmbed();
  return panel;
}

/** The panels of an address; an exercise's (model=01_lambert) opens that exercise with the
 * student's kept text. */
function addPanels(panels) {
  for (const p of panels) {
    if (lab.exerciseList.some((e) => e.name === p.name)) openExercise(p.name).then(() => showNotes());
    else addPanel(p.name, p.values);
  }
}

function removePanel(panel) {
  if (lab.panels.length <= 1) return;
  if (editor?.panel === panel) editor.close();
  lab.panels.splice(lab.panels.indexOf(panel), 1);
  panel.destroy();
  showAddModel();
  fitEmbed();
  scheduleRender();
}

/** The page's lights and settings back to their defaults (the models are the panels'). */
function defaultSettings() {
  lab.lights = [{ ...DEFAULT_LIGHT, rgb: [...DEFAULT_LIGHT.rgb] }];
  lab.ambient = [0, 0, 0];
  lab.exposure = 0;
  lab.cosWeighted = false;
  lab.active = 0;
  Object.assign(lab, SETTINGS);
}

// -- URL hash: model=NAME&PARAM=VALUE...&model=NAME2...&light=THETA,PHI[,R,G,B]...&ambient=R,G,B
function readHash() {
  // An address holds the whole state: what it leaves out has its default.
  defaultSettings();
  lab.views = [];
  lab.show = null;
  lab.plot = "polar";
  lab.scaleEach = false;
  const params = new URLSearchParams(location.hash.slice(1));
  let iblValue = null; // the IBL view's settings (ibl.js)
  const panels = [];
  const lights = [];
  for (const [key, value] of params) {
    if (key === "model") panels.push({ name: value, values: {} });
    else if (key === "light") {
      const [theta, phi, ...rest] = value.split(",").map(Number);
      const rgb = rest.length ? parseRgb(rest.join(",")) : [1, 1, 1];
      if (!Number.isFinite(theta) || (rest.length && !rgb)) {
        lab.notes.push(`light=${value}: write THETA,PHI in degrees, optionally ,R,G,B`);
      } else if (lights.length < C.MAX_LIGHTS) {
        lights.push({ theta: clampTheta(theta), phi: wrapPhi(Number.isFinite(phi) ? phi : 0), rgb });
      }
    } else if (key === "ambient") {
      const rgb = parseRgb(value);
      if (rgb) lab.ambient = rgb;
      else lab.notes.push(`ambient=${value}: write R,G,B (each 0 or more)`);
    } else if (key === "exposure") lab.exposure = Number(value) || 0;
    else if (key === "size" && lab.panels.length) {
      // The float targets have their size: a new size needs a reload.
      if (Math.round(Number(value)) !== lab.size) lab.notes.push("size=: reload the page to change the render size");
    } else if (key === "size") lab.size = Math.min(Math.max(Math.round(Number(value)) || 384, 32), 1024);
    else if (key === "embed") lab.embed = value !== "0";
    else if (key === "show") lab.show = value.split(",").filter(Boolean);
    else if (key === "scale") {
      if (value === "each" || value === "shared") lab.scaleEach = value === "each";
      else lab.notes.push(`scale=${value}: write scale=each (each plot on its own scale) or scale=shared`);
    } else if (key === "plot") {
      if (value === "theta" || value === "polar") lab.plot = value;
      else lab.notes.push(`plot=${value}: write plot=polar or plot=theta (the lobe against θo)`);
    }
    else if (key === "cos") lab.cosWeighted = value !== "0";
    else if (key === "log") lab.polarLog = value !== "0";
    else if (key === "views") {
      const names = value.split(",").filter(Boolean);
      const unknown = names.filter((n) => !VIEWS[n]);
      if (unknown.length) lab.notes.push(`views=${value}: unknown ${unknown.join(", ")}; choose from ${Object.keys(VIEWS).join(", ")}`);
      lab.views = Object.keys(VIEWS).filter((n) => names.includes(n));
    } else if (key === "ibl") iblValue = value;
    else if (key in HASH_SETTINGS) {
      const [field, lo, hi] = HASH_SETTINGS[key];
      const number = Number(value);
      if (value === "" || !Number.isFinite(number) || number < lo || number > hi) {
        lab.notes.push(`${key}=${value}: give a number from ${lo} to ${hi}`);
      } else lab[field] = Number.isInteger(SETTINGS[field]) && !CONTINUOUS.includes(field) ? Math.round(number) : number;
    }
    else if (panels.length) panels[panels.length - 1].values[key] = value;
    else lab.notes.push(`${key}=${value}: give model=NAME before its parameters`);
  }
  // Check each value against its model's header; bad ones are reported and left out.
  for (const panel of panels) {
    const model = lab.models[panel.name];
    if (lab.exerciseList.some((e) => e.name === panel.name)) continue; // exercise mode
    if (!model) {
      // An address keeps a model's name only: an opened file must be in this browser.
      lab.notes.push(lab.modelErrors[panel.name] ? `${panel.name}: ${lab.modelErrors[panel.name]}`
        : `unknown model ${panel.name}: it is not in the library and no file of that name was opened in ` +
        `this browser (an address keeps a model's name, not its file). Open its file (.glsl, .brdf or .binary) ` +
        `with "open file" to see it, or choose one of ${lab.order.join(", ")}`);
      panel.name = null;
      continue;
    }
    const checked = {};
    for (const [key, text] of Object.entries(panel.values)) {
      const p = model.params.find((q) => q.name === key);
      try {
        if (!p) throw new Error(`model ${model.name} has no parameter ${key}`);
        checked[key] = parseValue(p, text);
      } catch (err) {
        lab.notes.push(err.message);
      }
    }
    panel.values = checked;
  }
  readIblHash(iblValue, lab.environments?.names || [], lab.notes);
  if (lights.length) lab.lights = lights;
  const kept = panels.filter((p) => p.name);
  if (kept.length > MAX_PANELS) {
    const left = kept.slice(MAX_PANELS).map((p) => p.name);
    lab.notes.push(`at most ${MAX_PANELS} models side by side; left out: ${left.join(", ")}`);
  }
  return kept.slice(0, MAX_PANELS);
}

function writeHash() {
  clearTimeout(hashTimer);
  hashTimer = 0;
  hashWritten = performance.now();
  const parts = [];
  for (const panel of lab.panels) {
    if (!panel.model) continue;
    parts.push(`model=${panel.name}`);
    for (const p of panel.model.params) {
      const v = panel.values[p.name];
      if (valueText(p, v) !== valueText(p, p.default)) parts.push(`${p.name}=${valueText(p, v)}`);
    }
  }
  for (const light of lab.lights) {
    const white = light.rgb.every((c) => c === 1);
    const rgb = white ? "" : `,${light.rgb.map(formatG).join(",")}`;
    parts.push(`light=${formatG(light.theta)},${formatG(light.phi)}${rgb}`);
  }
  if (lab.ambient.some((c) => c)) parts.push(`ambient=${lab.ambient.map(formatG).join(",")}`);
  if (lab.exposure) parts.push(`exposure=${formatG(lab.exposure)}`);
  if (lab.size !== 384) parts.push(`size=${lab.size}`);
  if (lab.cosWeighted) parts.push("cos=1");
  if (lab.polarLog) parts.push("log=1");
  if (lab.views.length) parts.push(`views=${lab.views.join(",")}`);
  if (iblHash()) parts.push(iblHash());
  for (const [key, [field]] of Object.entries(HASH_SETTINGS)) {
    if (lab[field] !== SETTINGS[field]) parts.push(`${key}=${formatG(round(lab[field]))}`);
  }
  if (lab.show) parts.push(`show=${lab.show.join(",")}`);
  if (lab.plot !== "polar") parts.push(`plot=${lab.plot}`);
  if (lab.scaleEach) parts.push("scale=each");
  if (lab.embed) parts.push("embed=1");
  history.replaceState(null, "", `#${parts.join("&")}`);
}

// Address keys of the page settings: [field of lab, smallest, largest].
// Settings that keep their fractions in an address (the others with whole defaults round).
const CONTINUOUS = ["yaw", "pitch", "lobeZoom"];
const HASH_SETTINGS = { lyaw: ["lobeYaw", -100, 100], lpitch: ["lobePitch", -1.5, 1.5], lzoom: ["lobeZoom", 0.2, 8],
  sh: ["shOrder", 0, 16], phid: ["phiD", 0, 180], phio: ["phiO", 0, 180], shape: ["shape", 0, 3],
  mode: ["mode", 0, 3], yaw: ["yaw", -100, 100], pitch: ["pitch", -1.5, 1.5] };

/** The address of a desktop preset: its models (library names) and light settings; what the
 * page cannot show yet is listed in `skipped`. */
export function presetHash(preset, skipped = []) {
  const s = preset.settings || {};
  const parts = [];
  for (const entry of preset.model || []) {
    if (!lab.models[entry.model]) {
      skipped.push(`${entry.label || entry.model}: ${entry.model} opens in the desktop lab only`);
      continue;
    }
    parts.push(`model=${entry.model}`);
    for (const [k, v] of Object.entries(entry.values || {})) {
      parts.push(`${k}=${Array.isArray(v) ? v.map(formatG).join(",") : typeof v === "boolean" ? Number(v) : v}`);
    }
  }
  parts.push(`light=${formatG(s.theta_i ?? 30)},${formatG(s.phi_i ?? 0)}`);
  if (s.exposure) parts.push(`exposure=${formatG(s.exposure)}`);
  if (s.polar_cos) parts.push("cos=1");
  if (s.polar_log) parts.push("log=1");
  const views = (preset.views || []).filter((v) => VIEWS[v]);
  if (views.length) parts.push(`views=${views.join(",")}`);
  const desktop = { phi_d: "phid", shape: "shape", mode: "mode", yaw: "yaw", pitch: "pitch", lobe_yaw: "lyaw",
    lobe_pitch: "lpitch", lobe_zoom: "lzoom", sh_order: "sh" };
  for (const [name, key] of Object.entries(desktop)) if (name in s) parts.push(`${key}=${s[name]}`);
  if (typeof s.ambient === "number" && s.ambient > 0) parts.push(`ambient=${formatG(s.ambient)}`);
  if (lab.size !== 384) parts.push(`size=${lab.size}`);
  if (lab.embed) parts.push("embed=1");
  return parts.join("&");
}

function applyPreset(index) {
  const preset = lab.presets[index];
  if (!preset) return;
  const skipped = [];
  const hash = presetHash(preset, skipped);
  const notes = $("#preset-notes");
  notes.textContent = `${preset.title || preset.file}${preset.notes ? ": " + preset.notes : ""}`;
  notes.hidden = false;
  applyHash(hash, skipped);
}

/** Shows the state of an address (typed into the address bar, a link or a preset). */
function applyHash(hash = location.hash.slice(1), extraNotes = []) {
  if (`#${hash}` !== location.hash) history.replaceState(null, "", `#${hash}`);
  lab.notes = [];
  const panels = readHash();
  lab.notes.push(...extraNotes);
  if (!panels.length) panels.push({ name: defaultModel(), values: {} });
  while (lab.panels.length) lab.panels.pop().destroy();
  addPanels(panels);
  showNotes();
  showToolbar();
  buildLights();
  fitEmbed();
  if (pending) cancelAnimationFrame(pending);
  pending = 0;
  renderNow();
  writeHash();
}

/** Every parameter back to its default, one white light, no ambient; the models stay. */
function reset() {
  defaultSettings();
  for (const panel of lab.panels) panel.setModel(panel.name);
  $("#preset").value = "";
  $("#preset-notes").hidden = true;
  showToolbar();
  buildLights();
  renderNow();
  writeHash();
}

// -- loading --------------------------------------------------------------------------------
async function fetchText(path) {
  const response = await fetch(path);
  if (!response.ok) throw new Error(`cannot load ${path} (HTTP ${response.status})`);
  return response.text();
}

function addModelText(label, code, expectedName = null) {
  const name = expectedName || label.split("/").pop().replace(/\.glsl$/, "");
  return putModel(lab, name, () => parseModel(code, label, expectedName));
}

async function load() {
  const manifest = JSON.parse(await fetchText("manifest.json"));
  Object.assign(C, manifest.constants);
  lab.presets = manifest.presets || [];
  lab.environments = manifest.environments; // the IBL view's maps: names and size
  lab.exerciseList = manifest.exercises || [];
  lab.measuredCode = manifest.measured_model; // lab/measured/measured.glsl
  // The texts come with the manifest (one request); a manifest without them, file by file.
  const sources = manifest.sources || {};
  const texts = await Promise.all(manifest.files.map((f) => sources[f] ?? fetchText(`shaders/${f}`)));
  manifest.files.forEach((f, i) => (lab.files[f] = texts[i]));
  // The library's headers come parsed (lab/models.py, checked against header.js by
  // tests/test_web_mirrors.py): the page parses only the files a user opens or edits.
  for (const name of manifest.models) {
    const path = `shaders/brdfs/${name}.glsl`;
    const header = manifest.library[name];
    if (header.error) lab.modelErrors[name] = header.error;
    else lab.models[name] = { ...header, path, code: lab.files[`brdfs/${name}.glsl`] };
    if (!lab.order.includes(name)) lab.order.push(name);
  }
}

// Keys a presenter's clicker or keyboard sends to move between slides.
const SLIDE_KEYS = { PageDown: "next", PageUp: "prev", ArrowRight: "next", ArrowLeft: "prev",
  " ": "next" };

/** Embedded in a slide, the frame keeps the keyboard focus after a click on a control: pass
 * the slide keys on to the deck, unless a text box or slider needs the key itself. */
function forwardSlideKeys() {
  addEventListener("keydown", (e) => {
    const step = SLIDE_KEYS[e.key];
    if (!step || e.altKey || e.ctrlKey || e.metaKey || window.parent === window) return;
    const target = e.target;
    const typing = target instanceof HTMLInputElement && target.type === "text";
    const slider = target instanceof HTMLInputElement && target.type === "range";
    const owned = typing || target instanceof HTMLSelectElement || target instanceof HTMLTextAreaElement ||
      (slider && e.key.startsWith("Arrow")) || (e.key === " " && target instanceof HTMLButtonElement);
    if (owned) return;
    e.preventDefault();
    window.parent.postMessage({ brdfLab: "slide", step }, "*");
  });
}

const showExposure = () => {
  $("#exposure-text").textContent = `×${formatG(round(Math.pow(2, lab.exposure)))}`;
};

/** The page-wide controls show the state (after an address or a preset changed it). */
function showToolbar() {
  showAmbient();
  $("#exposure").value = lab.exposure;
  showExposure();
  $("#cos-weighted").checked = lab.cosWeighted;
  $("#polar-log").checked = lab.polarLog;
  for (const [id, field] of [["phi-o", "phiO"], ["phi-d", "phiD"]]) {
    $(`#${id}`).value = lab[field];
    $(`#${id}-text`).textContent = `${formatG(lab[field])}°`;
  }
  $("#shape").value = lab.shape;
  $("#mode").value = lab.mode;
  document.querySelectorAll("#view-choice input").forEach((box) => (box.checked = lab.views.includes(box.value)));
  for (const name of Object.keys(VIEWS)) document.body.classList.toggle(`with-${name}`, lab.views.includes(name));
  lab.panels.forEach((panel) => panel.syncViews());
}

function showNotes() {
  $("#notes").textContent = lab.notes.join("\n");
  $("#notes").hidden = !lab.notes.length;
}

const defaultModel = () => (lab.order.includes("phong") ? "phong" : lab.order[0]);

/** Help on tap: a label's meaning (its title) in a box at the bottom of the screen, for
 * phones and tablets, which show no tooltips. */
function showTip(text) {
  $("#tip-text").textContent = text;
  $("#tip").hidden = !text;
}

function buildPage() {
  document.body.classList.toggle("embed", lab.embed);
  if (lab.embed) forwardSlideKeys();
  $("#add-light").addEventListener("click", () => addLight());
  $("#ambient").addEventListener("input", (e) => {
    const level = Number(e.target.value);
    lab.ambient = [level, level, level];
    showAmbient();
    scheduleRender();
  });
  $("#exposure").addEventListener("input", (e) => {
    lab.exposure = Number(e.target.value);
    showExposure();
    scheduleRender();
  });
  addEventListener("resize", () => {
    fitEmbed();
    scheduleRender();
  });
  $("#cos-weighted").addEventListener("change", (e) => {
    lab.cosWeighted = e.target.checked;
    scheduleRender();
  });
  $("#add-model").addEventListener("click", () => {
    addPanel(lab.panels[lab.panels.length - 1]?.name || lab.order[0]);
    scheduleRender();
  });
  $("#forget-files").addEventListener("click", forgetFiles);
  $("#open-file").addEventListener("change", async (e) => {
    for (const file of e.target.files) await openFile(file);
    e.target.value = ""; // the same file again (fixed on disk) must fire another change
    showNotes();
    scheduleRender();
  });
  $("#view-choice").append(...Object.entries(VIEW_TITLES).map(([name, title]) => {
    const box = el("input", { type: "checkbox", value: name });
    box.addEventListener("change", () => {
      lab.views = Object.keys(VIEWS).filter((n) => (n === name ? box.checked : lab.views.includes(n)));
      showToolbar();
      scheduleRender();
    });
    return el("label", {}, box, ` ${title}`);
  }));
  $("#shape").append(...SHAPES.map((text, i) => el("option", { value: i }, text)));
  $("#mode").append(...MODES.map((text, i) => el("option", { value: i }, `${i + 1}. ${text}`)));
  const setting = (id, field, parse = Number) => $(`#${id}`).addEventListener("input", (e) => {
    lab[field] = parse(e.target);
    showToolbar();
    scheduleRender();
  });
  setting("polar-log", "polarLog", (box) => box.checked);
  setting("phi-o", "phiO", (input) => Number(input.value));
  setting("phi-d", "phiD", (input) => Number(input.value));
  setting("shape", "shape", (input) => Number(input.value));
  setting("mode", "mode", (input) => Number(input.value));
  $("#overlay").prepend(el("header", {}, "all models on one scale"));
  $("#overlay .view").append(el("button", { type: "button", class: "png", title: "save the overlaid polar plot as a PNG image",
    onclick: () => savePng($("#overlay canvas"), "polar_all.png") }, "PNG"));
  $("#exercise-pick").append(...lab.exerciseList.map((e) => el("option", { value: e.name }, e.title)));
  $("#exercise-pick").addEventListener("change", (e) => e.target.value && openExercise(e.target.value));
  $("#preset").append(...lab.presets.map((p, i) => el("option", { value: i }, p.title || p.file)));
  $("#preset").addEventListener("change", (e) => e.target.value !== "" && applyPreset(Number(e.target.value)));
  $("#reset").addEventListener("click", reset);
  $("#tip button").addEventListener("click", () => showTip(""));
  // A tap (or click) on a label's words shows its meaning; a tap on its slider does not.
  document.addEventListener("click", (e) => {
    const label = e.target.closest?.("label[title], .param[title], .light-name");
    if (!label || e.target.closest("input, select, button")) return;
    const text = label.title || label.closest("[title]")?.title || "";
    if (text) showTip(text);
  });
  addEventListener("hashchange", () => applyHash());
}

/** Opens a file the student chose and keeps it in this browser for the next visit. Panels
 * of its name show the new version (none: one is added); the edits of an earlier version
 * are dropped, and an open editor on it shows the file. */
async function openFile(file) {
  const name = await openModelFile(file, lab);
  originals[name] = lab.models[name]?.text ?? null;
  keepDraft(name, null);
  if (await keepFile(name, file)) keep(name, file.name);
  lab.panels.forEach((p) => p.fillPicker());
  const showing = lab.panels.filter((p) => p.name === name);
  for (const panel of showing) panel.setModel(name);
  if (!showing.length) addPanel(name);
  if (editor?.panel?.name === name && !editor.root.hidden) await openEditor(editor.panel);
  if (storeProblem && !lab.notes.includes(storeProblem)) lab.notes.push(storeProblem);
  return name;
}

/** The files opened in this browser on earlier visits (keptFiles()), before the address is
 * read. */
async function restoreFiles(keptList) {
  for (const { name, file } of keptList) {
    const opened = await openModelFile(file, lab);
    originals[opened] = lab.models[opened]?.text ?? null;
    if (opened !== name) lab.notes.push(`${file.name}: kept as ${name}, now opens as ${opened}`);
    keep(name, file.name);
  }
}

// The files kept in this browser: model name -> file name ("forget files" drops them).
const kept = new Map();

/** Records a kept file; one that replaces a library model says so (until forgotten). */
function keep(name, fileName) {
  kept.set(name, fileName);
  if (`brdfs/${name}.glsl` in lab.files) {
    lab.notes.push(`${name}: your ${fileName} (kept in this browser) is shown instead of the library's ${name}; ` +
      `"forget files" brings the library's back`);
  }
  showForget();
}

function showForget() {
  const button = $("#forget-files");
  button.hidden = !kept.size;
  button.title = `forget the files this browser keeps for the page (${[...kept.values()].join(", ")}) and ` +
    "the edits made to them, and reload";
}

/** Drops every kept file and its edits, and starts the page again without them. */
async function forgetFiles() {
  for (const name of kept.keys()) {
    await forgetFile(name);
    keepDraft(name, null);
  }
  location.reload();
}

/** The editor texts of earlier visits, shown in place of the files they edit. A text that
 * does not compile (any more) leaves the file's version on show; the editor brings it back. */
function restoreDrafts() {
  const panel = lab.panels.find((p) => p.gl);
  for (const name of draftNames()) {
    if (!lab.models[name] || lab.exerciseList.some((e) => e.name === name)) continue;
    const text = draft(name);
    if (text === originalText(name)) {
      keepDraft(name, null);
      continue;
    }
    try {
      const model = modelOfText(name, text);
      if (panel) tryCompile(panel, model);
      lab.models[name] = model;
      for (const p of lab.panels.filter((q) => q.name === name)) p.setModel(name, p.values);
      if (lab.panels.some((p) => p.name === name)) {
        lab.notes.push(`${name}: your edited version (kept in this browser) is shown; "edit" then "reset" goes back to the original`);
      }
    } catch (err) {
      if (!(err instanceof ModelError || err instanceof CompileFailure)) throw err;
      if (lab.panels.some((p) => p.name === name)) lab.notes.push(`${name}: your edited version (kept in this browser) has an error, so the original is shown; ` +
        `"edit" opens your version (${err.message.split("\n")[0]})`);
    }
  }
}

/** Renders every panel now and waits until the GPU is done; returns milliseconds. */
function renderNow() {
  const start = performance.now();
  renderAll();
  for (const panel of lab.panels) panel.gl?.finish();
  return performance.now() - start;
}

async function main() {
  // The kept files are looked up while the manifest loads.
  const [, keptList] = await Promise.all([load(), embedded() ? [] : keptFiles()]);
  await restoreFiles(keptList);
  const panels = readHash();
  buildPage();
  showToolbar();
  if (!panels.length) panels.push({ name: defaultModel(), values: {} });
  addPanels(panels);
  if (!embedded()) restoreDrafts();
  if (storeProblem) lab.notes.push(storeProblem);
  showNotes();
  buildLights();
  fitEmbed();
  if (pending) cancelAnimationFrame(pending);
  pending = 0;
  // Progressive: every view draws at once, the costly ones coarse (as while a slider moves);
  // their full quality follows in the next frame, once this one is on screen.
  lab.fast = lab.views.length > 0;
  renderNow();
  lab.firstRenderMs = performance.now(); // since navigation start
  if (lab.embed) {
    fitEmbed(); // again, now that every view has drawn once
    renderNow();
  }
  writeHash();
  if (!lab.fast) lab.fullRenderMs = lab.firstRenderMs;
  else {
    requestAnimationFrame(() => setTimeout(() => {
      settleNow();
      lab.fullRenderMs = performance.now();
    }));
  }
}

const toBase64 = (floats) => {
  const bytes = new Uint8Array(floats.buffer);
  let text = "";
  for (let i = 0; i < bytes.length; i += 0x8000) text += String.fromCharCode(...bytes.subarray(i, i + 0x8000));
  return btoa(text);
};

// For tests, slides and benchmarks.
window.brdfLab = {
  ready: main(),
  state: lab,
  panel: (i = 0) => lab.panels[i],
  renderNow,
  setLight: (theta, phi, index = 0) => {
    setLight(theta, phi, index);
    return renderNow();
  },
  /** Replaces the lights: [{theta, phi, rgb}], and the ambient radiance [r, g, b]. */
  setLights(lights, ambient = [0, 0, 0]) {
    lab.lights = lights.map((l) => ({ theta: l.theta, phi: l.phi, rgb: l.rgb || [1, 1, 1] }));
    lab.ambient = ambient;
    showAmbient();
    lab.active = 0;
    buildLights();
    fitEmbed();
    return renderNow();
  },
  addLight: () => {
    addLight();
    return renderNow();
  },
  /** Where the page's controls are (for layout tests): every range input's box. */
  sliderBoxes: () => [...document.querySelectorAll("input[type=range]")].map((s) => {
    const r = s.getBoundingClientRect();
    return { left: r.left, top: r.top, right: r.right, bottom: r.bottom };
  }),
  setModel(i, name, values = {}) {
    lab.panels[i].setModel(name, values);
    return renderNow();
  },
  values: (i = 0) => ({ ...lab.panels[i].values }),
  errors: (i = 0) => lab.panels[i].error,
  /** The loop guard's warning on panel i ('' when no loop was stopped). */
  loopWarning: (i = 0) => (lab.panels[i].loopBox.hidden ? "" : lab.panels[i].loopBox.textContent),
  notes: () => lab.notes.slice(),
  applyPreset: (i) => applyPreset(i),
  /** Opens the editor on panel i; returns its API (text, setText, errors, check). */
  async edit(i = 0) {
    await openEditor(lab.panels[i]);
    return true;
  },
  get editor() {
    return editor;
  },
  /** Opens an exercise (folder name) in practice mode; resolves when its checks ran. */
  openExercise,
  get exercises() {
    return exercises;
  },
  presetHash: (preset) => {
    const skipped = [];
    return { hash: presetHash(preset, skipped), skipped };
  },
  reset,
  moveSlider(i, name, position) {
    const value = lab.panels[i].moveSlider(name, position);
    renderNow();
    writeHash();
    return value;
  },
  /** The float sphere of panel i, base64 float32 RGBA, row 0 at the top. */
  readSphere(i = 0) {
    settleNow();
    const { width, height, data } = lab.panels[i].readSphere();
    return { width, height, data: toBase64(data) };
  },
  /** Polar probe values of panel i (181 x RGBA, theta_o = -90..90). */
  readLobe: (i = 0) => Array.from(lab.panels[i].lobe || []),
  /** Another view of panel i: images as {width, height, data} (base64 float32 RGBA, row 0
   * at the top); the albedo as {thetas, rgb, gain}. */
  readView(i, name) {
    settleNow();
    const view = lab.panels[i].extra[name];
    if (view.stale) view.render(); // off screen: drawn for the reader
    view.stale = false;
    const out = view.read();
    return out.data ? { ...out, data: toBase64(out.data) } : out;
  },
  /** Shows these views (keys of VIEWS) and renders. */
  setViews(names) {
    lab.views = Object.keys(VIEWS).filter((n) => names.includes(n));
    showToolbar();
    writeHash();
    return renderNow();
  },
  /** Sets page settings ({phiD, phiO, shape, mode, yaw, pitch, polarLog}) and renders. */
  setSettings(values) {
    Object.assign(lab, values);
    showToolbar();
    writeHash();
    return renderNow();
  },
  overlay: () => lab.overlayGeometry,
  /** The delta spike of panel i: its RGB reflectance (null for other models) and its
   * drawn length as a fraction of the polar plot's radius. */
  spike: (i = 0) => {
    const panel = lab.panels[i];
    const g = panel.polarGeometry;
    return { rgb: panel.spike, length: g ? g.spikeLength / g.radius : 0 };
  },
  loadModel(label, code) {
    const name = addModelText(label, code);
    lab.panels.forEach((p) => p.fillPicker());
    const panel = addPanel(name);
    renderNow();
    return panel ? panel.error : lab.modelErrors[name];
  },
  /** Frame times (ms) while a slider of panel i moves through `steps` positions. */
  sliderFrames(i, name, steps = 60) {
    const times = [];
    clearTimeout(settle);
    lab.fast = lab.views.length > 0;
    for (let k = 0; k < steps; k++) {
      const start = performance.now();
      lab.panels[i].moveSlider(name, Math.round((SLIDER_STEPS * ((k * 37) % steps)) / steps));
      renderAll();
      lab.panels[i].gl.finish();
      times.push(performance.now() - start);
    }
    lab.fast = false;
    renderNow();
    return times;
  },
};

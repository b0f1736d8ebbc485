// A panel: one model with its parameter controls, its lit sphere and polar plot (drawn
// here, on the panel's WebGL2 context) and the page's other views, each made by its page
// module (views/NAME.js) on the same context. What the panel does not own (removing it,
// opening the editor, moving the light) it asks the page for with DOM events (ask()).
import { ModelError, defaults } from "./header.js";
import { direction, planeOfIncidence } from "./geometry.js";
import { assembleFragment, floatTexture, startProgram, vertexSource } from "./assemble.js";
import { showOnly } from "./deck.js";
import { $, el, setText, shortTitle, viewBox } from "./dom.js";
import { CompileFailure, DISPLAY_SHADER, compile, finishModelProgram, floatTarget, loopStop, loopWarning, setUniform } from "./glkit.js";
import { paramControl } from "./controls.js";
import { PALETTE } from "./state.js";

export const POLAR_STEPS = 181; // theta_o from -90 to 90 degrees in 1-degree steps
const EMBED_PLOT = 1.5; // embedded in a slide: the plot's width over the sphere's
const SPHERE_FAST_MIN = 384; // spheres this large draw at half resolution while a slider moves

/** Views off screen skip their (costly) renders; one that comes into sight and missed a
 * render draws then. Until the first report a view counts as visible. */
let seen = null;
function watchVisibility(view) {
  seen ??= new IntersectionObserver((entries) => {
    let missed = null;
    for (const entry of entries) {
      const shown = entry.target.labView;
      shown.offscreen = !entry.isIntersecting;
      if (entry.isIntersecting && shown.stale) missed = shown;
    }
    missed?.panel.lab.requestRender();
  });
  view.root.labView = view;
  seen.observe(view.root);
}

export class Panel {
  /** A panel of `lab` (state.js) showing model `name` with `values` (the rest defaults). */
  constructor(lab, name, values = {}) {
    this.lab = lab;
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
      this.lab.requestRender();
    } });
    this.closeButton = el("button", { class: "close", title: "remove this model", onclick: () => this.ask("panel-remove") }, "×");
    this.editButton = el("button", { type: "button", class: "edit", title: "edit this model's GLSL file in the page",
      onclick: () => this.ask("panel-edit") }, "edit");
    this.canvas = el("canvas", { class: "sphere", width: this.lab.size, height: this.lab.size });
    // Embedded, the plot is wider than the sphere: its labels are large (deck.js).
    const plotWidth = Math.round(this.lab.size * (this.lab.embed ? EMBED_PLOT : 1));
    this.polar = el("canvas", { class: "polar", width: plotWidth,
      height: Math.round(this.lab.embed ? plotWidth * 0.62 : this.lab.size / 2 + 28) });
    this.displaySize(this.lab.size);
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
    this.target = floatTarget(gl, this.lab.size, this.lab.size);
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

  /** Asks the page for something the panel does not own itself (page.js listens):
   * "panel-remove", "panel-edit" or "panel-light" ({theta, phi}). */
  ask(what, detail = {}) {
    this.root.dispatchEvent(new CustomEvent(what, { bubbles: true, detail: { panel: this, ...detail } }));
  }

  /** CSS size of the sphere (and the polar plot's width); the render keeps lab.size. */
  displaySize(px) {
    // Never wider than the panel (phones): the canvases' height follows their aspect.
    this.canvas.style.width = `${px}px`;
    this.polar.style.width = `${px}px`;
    if (this.lab.embed) {
      // Embedded: exact heights, so that fitting the frame converges (the grid of a slide).
      this.canvas.style.height = `${px}px`;
      this.polar.style.width = `${px * EMBED_PLOT}px`;
      this.polar.style.height = `${(px * EMBED_PLOT * this.polar.height) / this.polar.width}px`;
    }
    for (const view of Object.values(this.extra)) view.canvas.style.width = `${px}px`;
  }

  get color() {
    return PALETTE[Math.max(this.lab.panels.indexOf(this), 0) % PALETTE.length];
  }

  /** Makes the panel show the page's chosen views (lab.views): each made by its page
   * module's create(panel). */
  syncViews() {
    for (const name of Object.keys(this.extra)) {
      if (!this.lab.views.includes(name)) delete this.extra[name];
    }
    for (const name of this.lab.views) {
      // Until the page's first picture, the views wait (lab.js): their canvases and
      // programs cost nothing before the spheres and polar plots are on screen.
      if (!this.extra[name] && this.gl && !this.lab.coreOnly) {
        this.extra[name] = this.lab.modules[name].create(this);
      }
    }
    // Laid out cheapest first (a page module's queue): the views nearest the top of the
    // window, the ones a first screen shows, are those that draw fastest.
    const queue = (name) => this.lab.modules[name].queue ?? 100;
    const shown = this.lab.views.filter((n) => this.extra[n]).sort((a, b) => queue(a) - queue(b));
    this.viewsBox.replaceChildren(...shown.map((n) => this.extra[n].root));
    this.displaySize(parseFloat(this.canvas.style.width) || this.lab.size);
    // A new view knows at once whether it is in sight (the observer reports a frame later).
    for (const view of Object.values(this.extra)) {
      if (view.root.labView) continue;
      if (this.root.isConnected) {
        const r = view.root.getBoundingClientRect();
        view.offscreen = r.bottom <= 0 || r.right <= 0 || r.top >= innerHeight || r.left >= innerWidth;
      }
      watchVisibility(view);
    }
  }

  fillPicker() {
    this.picker.replaceChildren(...this.lab.order.map((n) => el("option", { value: n, title: this.lab.models[n]?.title || n },
      shortTitle(this.lab.models[n], n))));
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
    this.model = this.lab.models[name];
    this.programs.clear(); // compiled for the previous model
    this.controls.replaceChildren();
    this.formula.replaceChildren();
    if (!this.model) {
      this.showError(this.lab.modelErrors[name] || `unknown model ${name}`);
      return;
    }
    this.values = { ...defaults(this.model), ...values };
    this.formula.append(el("strong", {}, this.model.title || name),
      ...this.model.formula.map((f) => el("code", {}, f)));
    for (const p of this.model.params) this.controls.append(paramControl(p, this.values, (value) => this.setValue(p, value), this.lab.constants.SLIDER_STEPS));
    if (this.lab.embed) showOnly(this.lab.show);
  }

  /** A parameter's new value from its control: an enum is a constant of the program. */
  setValue(p, value) {
    this.values[p.name] = value;
    if (p.kind === "enum") this.programs.clear(); // another constant: compile again
    this.lab.requestRender();
  }

  /** Moves the slider of `name` to a position (0..SLIDER_STEPS) as a user would. */
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
    const text = stop ? loopWarning(this.lab.constants, this.model, stop, ` at θo = ${stop.x - 90}° of the polar plot`) : "";
    setText(this.loopBox, text);
    this.loopBox.hidden = !text;
  }

  showError(text) {
    this.error = text;
    setText(this.errorBox, text);
    this.errorBox.hidden = !text;
  }

  dragLight(event) {
    const rect = this.canvas.getBoundingClientRect();
    let x = ((event.clientX - rect.left) / rect.width) * 2 - 1;
    let y = 1 - ((event.clientY - rect.top) / rect.height) * 2;
    const r = Math.hypot(x, y);
    if (r > 1) [x, y] = [x / r, y / r];
    const z = Math.sqrt(Math.max(0, 1 - x * x - y * y));
    this.ask("panel-light", { theta: (Math.acos(z) * 180) / Math.PI, phi: (Math.atan2(y, x) * 180) / Math.PI });
  }

  /** The compiled program of `view`; `transform(source, model)` may edit the assembled
   * source first (the object view's spatially varying parameters). */
  program(view, preamble = null, transform = null, { start = false } = {}) {
    const enums = Object.fromEntries(this.model.params.filter((p) => p.kind === "enum").map((p) => [p.name, this.values[p.name]]));
    // The light count is a constant of the lit views, as on the desktop.
    if (preamble === null) preamble = view === "sphere" ? `const int LIGHT_COUNT = ${this.lab.lights.length};` : "";
    const key = `${view}|${preamble}|${JSON.stringify(enums)}`;
    if (!this.programs.has(key)) {
      // A .brdf file assembles by its own rules (explorer.js).
      const assemble = this.model.assemble ?? assembleFragment;
      const source = assemble(this.model, view, this.lab.files, { target: "300es", preamble, enums, constants: this.lab.constants });
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
      // processed last. Cheap programs queue first (a page module's `queue`), so that each
      // picture's JS overlaps the GPU's work on the views after it. The page shows the views in
      // lab.views' order.
      // The page's first picture is the spheres and polar plots alone (lab.coreOnly).
      const queue = (name) => this.lab.modules[name].queue ?? 100;
      const order = this.lab.coreOnly ? [] : [...this.lab.views].sort((a, b) => queue(a) - queue(b));
      const views = [];
      for (const name of order) {
        const view = this.extra[name];
        // Off screen a view waits: it draws when scrolled into sight (watchVisibility) or
        // when the page is idle (lab.js).
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

  /** Draws one view alone (one out of sight, while the page is idle). */
  renderView(view) {
    if (!this.gl || !this.model) return;
    try {
      if (!view.submit) view.render();
      else {
        view.submit();
        view.collect();
        view.process();
      }
      view.stale = false;
    } catch (err) {
      if (!(err instanceof CompileFailure || err instanceof ModelError)) throw err;
      view.stale = false; // the panel's next full render names the error
    }
  }

  renderSphere(gl) {
    const compiled = this.program("sphere");
    const u = compiled.uniforms;
    gl.useProgram(compiled.program);
    gl.bindVertexArray(this.vao);
    this.setParams(gl, compiled);
    const dirs = new Float32Array(3 * this.lab.constants.MAX_LIGHTS);
    const rgb = new Float32Array(3 * this.lab.constants.MAX_LIGHTS);
    this.lab.lights.forEach((light, i) => {
      dirs.set(direction(light.theta, light.phi), 3 * i);
      rgb.set(light.rgb, 3 * i);
    });
    // While the hand moves, half the resolution: a quarter of the cost at 512 px.
    const step = this.lab.fast && this.lab.size >= SPHERE_FAST_MIN ? 2 : 1;
    let target = this.target;
    if (step === 2) {
      const half = Math.ceil(this.lab.size / 2);
      this.coarseTarget ??= floatTarget(gl, half, half);
      target = this.coarseTarget;
    }
    this.sphereStep = step;
    gl.uniform2f(u.u_resolution, target.width, target.height);
    if (u.u_light_dir) gl.uniform3fv(u.u_light_dir, dirs);
    if (u.u_light_rgb) gl.uniform3fv(u.u_light_rgb, rgb);
    if (u.u_ambient) gl.uniform3fv(u.u_ambient, this.lab.ambient);
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
    gl.viewport(0, 0, this.lab.size, this.lab.size);
    gl.uniform1i(this.display.uniforms.u_image, 0);
    gl.uniform1f(this.display.uniforms.u_scale, Math.pow(2, this.lab.settings.exposure));
    gl.drawArrays(gl.TRIANGLES, 0, 3);
  }

  /** Queues the lobe in the plane of incidence (probe values, read back as floats). */
  submitPolar(gl) {
    const { theta, phi } = this.lab.light;
    const key = `${theta},${phi},${this.lab.settings.phi_o}`;
    const directions = (which) => () => {
      const Ld = direction(theta, phi);
      // The plane of the plot: the plane of incidence turned by phi_o about the normal.
      const plane = planeOfIncidence(phi + this.lab.settings.phi_o).V;
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
    const { theta, phi } = this.lab.light;
    this.spike = this.model.delta && this.lab.settings.phi_o === 0 ? this.deltaReflectance(gl, theta, phi) : null;
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

// The 3D lobe: f_r over the hemisphere as a surface drawn by the model's own BRDF in the
// vertex stage, from the desktop's templates (shaders/views/lobe_mesh*.glsl, as
// lab/views/lobe3d.py draws them); every panel on one shared scale; drag (or touch) to
// orbit, wheel to zoom. The marks (horizon, N, L, R, a delta's spike) are drawn on top.
import { ModelError, formatG } from "../header.js";
import { cssWidth, el, setText, viewBox } from "../dom.js";
import { direction } from "../geometry.js";
import { VERSION_LINES, assembleFragment, finishProgram, floatTexture, startProgram, translateLog } from "../assemble.js";

const TARGET = [0, 0, 0.3];
const DISTANCE = 5;
const SCALE = 0.85;
const BACKGROUND = [40 / 255, 40 / 255, 44 / 255]; // the desktop lab's
const MARKS = { N: [0.78, 0.78, 0.78], L: [1.0, 0.82, 0.0], R: [0.47, 0.78, 1.0] };

/** (θo, φo) of every vertex of a rows x cols grid (flat, vertex i * cols + j), as lobe_grid
 * in shaders/views/lobe_mesh_common.glsl places them (in float, as the GPU does): rows of
 * θo from the normal to 89.5°, columns of φo around the circle, both refined quadratically
 * toward the mirror direction of the light at (θi, φi) (radians). */
export function lobeGridAngles([rows, cols], thetaI, phiI) {
  const f = Math.fround;
  const warp = (k, kc, n, center, lo, hi) => {
    if (k < kc) {
      const s = f(f(kc - k) / kc);
      return f(center - f(f(f(center - lo) * s) * s));
    }
    if (k > kc) {
      const s = f(f(k - kc) / (n - 1 - kc));
      return f(center + f(f(f(hi - center) * s) * s));
    }
    return center;
  };
  const pi = f(3.14159265358979); // LOBE_PI
  const top = f((89.5 * Math.PI) / 180);
  const theta = f(Math.min(Math.max(f(thetaI), 0), f(0.5 * pi)));
  const kc = Math.floor(f(f((rows - 1) * f(Math.min(f(theta / top), 1))) + 0.5));
  const phiM = f(f(phiI) + pi);
  const jc = Math.trunc((cols - 1) / 2);
  const out = new Float64Array(2 * rows * cols);
  for (let i = 0; i < rows; i++) {
    const t = warp(i, kc, rows, Math.min(theta, top), 0, top);
    for (let j = 0; j < cols; j++) {
      out[2 * (i * cols + j)] = t;
      out[2 * (i * cols + j) + 1] = warp(j, jc, cols, phiM, f(phiM - pi), f(phiM + pi));
    }
  }
  return out;
}

/** Pixel position (x right, y down) of a world point: LobeCamera.project. */
export function project(camera, p, width, height) {
  const [c, s] = [Math.cos(camera.yaw), Math.sin(camera.yaw)];
  const q = [c * p[0] - s * p[1] - TARGET[0], s * p[0] + c * p[1] - TARGET[1], p[2] - TARGET[2]];
  const [cp, sp] = [Math.cos(camera.pitch), Math.sin(camera.pitch)];
  const view = [q[0], q[1] * sp + q[2] * cp, q[2] * sp - q[1] * cp];
  const w = (DISTANCE - view[2]) / DISTANCE;
  const short = Math.min(width, height);
  const x = (view[0] * SCALE * camera.zoom * short) / width / w;
  const y = (view[1] * SCALE * camera.zoom * short) / height / w;
  return [((x + 1) / 2) * width, ((1 - y) / 2) * height];
}

const hexRgb = (hex) => [1, 3, 5].map((i) => parseInt(hex.slice(i, i + 2), 16) / 255);
const css = (rgb, alpha = 1) => `rgba(${rgb.map((c) => Math.round(255 * c)).join(",")},${alpha})`;

/** The lobe program queued by startProgram(), linked (throws ModelError where it does not). */
function finishLobeProgram(pending, source) {
  const logs = {};
  const compiled = finishProgram(pending, logs);
  if (compiled) return compiled;
  const errors = translateLog(logs.vertex, source);
  const text = errors.length ? errors.map((e) => `${e.file}:${e.line}: ${e.message}`).join("\n") : logs.vertex + logs.fragment + logs.link;
  throw new ModelError(`the shader does not compile in the 3D lobe (its BRDF runs in the vertex stage):\n${text}`);
}

/** Another panel's peak; [0, 0] where its model cannot be drawn (its panel says why). */
function otherPeak(panel) {
  if (!panel.model || !panel.gl || !panel.extra.lobe3d) return [0, 0];
  try {
    return panel.extra.lobe3d.peak();
  } catch {
    return [0, 0];
  }
}

export class LobeView {
  constructor(panel) {
    this.panel = panel;
    this.lab = panel.lab;
    const lab = this.lab;
    // Vertices in θo and φo, full and while a slider moves (lab/views/lobe3d.py's, sent
    // in the manifest).
    const { grid, fast_grid: fastGrid } = lab.viewData("lobe3d");
    this.grid = grid;
    this.fastGrid = fastGrid;
    this.canvas = el("canvas", { class: "lobe3d", width: lab.size, height: Math.round(lab.size * 0.75) });
    this.root = viewBox(this.canvas, "3D lobe", () => `${panel.name}_lobe3d.png`);
    this.wire = el("input", { type: "checkbox" });
    this.wire.addEventListener("change", () => this.lab.requestRender());
    this.note = el("div", { class: "view-note" });
    this.root.append(el("label", { class: "group", title: "grid lines only: the surface shows through" }, this.wire, " wire"),
      this.note);
    // One finger or the mouse orbits; two fingers pinch to zoom.
    const pointers = new Map();
    const spread = () => {
      const [a, b] = [...pointers.values()];
      return Math.hypot(a[0] - b[0], a[1] - b[1]);
    };
    const zoom = (factor) => {
      lab.set("lobe_zoom", lab.settings.lobe_zoom * factor);
      this.lab.requestRender();
    };
    this.canvas.addEventListener("pointerdown", (e) => {
      this.canvas.setPointerCapture(e.pointerId);
      pointers.set(e.pointerId, [e.clientX, e.clientY]);
    });
    this.canvas.addEventListener("pointermove", (e) => {
      const last = pointers.get(e.pointerId);
      if (!last || !e.buttons) return;
      if (pointers.size === 2) {
        const before = spread();
        pointers.set(e.pointerId, [e.clientX, e.clientY]);
        if (before > 0) zoom(spread() / before);
        return;
      }
      const rect = this.canvas.getBoundingClientRect();
      lab.set("lobe_yaw", lab.settings.lobe_yaw + ((e.clientX - last[0]) / rect.width) * Math.PI);
      lab.set("lobe_pitch", lab.settings.lobe_pitch + ((e.clientY - last[1]) / rect.height) * Math.PI);
      pointers.set(e.pointerId, [e.clientX, e.clientY]);
      this.lab.requestRender();
    });
    for (const end of ["pointerup", "pointercancel"]) this.canvas.addEventListener(end, (e) => pointers.delete(e.pointerId));
    this.canvas.addEventListener("wheel", (e) => {
      e.preventDefault();
      zoom(Math.exp(-0.0015 * e.deltaY));
    }, { passive: false });
  }

  /** [largest value shown, delta spike] of this panel's lobe on the full grid (the scale
   * does not jump while the coarse grid draws), cached until its inputs change. The values
   * at the vertices come from the probe program (the polar plot's, already compiled: one
   * program less to compile at the first draw) at the directions of lobeGridAngles. */
  peak() {
    return this.peakCache?.model === this.panel.model && this.peakCache.key === this.peakKey()
      ? this.peakCache.value : this.readPeak(this.queuePeak());
  }

  peakKey() {
    const lab = this.lab;
    const light = lab.lights[0];
    return JSON.stringify([this.panel.values, light.theta, light.phi, lab.settings.polar_cos]);
  }

  /** Queues the probe of the full grid for peak() (null while the cached peak holds). */
  queuePeak() {
    const key = this.peakKey();
    if (this.peakCache?.model === this.panel.model && this.peakCache.key === key) return null;
    const light = this.lab.lights[0];
    const [rows, cols] = this.grid;
    const n = rows * cols;
    // The grid's directions change with the light only (not while a parameter moves).
    const lightKey = `${light.theta},${light.phi}`;
    if (this.directions?.key !== lightKey) {
      const thetaI = Math.fround((light.theta * Math.PI) / 180);
      const phiI = Math.fround((light.phi * Math.PI) / 180);
      const angles = lobeGridAngles(this.grid, thetaI, phiI);
      const L = new Float32Array(4 * n);
      const V = new Float32Array(4 * n);
      const Ld = [Math.sin(thetaI) * Math.cos(phiI), Math.sin(thetaI) * Math.sin(phiI), Math.cos(thetaI)];
      for (let k = 0; k < n; k++) {
        const [theta, phi] = [angles[2 * k], angles[2 * k + 1]];
        L.set(Ld, 4 * k);
        V.set([Math.sin(theta) * Math.cos(phi), Math.sin(theta) * Math.sin(phi), Math.cos(theta)], 4 * k);
      }
      this.directions = { key: lightKey, angles, L, V };
    }
    const { L, V } = this.directions;
    const textures = [this.panel.heldTexture("lobe L", lightKey, cols, rows, () => L),
      this.panel.heldTexture("lobe V", lightKey, cols, rows, () => V)];
    return { key, pass: this.panel.draw("probe", cols, rows, { u_L: 0, u_V: 1 }, { textures, tag: "lobe peak" }) };
  }

  /** [largest value, delta spike] from the probe queued by queuePeak(), cached. */
  readPeak(queued) {
    if (!queued) return this.peakCache.value;
    const lab = this.lab;
    const C = lab.constants;
    const light = lab.lights[0];
    const f = this.panel.collect(queued.pass);
    const { angles, V } = this.directions;
    const n = this.grid[0] * this.grid[1];
    // As lobe_mesh_peak.glsl: the luminance (times cos θo when asked), and the largest
    // value away from grazing, where some models diverge.
    const values = new Float32Array(n);
    const grazing = (C.GRAZING_DEG * Math.PI) / 180;
    let peak = 0;
    for (let k = 0; k < n; k++) {
      let value = C.LUMA[0] * f[4 * k] + C.LUMA[1] * f[4 * k + 1] + C.LUMA[2] * f[4 * k + 2];
      if (lab.settings.polar_cos) value *= Math.max(V[4 * k + 2], 0);
      values[k] = value;
      if (angles[2 * k] <= grazing && Number.isFinite(value)) peak = Math.max(peak, value);
    }
    let spike = 0;
    if (this.panel.model.delta) {
      const rgb = this.panel.deltaReflectance(this.panel.gl, light.theta, light.phi);
      spike = C.LUMA[0] * rgb[0] + C.LUMA[1] * rgb[1] + C.LUMA[2] * rgb[2];
      if (!Number.isFinite(spike)) spike = 0;
    }
    this.peakCache = { model: this.panel.model, key: queued.key, value: [peak, spike], values };
    return this.peakCache.value;
  }

  uniforms(grid) {
    const lab = this.lab;
    const light = lab.lights[0];
    return { u_grid: [grid[0], grid[1]], u_light_angles: [(light.theta * Math.PI) / 180, (light.phi * Math.PI) / 180],
      u_cos: lab.settings.polar_cos };
  }

  /** The model's lobe program: the assembled model + lobe_mesh.glsl as the vertex stage
   * (with `start`, only queued: see Panel.warmPrograms). */
  program({ start = false } = {}) {
    const { panel } = this;
    const lab = this.lab;
    const C = lab.constants;
    const enums = Object.fromEntries(panel.model.params.filter((p) => p.kind === "enum").map((p) => [p.name, panel.values[p.name]]));
    const key = `lobe_mesh vertex|${JSON.stringify(enums)}`;
    if (!panel.programs.has(key)) {
      const assemble = panel.model.assemble ?? assembleFragment;
      const source = assemble(panel.model, "lobe_mesh", lab.files, { target: "300es",
        preamble: lab.files["views/lobe_mesh_common.glsl"], enums, constants: C });
      const fragment = `${VERSION_LINES["300es"].join("\n")}\n${lab.files["views/lobe_mesh_shade.glsl"]}`;
      panel.programs.set(key, { pending: startProgram(panel.gl, source.text, fragment), source });
    }
    if (start) return null;
    const entry = panel.programs.get(key);
    if (entry.pending) {
      panel.programs.delete(key); // one that does not compile is tried again next time
      panel.programs.set(key, finishLobeProgram(entry.pending, entry.source));
    }
    return panel.programs.get(key);
  }

  warm() {
    this.program({ start: true });
  }

  /** Two triangles per grid cell (lab/views/lobe3d.py's _lobe_indices). */
  indices(gl, [rows, cols]) {
    const key = `${rows}x${cols}`;
    this.buffers ??= new Map();
    if (!this.buffers.has(key)) {
      const out = new Uint16Array((rows - 1) * (cols - 1) * 6);
      let k = 0;
      for (let i = 0; i < rows - 1; i++) {
        for (let j = 0; j < cols - 1; j++) {
          const v00 = i * cols + j;
          out.set([v00, v00 + cols, v00 + cols + 1, v00, v00 + cols + 1, v00 + 1], k);
          k += 6;
        }
      }
      const buffer = gl.createBuffer();
      gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, buffer);
      gl.bufferData(gl.ELEMENT_ARRAY_BUFFER, out, gl.STATIC_DRAW);
      this.buffers.set(key, { buffer, count: out.length });
    }
    return this.buffers.get(key);
  }

  target(gl, width, height) {
    this.fbos ??= new Map(); // by size: the full one and the coarse one (while the hand moves)
    const key = `${width}x${height}`;
    if (this.fbos.has(key)) return this.fbos.get(key);
    const texture = floatTexture(gl, width, height);
    const depth = gl.createRenderbuffer();
    gl.bindRenderbuffer(gl.RENDERBUFFER, depth);
    gl.renderbufferStorage(gl.RENDERBUFFER, gl.DEPTH_COMPONENT24, width, height);
    const fbo = gl.createFramebuffer();
    gl.bindFramebuffer(gl.FRAMEBUFFER, fbo);
    gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.TEXTURE_2D, texture, 0);
    gl.framebufferRenderbuffer(gl.FRAMEBUFFER, gl.DEPTH_ATTACHMENT, gl.RENDERBUFFER, depth);
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    this.fbos.set(key, { fbo, width, height });
    return this.fbos.get(key);
  }

  render() {
    this.submit();
    this.collect();
    this.process();
  }

  /** Queues the probe for this panel's peak (unless it is cached), and a first program's
   * draw on one pixel: SwiftShader compiles the program then, not after the scale is read. */
  submit() {
    this.queued = this.queuePeak();
    const compiled = this.program();
    if (this.drawn !== compiled) this.drawMesh(1, { pixel: true });
    this.drawn = compiled;
  }

  /** The scale (every panel's peak: small probes), then the mesh's draw, queued: a second
   * round, read back by process(). */
  collect() {
    const lab = this.lab;
    // One scale for every panel: the largest value (or spike) of all of them.
    const peaks = lab.panels.map((p) => (p === this.panel ? this.readPeak(this.queued) : otherPeak(p)));
    const shared = Math.max(...peaks.flat(), 0);
    this.scale = Number.isFinite(shared) && shared > 0 ? shared : 1e-12;
    this.spike = peaks[lab.panels.indexOf(this.panel)]?.[1] ?? 0;
    this.pass = this.drawMesh(this.scale);
    return "later";
  }

  /** Queues the lobe's mesh at `scale` (radius 1) into the float target; with `pixel`, on
   * one pixel only. */
  drawMesh(scale, { pixel = false } = {}) {
    const lab = this.lab;
    const gl = this.panel.gl;
    const grid = lab.fast ? this.fastGrid : this.grid;
    // While the hand moves, half the resolution (a quarter of the pixels to draw and read).
    const step = lab.fast ? 2 : 1;
    const width = Math.ceil(this.canvas.width / step);
    const height = Math.ceil(this.canvas.height / step);
    this.size = [width, height];
    const compiled = this.program();
    const target = this.target(gl, width, height);
    gl.bindFramebuffer(gl.FRAMEBUFFER, target.fbo);
    gl.viewport(0, 0, width, height);
    if (pixel) {
      gl.enable(gl.SCISSOR_TEST);
      gl.scissor(0, 0, 1, 1);
    }
    gl.clearColor(...BACKGROUND, 1);
    gl.clearDepth(1);
    gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
    gl.useProgram(compiled.program);
    gl.bindVertexArray(this.panel.vao);
    this.panel.setParams(gl, compiled);
    const short = Math.min(width, height);
    const u = compiled.uniforms;
    const set = {
      u_grid: () => gl.uniform2i(u.u_grid, grid[0], grid[1]),
      u_light_angles: () => gl.uniform2fv(u.u_light_angles, this.uniforms(grid).u_light_angles),
      u_yaw: () => gl.uniform1f(u.u_yaw, lab.settings.lobe_yaw),
      u_pitch: () => gl.uniform1f(u.u_pitch, lab.settings.lobe_pitch),
      u_zoom: () => gl.uniform1f(u.u_zoom, lab.settings.lobe_zoom),
      u_perspective: () => gl.uniform1i(u.u_perspective, 1),
      // Clip y flipped (as LobeCamera.uniforms): the first row read back is the top row.
      u_aspect: () => gl.uniform2f(u.u_aspect, short / width, -short / height),
      u_peak: () => gl.uniform1f(u.u_peak, scale),
      u_log: () => gl.uniform1i(u.u_log, lab.settings.polar_log ? 1 : 0),
      u_decades: () => gl.uniform1f(u.u_decades, this.lab.constants.PLOT_DECADES),
      u_cos: () => gl.uniform1i(u.u_cos, lab.settings.polar_cos ? 1 : 0),
      u_color: () => gl.uniform3fv(u.u_color, hexRgb(this.panel.color)),
      u_wire: () => gl.uniform1i(u.u_wire, this.wire.checked ? 1 : 0),
    };
    for (const [name, apply] of Object.entries(set)) if (u[name]) apply();
    const blend = gl.getExtension("EXT_float_blend"); // blending into float targets
    gl.enable(gl.DEPTH_TEST);
    gl.depthFunc(gl.LESS);
    if (blend) {
      gl.enable(gl.BLEND);
      gl.blendFuncSeparate(gl.SRC_ALPHA, gl.ONE_MINUS_SRC_ALPHA, gl.ONE, gl.ONE_MINUS_SRC_ALPHA);
    }
    gl.frontFace(gl.CW); // the camera draws upside down
    const { buffer, count } = this.indices(gl, grid);
    gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, buffer);
    gl.drawElements(gl.TRIANGLES, count, gl.UNSIGNED_SHORT, 0);
    gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, null);
    gl.disable(gl.DEPTH_TEST);
    gl.disable(gl.BLEND);
    gl.disable(gl.SCISSOR_TEST);
    gl.frontFace(gl.CCW);
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    gl.bindVertexArray(this.panel.vao);
    gl.flush(); // to the GPU now: it works while the page's JS goes on
    return target;
  }

  process() {
    const gl = this.panel.gl;
    const { fbo, width, height } = this.pass;
    gl.bindFramebuffer(gl.FRAMEBUFFER, fbo);
    this.data = new Float32Array(width * height * 4);
    gl.readPixels(0, 0, width, height, gl.RGBA, gl.FLOAT, this.data);
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    this.draw();
  }

  /** The picture (display values, not radiance: no exposure or sRGB) and the marks. */
  draw() {
    const lab = this.lab;
    const { width, height } = this.canvas;
    const image = new ImageData(...this.size);
    // A clamped array clamps to 0..255 and rounds (NaN gives 0) by itself.
    const pixels = image.data;
    const values = this.data;
    for (let k = 0; k < values.length; k++) pixels[k] = 255 * values[k];
    const ctx = this.canvas.getContext("2d");
    if (this.size[0] === width && this.size[1] === height) ctx.putImageData(image, 0, 0);
    else {
      const scratch = new OffscreenCanvas(...this.size);
      scratch.getContext("2d").putImageData(image, 0, 0);
      ctx.imageSmoothingEnabled = true; // a smooth draft, not blocks
      ctx.drawImage(scratch, 0, 0, width, height);
    }
    const camera = { yaw: lab.settings.lobe_yaw, pitch: lab.settings.lobe_pitch, zoom: lab.settings.lobe_zoom };
    const at = (p) => project(camera, p, width, height);
    const line = (a, b, rgb, widthPx, dash = []) => {
      ctx.strokeStyle = css(rgb);
      ctx.lineWidth = widthPx;
      ctx.setLineDash(dash);
      ctx.beginPath();
      ctx.moveTo(...at(a));
      ctx.lineTo(...at(b));
      ctx.stroke();
      ctx.setLineDash([]);
    };
    ctx.strokeStyle = "rgba(140,140,153,0.9)";
    ctx.lineWidth = 1.3;
    ctx.beginPath();
    for (let k = 0; k <= 72; k++) ctx[k ? "lineTo" : "moveTo"](...at([Math.cos((k * Math.PI) / 36), Math.sin((k * Math.PI) / 36), 0]));
    ctx.stroke();
    line([-1, 0, 0], [1, 0, 0], [0.45, 0.45, 0.5], 1);
    line([0, -1, 0], [0, 1, 0], [0.45, 0.45, 0.5], 1);
    const { theta, phi } = lab.lights[0];
    const ends = { N: direction(0, 0), L: direction(theta, phi), R: direction(theta, phi + 180) };
    const font = Math.round((12 * width) / (cssWidth(this.canvas) || width));
    ctx.font = `${font}px system-ui, sans-serif`;
    ctx.textAlign = "center";
    ctx.textBaseline = "middle";
    for (const [name, end] of Object.entries(ends)) {
      line([0, 0, 0], end.map((c) => 1.15 * c), MARKS[name], 1.6, [4, 3]);
      ctx.fillStyle = css(MARKS[name]);
      ctx.fillText(name, ...at(end.map((c) => 1.25 * c)));
    }
    if (this.spike > 0) {
      const r = lab.settings.polar_log
        ? Math.min(Math.max(Math.log10(this.spike / (this.scale * 10 ** -this.lab.constants.PLOT_DECADES)), 0) / this.lab.constants.PLOT_DECADES, 1.5)
        : Math.min(this.spike / this.scale, 1.5);
      line([0, 0, 0], ends.R.map((c) => r * c), hexRgb(this.panel.color), 4);
    }
    ctx.textAlign = "left";
    ctx.textBaseline = "alphabetic";
    ctx.fillStyle = "#bbb";
    const what = lab.settings.polar_cos ? "fᵣ cos θₒ" : "fᵣ";
    const scale = lab.settings.polar_log ? `, log over ${this.lab.constants.PLOT_DECADES} decades` : "";
    ctx.fillText(`${what}${scale}`, 4, font + 2);
    ctx.fillText(`radius 1: ${formatG(Number(this.scale.toPrecision(3)))} sr⁻¹`, 4, 2 * font + 4);
    setText(this.note, "drag to orbit; wheel or pinch to zoom" + (this.spike > 0 ? `; the line along R: the δ spike, ρ = ${formatG(Number(this.spike.toPrecision(3)))}` : ""));
  }

  /** The float picture (display values over the background, row 0 at the top), its scale,
   * the camera, and the value at every vertex of the full grid (row i = theta_o). */
  read() {
    const [width, height] = this.size;
    const grid = Array.from({ length: this.grid[0] * this.grid[1] }, (_, k) => this.peakCache?.values[k]);
    return { width, height, data: this.data, scale: this.scale, peak: this.peakCache?.value, grid };
  }
}

export const VIEW = { name: "lobe3d", queue: 30, create: (panel) => new LobeView(panel) };

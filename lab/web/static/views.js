// The views beyond the sphere and the polar plot, drawn from the same templates in
// shaders/views/ as the desktop lab: the (θh, θd) slice, directional albedo and the lit
// object with its spatially varying steps. Each renders on its panel's WebGL context into
// a float target, read back and shown on a 2D canvas (so a panel needs one context only).
import { formatG } from "./header.js";
import { font } from "./plotscale.js";
import { LobeView } from "./lobe3d.js";
import { SHView } from "./sh.js";
import { TermsView } from "./terms.js";

export const SHAPES = ["torus", "sphere", "rounded box", "bumpy sphere"];
export const MODES = ["geometry only", "single BRDF", "diffuse texture only", "textures drive the BRDF"];
// theta_i from 0 to 87.5 degrees, samples along each wedge, wedges around the mirror
// direction: the desktop's full-quality albedo (lab/app/views/albedo.py AlbedoView.FULL).
export const ALBEDO = { theta0: 0, step: 2.5, count: 36, samples: 192, wedges: 48 };
// While a slider or the light moves: the desktop's fast albedo, a smaller slice and a
// half-resolution object; the full views follow once the hand stops (lab.fast is off).
export const ALBEDO_FAST = { theta0: 0, step: 85 / 8, count: 9, samples: 32, wedges: 16 };
export const SLICE_FAST = 96;
export const SLICE_MAX = 256;
// The object is ray-marched (about 1 µs a pixel on SwiftShader): at most 96 px square while
// the hand moves, the full render once it stops.
export const OBJECT_FAST = 96;

/** Linear RGB(A) floats (rows from the bottom) -> an sRGB ImageData (rows from the top),
 * times 2^exposure and clamped, as the spheres are shown. */
export function toImage(floats, width, height, exposure) {
  const image = new ImageData(width, height);
  const scale = Math.pow(2, exposure);
  const srgb = (c) => {
    c = Math.min(Math.max(c * scale, 0), 1) || 0;
    return 255 * (c <= 0.0031308 ? 12.92 * c : 1.055 * Math.pow(c, 1 / 2.4) - 0.055);
  };
  for (let y = 0; y < height; y++) {
    for (let x = 0; x < width; x++) {
      const i = 4 * ((height - 1 - y) * width + x);
      const o = 4 * (y * width + x);
      const alpha = floats[i + 3];
      for (let c = 0; c < 3; c++) image.data[o + c] = Math.round(srgb(floats[i + c]) * alpha);
      image.data[o + 3] = Math.round(255 * alpha);
    }
  }
  return image;
}

/** Rows flipped so that row 0 is the top (what a test compares with the desktop). */
export function topFirst(floats, width, height) {
  const out = new Float32Array(floats.length);
  const row = 4 * width;
  for (let y = 0; y < height; y++) out.set(floats.subarray(y * row, (y + 1) * row), (height - 1 - y) * row);
  return out;
}

/** GLSL ES float literal (always with a point or an exponent: ES has no int -> float). */
const glslFloat = (x) => {
  const text = String(Number(x.toPrecision(9)));
  return /[.e]/.test(text) ? text : `${text}.0`;
};

/** The object view's spatially varying parameters, as lab/app/renderer.py makes them: each
 * float or colour uniform NAME becomes NAME_base and a global NAME that sv_assign sets per
 * pixel (the albedo map scales the first colour, the variation map moves log floats). */
export function spatiallyVarying(source, model) {
  source.origins.forEach(([label], index) => {
    if (!label.endsWith("(parameters)")) return;
    const match = /^uniform (float|vec3) ([A-Za-z_]\w*);$/.exec(source.lines[index]);
    if (match) source.lines[index] = `uniform ${match[1]} ${match[2]}_base; ${match[1]} ${match[2]};`;
  });
  const body = [];
  let firstColor = true;
  for (const p of model.params) {
    if (p.kind === "color") {
      body.push(`    ${p.name} = ${p.name}_base${firstColor ? " * sv_albedo" : ""};`);
      firstColor = false;
    } else if (p.kind === "float" && p.scale === "log") {
      body.push(`    ${p.name} = sv_vary(${p.name}_base, ${glslFloat(p.minimum)}, ${glslFloat(p.maximum)}, sv_amount);`);
    } else if (p.kind === "float") {
      body.push(`    ${p.name} = ${p.name}_base;`);
    }
  }
  source.add(
    "float sv_vary(float base, float lo, float hi, float t) {\n" +
      "    float a = log(base);\n" +
      "    float far_end = (a - log(lo) > log(hi) - a) ? log(lo) : log(hi);\n" +
      "    return exp(mix(a, far_end, 0.75 * t));\n" +
      "}\n" +
      "void sv_assign(float sv_amount, vec3 sv_albedo) {\n" + body.join("\n") + "\n}",
    "<host: spatially varying parameters>");
}

/** The object's program: its spatially varying parameters, and the shape (u_shape) and the
 * step (u_mode) as constants from the preamble instead of uniforms. The compiler then drops
 * the code of the other shapes and steps: SwiftShader (Chromium without a GPU) compiles a
 * program at its first draw, and this one in about a fifth of the time. */
export function objectProgram(source, model) {
  spatiallyVarying(source, model);
  for (const name of ["u_shape", "u_mode"]) {
    const index = source.lines.findIndex((line) => line.startsWith(`uniform int ${name};`));
    // Replaced, not removed: the lines keep their numbers for error messages.
    if (index >= 0) source.lines[index] = `// ${name}: a constant of this program (its preamble)`;
  }
}

/** f_r over (θh, θd) at the page's φd. */
export class SliceView {
  constructor(panel, env) {
    this.panel = panel;
    this.env = env;
    this.canvas = env.el("canvas", { class: "slice", width: 384, height: 384 });
    this.root = env.viewBox(this.canvas, "slice", () => `${panel.name}_slice.png`);
  }

  render() {
    this.submit();
    this.collect();
    this.process();
  }

  warm() {
    this.panel.program("slice", null, null, { start: true });
  }

  submit() {
    const { lab } = this.env;
    const n = Math.min(lab.size, lab.fast ? SLICE_FAST : SLICE_MAX);
    this.size = n;
    this.pass = this.panel.draw("slice", n, n, { u_resolution: [n, n], u_phi_d: (lab.phiD * Math.PI) / 180 });
  }

  collect() {
    this.data = this.panel.collect(this.pass);
  }

  process() {
    const { lab } = this.env;
    const n = this.size;
    const canvas = this.canvas;
    const ctx = canvas.getContext("2d");
    const f = font(ctx, canvas);
    const left = 3.8 * f;
    const bottom = 2.4 * f;
    // The 90° tick label is centred on the right edge of the image: room for its half.
    const side = Math.min(canvas.width - left - ctx.measureText("90°").width / 2 - 2, canvas.height - bottom - 1.6 * f);
    const top = 1.6 * f;
    ctx.clearRect(0, 0, canvas.width, canvas.height);
    const image = toImage(this.data, n, n, lab.exposure);
    const scratch = new OffscreenCanvas(n, n);
    scratch.getContext("2d").putImageData(image, 0, 0);
    ctx.imageSmoothingEnabled = false;
    ctx.drawImage(scratch, left, top, side, side);
    ctx.fillStyle = "#bbb";
    ctx.fillText(`fᵣ(θh, θd) at φd = ${formatG(lab.phiD)}°`, 2, f);
    ctx.textAlign = "center";
    for (const deg of [0, 30, 60, 90]) {
      ctx.fillText(`${deg}°`, left + (side * deg) / 90, top + side + 1.1 * f);
      ctx.textAlign = "right";
      ctx.fillText(`${deg}°`, left - 4, top + side - (side * deg) / 90 + 0.35 * f);
      ctx.textAlign = "center";
    }
    ctx.fillText("θh (half vector from the normal) →", left + side / 2, top + side + 2.2 * f);
    ctx.save();
    ctx.translate(f * 0.9, top + side / 2);
    ctx.rotate(-Math.PI / 2);
    ctx.fillText("θd (light from the half vector) →", 0, 0);
    ctx.restore();
    ctx.textAlign = "left";
  }

  read() {
    return { width: this.size, height: this.size, data: topFirst(this.data, this.size, this.size) };
  }
}

/** Directional albedo against θi, energy gain (albedo > 1) flagged in red. */
export class AlbedoView {
  constructor(panel, env) {
    this.panel = panel;
    this.env = env;
    this.canvas = env.el("canvas", { class: "albedo", width: 384, height: 240 });
    this.root = env.viewBox(this.canvas, "albedo", () => `${panel.name}_albedo.png`);
    this.note = env.el("div", { class: "view-note" });
    this.root.append(this.note);
  }

  render() {
    this.submit();
    this.collect();
    this.process();
  }

  warm() {
    this.panel.program("albedo", null, null, { start: true });
  }

  submit() {
    const { lab } = this.env;
    const a = (this.quality = lab.fast ? ALBEDO_FAST : ALBEDO);
    this.pass = this.panel.draw("albedo", a.wedges, a.count, {
      u_theta0: (a.theta0 * Math.PI) / 180, u_theta_step: (a.step * Math.PI) / 180,
      u_phi_i: (lab.lights[0].phi * Math.PI) / 180, u_samples: a.samples, u_wedges: a.wedges,
    });
  }

  collect() {
    this.raw = this.panel.collect(this.pass);
  }

  process() {
    const a = this.quality;
    const raw = this.raw;
    // The host sums the wedges (in double precision, as numpy does).
    this.thetas = [];
    this.rgb = [];
    for (let k = 0; k < a.count; k++) {
      const sum = [0, 0, 0];
      for (let j = 0; j < a.wedges; j++) for (let c = 0; c < 3; c++) sum[c] += raw[4 * (k * a.wedges + j) + c];
      this.thetas.push(a.theta0 + k * a.step);
      this.rgb.push(sum);
    }
    this.albedo = this.rgb.map((rgb) => Math.max(...rgb));
    this.gain = this.albedo.some((x) => x > 1 + 1e-3);
    this.draw();
  }

  draw() {
    const canvas = this.canvas;
    const ctx = canvas.getContext("2d");
    const f = font(ctx, canvas);
    const finite = this.albedo.filter(Number.isFinite);
    const high = Math.max(1, ...finite) * 1.05;
    const topValue = [1.1, 1.5, 2, 3, 5, 10, 20, 50].find((t) => t >= high) ?? 10 ** Math.ceil(Math.log10(high));
    const left = 3 * f;
    const right = canvas.width - ctx.measureText("90°").width / 2 - 2; // the 90° label fits
    const top = 1.6 * f;
    const bottom = canvas.height - 2.4 * f;
    const x = (deg) => left + ((right - left) * deg) / 90;
    const y = (v) => bottom - ((bottom - top) * v) / topValue;
    ctx.clearRect(0, 0, canvas.width, canvas.height);
    ctx.fillStyle = "#bbb";
    ctx.fillText("directional albedo ∫ fᵣ cos θₒ dω (largest channel)", 2, f);
    ctx.strokeStyle = "#666";
    ctx.lineWidth = 1;
    ctx.beginPath();
    ctx.moveTo(left, top);
    ctx.lineTo(left, bottom);
    ctx.lineTo(right, bottom);
    ctx.stroke();
    ctx.textAlign = "center";
    for (const deg of [0, 30, 60, 90]) ctx.fillText(`${deg}°`, x(deg), bottom + 1.1 * f);
    ctx.fillText("θi", (left + right) / 2, bottom + 2.2 * f);
    ctx.textAlign = "right";
    for (const v of [0, topValue / 2, topValue]) ctx.fillText(formatG(Number(v.toPrecision(3))), left - 4, y(v) + 0.35 * f);
    ctx.textAlign = "left";
    ctx.setLineDash([5, 4]);
    ctx.strokeStyle = "#ddd";
    ctx.beginPath();
    ctx.moveTo(left, y(1));
    ctx.lineTo(right, y(1));
    ctx.stroke();
    ctx.setLineDash([]);
    ctx.fillStyle = "#ddd";
    ctx.fillText("albedo = 1", right - 6.5 * f, y(1) - 4);
    ctx.strokeStyle = this.panel.color;
    ctx.lineWidth = 2;
    ctx.beginPath();
    this.thetas.forEach((t, k) => ctx[k ? "lineTo" : "moveTo"](x(t), y(Math.min(this.albedo[k], topValue))));
    ctx.stroke();
    ctx.strokeStyle = "#ff4040";
    ctx.lineWidth = 2;
    this.thetas.forEach((t, k) => {
      if (!(this.albedo[k] > 1 + 1e-3)) return;
      const [cx, cy, r] = [x(t), y(Math.min(this.albedo[k], topValue)), 4];
      ctx.beginPath();
      ctx.moveTo(cx - r, cy - r);
      ctx.lineTo(cx + r, cy + r);
      ctx.moveTo(cx - r, cy + r);
      ctx.lineTo(cx + r, cy - r);
      ctx.stroke();
    });
    this.note.textContent = this.gain ? "energy gain: the albedo exceeds 1 (×), more light leaves than arrives" : "";
    this.note.classList.toggle("bad", this.gain);
  }

  read() {
    return { thetas: this.thetas, rgb: this.rgb, gain: this.gain };
  }
}

/** The procedural object lit by every light, with the lecture's spatially varying steps;
 * drag on it to orbit. */
export class ObjectView {
  constructor(panel, env) {
    this.panel = panel;
    this.env = env;
    const size = env.lab.size;
    this.canvas = env.el("canvas", { class: "object", width: size, height: size });
    this.root = env.viewBox(this.canvas, "object", () => `${panel.name}_object.png`);
    this.canvas.addEventListener("pointerdown", (e) => {
      this.canvas.setPointerCapture(e.pointerId);
      this.drag = [e.clientX, e.clientY];
    });
    this.canvas.addEventListener("pointermove", (e) => {
      if (!this.drag || !e.buttons) return;
      const rect = this.canvas.getBoundingClientRect();
      const { lab } = env;
      lab.yaw += ((e.clientX - this.drag[0]) / rect.width) * Math.PI;
      lab.pitch = Math.min(Math.max(lab.pitch + ((e.clientY - this.drag[1]) / rect.height) * Math.PI, -1.5), 1.5);
      this.drag = [e.clientX, e.clientY];
      env.scheduleRender();
    });
    this.canvas.addEventListener("pointerup", () => (this.drag = null));
  }

  render() {
    this.submit();
    this.collect();
    this.process();
  }

  submit() {
    const { lab, C, direction } = this.env;
    const n = lab.fast ? Math.min(lab.size, OBJECT_FAST) : lab.size;
    const dirs = [];
    const rgb = [];
    for (let i = 0; i < C.MAX_LIGHTS; i++) {
      const light = lab.lights[i];
      dirs.push(light ? direction(light.theta, light.phi) : [0, 0, 1]);
      rgb.push(light ? light.rgb : [0, 0, 0]);
    }
    this.size = n;
    this.pass = this.panel.draw("object", n, n, {
      u_resolution: [n, n], u_light_dir: dirs, u_light_rgb: rgb, u_ambient: lab.ambient, u_yaw: lab.yaw, u_pitch: lab.pitch,
    }, { preamble: this.preamble(), transform: objectProgram, suffix: "_base" });
  }

  /** The shape and the step are constants of the program (one per choice), not uniforms. */
  preamble() {
    const { lab } = this.env;
    return [`const int LIGHT_COUNT = ${lab.lights.length};`,
      `const int u_shape = ${Math.trunc(lab.shape) || 0};`, `const int u_mode = ${Math.trunc(lab.mode) || 0};`].join("\n");
  }

  warm() {
    this.panel.program("object", this.preamble(), objectProgram, { start: true });
  }

  collect() {
    this.data = this.panel.collect(this.pass);
  }

  process() {
    const { lab } = this.env;
    const n = this.size;
    const ctx = this.canvas.getContext("2d");
    if (n === this.canvas.width) ctx.putImageData(toImage(this.data, n, n, lab.exposure), 0, 0);
    else {
      const scratch = new OffscreenCanvas(n, n);
      scratch.getContext("2d").putImageData(toImage(this.data, n, n, lab.exposure), 0, 0);
      ctx.clearRect(0, 0, this.canvas.width, this.canvas.height);
      ctx.drawImage(scratch, 0, 0, this.canvas.width, this.canvas.height);
    }
  }

  read() {
    return { width: this.size, height: this.size, data: topFirst(this.data, this.size, this.size) };
  }
}

export const VIEWS = { lobe3d: LobeView, sh: SHView, terms: TermsView, slice: SliceView, albedo: AlbedoView,
  object: ObjectView };
export const VIEW_TITLES = { lobe3d: "3D lobe", sh: "spherical harmonics", terms: "D, G, F", slice: "(θh, θd) slice",
  albedo: "albedo", object: "lit object" };

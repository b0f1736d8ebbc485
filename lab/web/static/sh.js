// The spherical-harmonics view, as the desktop's (lab/app/sh_view.py with lab/measured/sh.py):
// the lobe g(wo) = fr(wi, wo) cos θo for light 1, from the model's GLSL on a quadrature grid
// (the probe template), projected on real harmonics up to order 16 as an odd function of z.
// Left: g and its series at order L in the plane of incidence; right: the relative L2
// error over the hemisphere against the order.
import { formatG } from "./header.js";

export const MAX_ORDER = 16;
export const GRID = [48, 96]; // Gauss-Legendre nodes in cos θ × uniform φ (sh_view.GRID)
const SERIES = "#ffd200";
const count = (order) => (order + 1) ** 2;

/** Gauss-Legendre nodes and weights on [-1, 1] (n nodes, ascending), by Newton's method. */
export function gaussLegendre(n) {
  const x = new Float64Array(n);
  const w = new Float64Array(n);
  for (let k = 0; k < Math.ceil(n / 2); k++) {
    let z = Math.cos((Math.PI * (k + 0.75)) / (n + 0.5));
    let dp = 0;
    for (let it = 0; it < 100; it++) {
      let [p0, p1] = [1, z];
      for (let l = 2; l <= n; l++) [p0, p1] = [p1, ((2 * l - 1) * z * p1 - (l - 1) * p0) / l];
      dp = (n * (z * p1 - p0)) / (z * z - 1);
      const step = p1 / dp;
      z -= step;
      if (Math.abs(step) < 1e-16) break;
    }
    let [p0, p1] = [1, z];
    for (let l = 2; l <= n; l++) [p0, p1] = [p1, ((2 * l - 1) * z * p1 - (l - 1) * p0) / l];
    dp = (n * (z * p1 - p0)) / (z * z - 1);
    x[n - 1 - k] = z;
    x[k] = -z;
    w[k] = w[n - 1 - k] = 2 / ((1 - z * z) * dp * dp);
  }
  return { x, w };
}

const lgamma = (n) => { // log((n - 1)!) for whole n >= 1
  let s = 0;
  for (let k = 2; k < n; k++) s += Math.log(k);
  return s;
};

/** Real orthonormal harmonics up to `order` at (θ, φ), index l² + l + m (sh.real_sh). */
export function realSh(order, theta, phi) {
  const out = new Float64Array(count(order));
  const x = Math.cos(theta);
  const sine = Math.sqrt(Math.max(1 - x * x, 0));
  const P = Array.from({ length: order + 1 }, () => new Float64Array(order + 1)); // P[l][m]
  let diagonal = 1;
  for (let m = 0; m <= order; m++) {
    if (m) diagonal = -(2 * m - 1) * sine * diagonal;
    P[m][m] = diagonal;
    if (m < order) P[m + 1][m] = (2 * m + 1) * x * diagonal;
    for (let l = m + 2; l <= order; l++) P[l][m] = ((2 * l - 1) * x * P[l - 1][m] - (l + m - 1) * P[l - 2][m]) / (l - m);
  }
  for (let l = 0; l <= order; l++) {
    for (let m = 0; m <= l; m++) {
      const ratio = Math.exp(lgamma(l - m + 1) - lgamma(l + m + 1));
      const p = Math.sqrt(((2 * l + 1) / (4 * Math.PI)) * ratio) * P[l][m];
      if (m === 0) out[l * l + l] = p;
      else {
        out[l * l + l + m] = Math.SQRT2 * p * Math.cos(m * phi);
        out[l * l + l - m] = Math.SQRT2 * p * Math.sin(m * phi);
      }
    }
  }
  return out;
}

let projector = null; // the grid and its harmonics: the same for every model and light

/** The quadrature grid on the upper hemisphere with the harmonics at its nodes. */
function grid() {
  if (projector) return projector;
  const [nTheta, nPhi] = GRID;
  const { x, w } = gaussLegendre(2 * nTheta);
  const n = nTheta * nPhi;
  const V = new Float32Array(4 * n);
  const weight = new Float64Array(n);
  const basis = [];
  for (let i = 0; i < nTheta; i++) {
    const c = x[nTheta + i]; // the nodes with cos θ > 0
    const theta = Math.acos(c);
    for (let j = 0; j < nPhi; j++) {
      const phi = ((j + 0.5) * 2 * Math.PI) / nPhi;
      const k = i * nPhi + j;
      V.set([Math.sin(theta) * Math.cos(phi), Math.sin(theta) * Math.sin(phi), c, 0], 4 * k);
      weight[k] = (w[nTheta + i] * 2 * Math.PI) / nPhi;
      basis.push(realSh(MAX_ORDER, theta, phi));
    }
  }
  const odd = new Float64Array(count(MAX_ORDER));
  for (let index = 0; index < odd.length; index++) {
    const l = Math.floor(Math.sqrt(index));
    odd[index] = (l + Math.abs(index - l * l - l)) % 2 === 1 ? 1 : 0;
  }
  projector = { V, weight, basis, odd, n };
  return projector;
}

/** Coefficients of the odd extension of `lobe`, and the relative L2 error of every order. */
export function analyse(lobe) {
  const { weight, basis, odd, n } = grid();
  const coefficients = new Float64Array(count(MAX_ORDER));
  for (let k = 0; k < n; k++) {
    const wk = 2 * weight[k] * lobe[k];
    if (wk === 0) continue;
    const Y = basis[k];
    for (let c = 0; c < coefficients.length; c++) coefficients[c] += odd[c] * Y[c] * wk;
  }
  let norm = 0;
  for (let k = 0; k < n; k++) norm += weight[k] * lobe[k] * lobe[k];
  norm = Math.sqrt(norm);
  const approx = new Float64Array(n);
  const errors = [];
  for (let order = 0; order <= MAX_ORDER; order++) {
    let sum = 0;
    for (let k = 0; k < n; k++) {
      const Y = basis[k];
      for (let c = order * order; c < count(order); c++) approx[k] += Y[c] * coefficients[c];
      sum += weight[k] * (approx[k] - lobe[k]) ** 2;
    }
    errors.push(Math.sqrt(sum) / Math.max(norm, 1e-300));
  }
  return { coefficients, errors };
}

export class SHView {
  constructor(panel, env) {
    this.panel = panel;
    this.env = env;
    this.canvas = env.el("canvas", { class: "sh", width: 384, height: 220 });
    this.root = env.viewBox(this.canvas, "spherical harmonics", () => `${panel.name}_sh.png`);
    this.order = env.el("input", { type: "number", min: 0, max: MAX_ORDER, step: 1, value: env.lab.shOrder });
    this.order.addEventListener("input", () => {
      const value = Math.round(Number(this.order.value));
      if (!(value >= 0 && value <= MAX_ORDER)) return;
      env.lab.shOrder = value;
      env.scheduleRender();
    });
    this.note = env.el("div", { class: "view-note" });
    this.root.append(env.el("label", { class: "group", title: `the order L of the series (0 to ${MAX_ORDER}): (L + 1)² coefficients` },
      "order L ", this.order), this.note);
    this.planeBasis = new Map(); // φi -> the harmonics in the plane of incidence
  }

  render() {
    const { lab, direction } = this.env;
    this.order.value = lab.shOrder;
    const light = lab.lights[0];
    this.data = null;
    if (this.panel.model.delta) {
      this.draw();
      return;
    }
    const key = JSON.stringify([this.panel.values, light.theta, light.phi]);
    if (this.cache?.model !== this.panel.model || this.cache.key !== key) {
      const { V, n } = grid();
      const [nTheta, nPhi] = GRID;
      const gl = this.panel.gl;
      const L = new Float32Array(4 * n);
      const Ld = direction(light.theta, light.phi);
      for (let k = 0; k < n; k++) L.set(Ld, 4 * k);
      const textures = [L, V].map((data) => {
        const t = gl.createTexture();
        gl.bindTexture(gl.TEXTURE_2D, t);
        gl.texImage2D(gl.TEXTURE_2D, 0, gl.RGBA32F, nPhi, nTheta, 0, gl.RGBA, gl.FLOAT, data);
        gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.NEAREST);
        gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.NEAREST);
        return t;
      });
      const f = this.panel.run("probe", nPhi, nTheta, { u_L: 0, u_V: 1 }, { textures });
      textures.forEach((t) => gl.deleteTexture(t));
      const C = this.env.C;
      const lobe = new Float64Array(n);
      for (let k = 0; k < n; k++) {
        const g = (C.LUMA[0] * f[4 * k] + C.LUMA[1] * f[4 * k + 1] + C.LUMA[2] * f[4 * k + 2]) * V[4 * k + 2];
        lobe[k] = Number.isFinite(g) ? g : 0; // a division by zero would swamp every coefficient
      }
      this.cache = { model: this.panel.model, key, ...analyse(lobe) };
    }
    this.data = this.cache;
    this.draw();
  }

  /** The harmonics at the polar plot's directions (θo = -90..90 in the plane of incidence
   * of azimuth φi, turned by φo). */
  plane(phiDeg, phiO) {
    const key = `${phiDeg},${phiO}`;
    if (!this.planeBasis.has(key)) {
      const rows = [];
      for (let t = -90; t <= 90; t++) {
        const [x, y, z] = this.env.direction(Math.abs(t), (t >= 0 ? phiDeg + 180 : phiDeg) + phiO);
        rows.push(realSh(MAX_ORDER, Math.acos(Math.min(Math.max(z, -1), 1)), Math.atan2(y, x)));
      }
      this.planeBasis.clear();
      this.planeBasis.set(key, rows);
    }
    return this.planeBasis.get(key);
  }

  draw() {
    const { lab, C } = this.env;
    const canvas = this.canvas;
    const ctx = canvas.getContext("2d");
    const px = Math.round((12 * canvas.width) / (canvas.clientWidth || canvas.width));
    ctx.font = `${px}px system-ui, sans-serif`;
    ctx.clearRect(0, 0, canvas.width, canvas.height);
    ctx.fillStyle = "#bbb";
    if (!this.data) {
      ctx.fillText("an ideal mirror has no finite lobe to expand", 4, 2 * px);
      this.note.textContent = "";
      return;
    }
    const order = lab.shOrder;
    const light = lab.lights[0];
    // The lobe in the plane of incidence from the panel's polar plot probe (fr, 1° steps).
    const f = this.panel.lobe;
    const lum = (i) => (C.LUMA[0] * f[4 * i] + C.LUMA[1] * f[4 * i + 1] + C.LUMA[2] * f[4 * i + 2]) * Math.cos(((i - 90) * Math.PI) / 180);
    const plane = Array.from({ length: 181 }, (_, i) => (Number.isFinite(lum(i)) ? lum(i) : 0));
    const peak = Math.max(1e-9, ...plane.filter((_, i) => Math.abs(i - 90) <= C.GRAZING_DEG));
    const basis = this.plane(light.phi, lab.phiO);
    const series = basis.map((Y) => {
      let s = 0;
      for (let c = 0; c < count(order); c++) s += Y[c] * this.data.coefficients[c];
      return s;
    });
    this.series = series;
    this.planeValues = plane;
    // Left 3/5: the lobe relative to its peak, y from -0.35 to 1.15 as on the desktop.
    const split = Math.round(canvas.width * 0.6);
    const top = 2.2 * px;
    const bottom = canvas.height - 2.4 * px;
    let left = 2.4 * px;
    let right = split - 8;
    const x = (t) => left + ((right - left) * (t + 90)) / 180;
    const y = (v) => bottom - ((bottom - top) * (v + 0.35)) / 1.5;
    ctx.fillText(`fᵣ cos θₒ, ${lab.phiO ? `plane turned φo = ${formatG(lab.phiO)}°` : "plane of incidence"}`, 2, px);
    ctx.strokeStyle = "#666";
    ctx.lineWidth = 1;
    ctx.strokeRect(left, top, right - left, bottom - top);
    ctx.beginPath();
    ctx.moveTo(left, y(0));
    ctx.lineTo(right, y(0));
    ctx.stroke();
    ctx.setLineDash([4, 4]);
    ctx.strokeStyle = "#78c8ff";
    ctx.beginPath();
    ctx.moveTo(x(light.theta), top);
    ctx.lineTo(x(light.theta), bottom);
    ctx.stroke();
    ctx.setLineDash([]);
    ctx.textAlign = "center";
    for (const t of [-90, 0, 90]) ctx.fillText(`${t}°`, x(t), bottom + 1.1 * px);
    ctx.fillText("θₒ (R: dashed)", (left + right) / 2, bottom + 2.2 * px);
    ctx.textAlign = "right";
    for (const v of [0, 1]) ctx.fillText(String(v), left - 3, y(v) + 0.35 * px);
    ctx.textAlign = "left";
    const curve = (values, color, dash) => {
      ctx.strokeStyle = color;
      ctx.lineWidth = 2;
      ctx.setLineDash(dash);
      ctx.beginPath();
      values.forEach((v, i) => ctx[i ? "lineTo" : "moveTo"](x(i - 90), y(Math.min(Math.max(v / peak, -0.35), 1.15))));
      ctx.stroke();
      ctx.setLineDash([]);
    };
    curve(plane, this.panel.color, []);
    curve(series, SERIES, [6, 4]);
    ctx.fillStyle = this.panel.color;
    ctx.fillText("original (GLSL)", left + 4, top + 1.1 * px);
    ctx.fillStyle = SERIES;
    ctx.fillText(`SH series, L = ${order}`, left + 4, top + 2.2 * px);
    // Right: the error against the order, log scale.
    const errors = this.data.errors.map((e) => Math.max(e, 1e-6));
    const low = Math.floor(Math.log10(Math.min(...errors)));
    left = split + 3.2 * px;
    right = canvas.width - 6;
    const ex = (k) => left + ((right - left) * (k + 0.5)) / (MAX_ORDER + 1);
    const ey = (e) => top + ((bottom - top) * (0.2 - Math.log10(e))) / (0.2 - low);
    ctx.fillStyle = "#bbb";
    ctx.fillText("relative L2 error", split + 4, px);
    ctx.strokeStyle = "#666";
    ctx.strokeRect(left, top, right - left, bottom - top);
    ctx.textAlign = "right";
    const step = Math.max(1, Math.ceil(-low / 3));
    for (let k = 0; k >= low; k -= step) ctx.fillText(k ? `1e${k}` : "1", left - 3, ey(10 ** k) + 0.35 * px);
    ctx.textAlign = "center";
    for (const k of [0, 8, 16]) ctx.fillText(String(k), ex(k), bottom + 1.1 * px);
    ctx.fillText("order L", (left + right) / 2, bottom + 2.2 * px);
    ctx.textAlign = "left";
    ctx.strokeStyle = SERIES;
    ctx.lineWidth = 1.5;
    ctx.beginPath();
    ctx.moveTo(ex(order), top);
    ctx.lineTo(ex(order), bottom);
    ctx.stroke();
    ctx.strokeStyle = this.panel.color;
    ctx.lineWidth = 2;
    ctx.beginPath();
    errors.forEach((e, k) => ctx[k ? "lineTo" : "moveTo"](ex(k), ey(e)));
    ctx.stroke();
    this.note.textContent = `L = ${order}: ${count(order)} coefficients, error ${formatG(Number((100 * this.data.errors[order]).toPrecision(2)))} %`;
  }

  /** Coefficients (luminance lobe), errors by order 0..16, and the plane's curves. */
  read() {
    if (!this.data) return { coefficients: [], errors: [], plane: [], series: [] };
    return { coefficients: Array.from(this.data.coefficients), errors: this.data.errors, plane: this.planeValues, series: this.series };
  }
}

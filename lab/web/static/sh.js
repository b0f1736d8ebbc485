// The spherical-harmonics view, as the desktop's (lab/app/sh_view.py with lab/measured/sh.py):
// the lobe g(wo) = fr(wi, wo) cos θo for light 1, from the model's GLSL on a quadrature grid
// (the probe template), projected on real harmonics up to order 16 as an odd function of z.
// Left: g and its series at order L in the plane of incidence; right: the relative L2
// error over the hemisphere against the order.
import { formatG } from "./header.js";
import { clearedPlot } from "./plotscale.js";

export const MAX_ORDER = 16;
export const GRID = [48, 96]; // Gauss-Legendre nodes in cos θ × uniform φ (sh_view.GRID)
const SERIES = "#ffd200";
const count = (order) => (order + 1) ** 2;

/** Gauss-Legendre nodes and weights on [-1, 1] (n nodes, ascending), by Newton's method. */
export function gaussLegendre(n) {
  const x = new Float64Array(n);
  const w = new Float64Array(n);
  // P_n(z) and its derivative, by the three-term recurrence.
  const legendre = (z) => {
    let p0 = 1;
    let p1 = z;
    for (let l = 2; l <= n; l++) {
      const p2 = ((2 * l - 1) * z * p1 - (l - 1) * p0) / l;
      p0 = p1;
      p1 = p2;
    }
    return [p1, (n * (z * p1 - p0)) / (z * z - 1)];
  };
  for (let k = 0; k < Math.ceil(n / 2); k++) {
    let z = Math.cos((Math.PI * (k + 0.75)) / (n + 0.5));
    for (let it = 0; it < 100; it++) {
      const [p, slope] = legendre(z);
      const step = p / slope;
      z -= step;
      if (Math.abs(step) < 1e-16) break;
    }
    const dp = legendre(z)[1]; // at the root itself, for the weight
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

// sqrt((2l + 1) / 4π · (l - m)! / (l + m)!) at l * (MAX_ORDER + 1) + m: the same for every
// direction, computed once (as sh.real_sh computes it).
const NORM = new Float64Array((MAX_ORDER + 1) ** 2);
for (let l = 0; l <= MAX_ORDER; l++) {
  for (let m = 0; m <= l; m++) {
    NORM[l * (MAX_ORDER + 1) + m] = Math.sqrt(((2 * l + 1) / (4 * Math.PI)) * Math.exp(lgamma(l - m + 1) - lgamma(l + m + 1)));
  }
}

/** Real orthonormal harmonics up to `order` (at most MAX_ORDER) at (θ, φ), index l² + l + m
 * (sh.real_sh). */
export function realSh(order, theta, phi) {
  const out = new Float64Array(count(order));
  const x = Math.cos(theta);
  const sine = Math.sqrt(Math.max(1 - x * x, 0));
  const stride = order + 1;
  const P = new Float64Array(stride * stride); // P[l * stride + m]
  let diagonal = 1;
  for (let m = 0; m <= order; m++) {
    if (m) diagonal = -(2 * m - 1) * sine * diagonal;
    P[m * stride + m] = diagonal;
    if (m < order) P[(m + 1) * stride + m] = (2 * m + 1) * x * diagonal;
    for (let l = m + 2; l <= order; l++) {
      P[l * stride + m] = ((2 * l - 1) * x * P[(l - 1) * stride + m] - (l + m - 1) * P[(l - 2) * stride + m]) / (l - m);
    }
  }
  for (let m = 0; m <= order; m++) {
    const c = Math.SQRT2 * Math.cos(m * phi);
    const s = Math.SQRT2 * Math.sin(m * phi);
    for (let l = m; l <= order; l++) {
      const p = NORM[l * (MAX_ORDER + 1) + m] * P[l * stride + m];
      if (m === 0) out[l * l + l] = p;
      else {
        out[l * l + l + m] = c * p;
        out[l * l + l - m] = s * p;
      }
    }
  }
  return out;
}

/** The harmonics odd in z (l + |m| odd): the only ones the odd extension of a lobe has. */
export const ODD = [];
for (let index = 0; index < count(MAX_ORDER); index++) {
  const l = Math.floor(Math.sqrt(index));
  if ((l + Math.abs(index - l * l - l)) % 2 === 1) ODD.push(index);
}

let projector = null; // the grid and its harmonics: the same for every model and light

/** The quadrature grid on the upper hemisphere (rows of θ, then φ; as sh.hemisphere_grid):
 * directions V (RGBA floats), solid angles, and the harmonics split as they separate,
 * Y_lm(θ, φ) = N_lm P_lm(cos θ) trig(mφ): per row of θ, 2·w·N·P of each odd harmonic (√2
 * folded in for m ≠ 0), per column of φ, cos(mφ) and sin(mφ). */
export function quadrature() {
  if (projector) return projector;
  const [nTheta, nPhi] = GRID;
  const { x, w } = gaussLegendre(2 * nTheta);
  const n = nTheta * nPhi;
  const V = new Float32Array(4 * n);
  const weight = new Float64Array(n);
  const K = ODD.length;
  const rows = new Float64Array(nTheta * K);
  const M = MAX_ORDER + 1;
  const cos = new Float64Array(nPhi * M);
  const sin = new Float64Array(nPhi * M);
  for (let j = 0; j < nPhi; j++) {
    const phi = ((j + 0.5) * 2 * Math.PI) / nPhi;
    for (let m = 0; m < M; m++) {
      cos[j * M + m] = Math.cos(m * phi);
      sin[j * M + m] = Math.sin(m * phi);
    }
  }
  for (let i = 0; i < nTheta; i++) {
    const c = x[nTheta + i]; // the nodes with cos θ > 0
    const theta = Math.acos(c);
    const solid = (w[nTheta + i] * 2 * Math.PI) / nPhi;
    // The harmonics at φ = 0 give N·P (m >= 0, times √2 for m > 0).
    const Y = realSh(MAX_ORDER, theta, 0);
    ODD.forEach((index, o) => {
      const l = Math.floor(Math.sqrt(index));
      const m = index - l * l - l;
      rows[i * K + o] = 2 * solid * Y[l * l + l + Math.abs(m)];
    });
    const sine = Math.sin(theta);
    for (let j = 0; j < nPhi; j++) {
      const k = i * nPhi + j;
      V[4 * k] = sine * cos[j * M + 1];
      V[4 * k + 1] = sine * sin[j * M + 1];
      V[4 * k + 2] = c;
      weight[k] = solid;
    }
  }
  projector = { V, weight, rows, cos, sin, n, nTheta, nPhi };
  return projector;
}

/** Coefficients of the odd extension of `lobe` (values at the quadrature's nodes), and the
 * relative L2 error over the hemisphere of the series of every order.
 *
 * The errors come from Parseval's identity: the grid integrates products of harmonics up
 * to order 16 exactly, so over the hemisphere the odd harmonics are orthogonal with norm
 * 1/2 and the series' error is ||g||² - Σ a² / 2 over its coefficients (no sum over the
 * nodes per order; the same as summing (series - g)² there, to rounding). */
export function analyse(lobe) {
  const { weight, rows, cos, sin, n, nTheta, nPhi } = quadrature();
  const K = ODD.length;
  const M = MAX_ORDER + 1;
  const odd = new Float64Array(K);
  const C = new Float64Array(M);
  const S = new Float64Array(M);
  for (let i = 0; i < nTheta; i++) {
    // The row's Fourier sums, then each harmonic's share of them.
    C.fill(0);
    S.fill(0);
    for (let j = 0; j < nPhi; j++) {
      const g = lobe[i * nPhi + j];
      if (g === 0) continue;
      for (let m = 0; m < M; m++) {
        C[m] += g * cos[j * M + m];
        S[m] += g * sin[j * M + m];
      }
    }
    for (let o = 0; o < K; o++) {
      const index = ODD[o];
      const l = Math.floor(Math.sqrt(index));
      const m = index - l * l - l;
      odd[o] += rows[i * K + o] * (m >= 0 ? C[m] : S[-m]);
    }
  }
  const coefficients = new Float64Array(count(MAX_ORDER));
  ODD.forEach((index, o) => (coefficients[index] = odd[o]));
  let norm2 = 0;
  for (let k = 0; k < n; k++) norm2 += weight[k] * lobe[k] * lobe[k];
  const norm = Math.max(Math.sqrt(norm2), 1e-300);
  const errors = [];
  let captured = 0;
  for (let order = 0; order <= MAX_ORDER; order++) {
    for (let c = order * order; c < count(order); c++) captured += (coefficients[c] * coefficients[c]) / 2;
    errors.push(Math.sqrt(Math.max(norm2 - captured, 0)) / norm);
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
    this.submit();
    this.collect();
    this.process();
  }

  /** Queues the probe of the lobe on the quadrature grid, unless the series is cached. */
  submit() {
    const { lab, direction } = this.env;
    this.order.value = lab.shOrder;
    const light = lab.lights[0];
    this.pass = null;
    this.key = JSON.stringify([this.panel.values, light.theta, light.phi]);
    if (this.panel.model.delta || (this.cache?.model === this.panel.model && this.cache.key === this.key)) return;
    const { V, n } = quadrature();
    const [nTheta, nPhi] = GRID;
    const Ld = direction(light.theta, light.phi);
    const lightL = () => {
      const L = new Float32Array(4 * n);
      for (let k = 0; k < n; k++) L.set(Ld, 4 * k);
      return L;
    };
    const textures = [this.panel.heldTexture("sh L", `${light.theta},${light.phi}`, nPhi, nTheta, lightL),
      this.panel.heldTexture("sh V", "grid", nPhi, nTheta, () => V)];
    this.pass = this.panel.draw("probe", nPhi, nTheta, { u_L: 0, u_V: 1 }, { textures });
  }

  collect() {
    this.probed = this.pass ? this.panel.collect(this.pass) : null;
  }

  /** Projects a new lobe (the values of fr cos θo on the grid) and draws. */
  process() {
    this.data = null;
    if (this.panel.model.delta) {
      this.draw();
      return;
    }
    const f = this.probed;
    if (f) {
      const { V, n } = quadrature();
      const C = this.env.C;
      const lobe = new Float64Array(n);
      for (let k = 0; k < n; k++) {
        const g = (C.LUMA[0] * f[4 * k] + C.LUMA[1] * f[4 * k + 1] + C.LUMA[2] * f[4 * k + 2]) * V[4 * k + 2];
        lobe[k] = Number.isFinite(g) ? g : 0; // a division by zero would swamp every coefficient
      }
      this.cache = { model: this.panel.model, key: this.key, ...analyse(lobe) };
      this.probed = null;
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
    const { ctx, px } = clearedPlot(canvas);
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

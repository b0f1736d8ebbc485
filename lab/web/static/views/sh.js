// The spherical-harmonics view, as the desktop's (lab/app/views/sh.py with lab/measured/sh.py):
// the lobe g(wo) = fr(wi, wo) cos θo for light 1, from the model's GLSL on a quadrature grid
// (the probe template), projected on real harmonics up to the highest order (lab/views/sh.py
// MAX_ORDER) as an odd function of z (../sh.js). Left: g and its series at order L in the plane of incidence; right: the
// relative L2 error over the hemisphere against the order.
import { formatG } from "../header.js";
import { clearedPlot } from "../plotscale.js";
import { el, setText, viewBox } from "../dom.js";
import { direction } from "../geometry.js";
import { analyse, count, grid, maxOrder, quadrature, realSh, useGrid } from "../sh.js";

const SERIES = "#ffd200";

export class SHView {
  constructor(panel) {
    this.panel = panel;
    this.lab = panel.lab;
    useGrid(this.lab.viewData("sh")); // lab/views/sh.py's highest order and grid
    const top = maxOrder();
    this.canvas = el("canvas", { class: "sh", width: 384, height: 220 });
    this.root = viewBox(this.canvas, "spherical harmonics", () => `${panel.name}_sh.png`);
    this.order = el("input", { type: "number", min: 0, max: top, step: 1, value: this.lab.settings.sh_order });
    this.order.addEventListener("input", () => {
      const value = Math.round(Number(this.order.value));
      if (!(value >= 0 && value <= top)) return;
      this.lab.set("sh_order", value);
      this.lab.requestRender();
    });
    this.note = el("div", { class: "view-note" });
    this.root.append(el("label", { class: "group", title: `the order L of the series (0 to ${top}): (L + 1)² coefficients` },
      "order L ", this.order), this.note);
    this.planeBasis = new Map(); // φi -> the harmonics in the plane of incidence
  }

  render() {
    this.submit();
    this.collect();
    this.process();
  }

  /** Queues the probe of the lobe on the quadrature grid, unless the series is cached. While
   * the hand moves (lab.fast) the projection waits, as on the desktop: the lobe in the plane
   * follows the slider, the series and its errors come when it stops (the probe and the
   * projection are most of this view's frame, and more than the sphere's). A model's first
   * series never waits (the page's first, coarse draw of its views shows it). */
  submit() {
    const lab = this.lab;
    if (Number(this.order.value) !== lab.settings.sh_order) this.order.value = lab.settings.sh_order;
    const light = lab.lights[0];
    this.pass = null;
    this.key = JSON.stringify([this.panel.values, light.theta, light.phi]);
    if (this.panel.model.delta || (this.cache?.model === this.panel.model && this.cache.key === this.key)) return;
    if (lab.fast && this.cache?.model === this.panel.model) return;
    const { V, n } = quadrature();
    const [nTheta, nPhi] = grid();
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
      const C = this.lab.constants;
      const lobe = new Float64Array(n);
      for (let k = 0; k < n; k++) {
        const g = (C.LUMA[0] * f[4 * k] + C.LUMA[1] * f[4 * k + 1] + C.LUMA[2] * f[4 * k + 2]) * V[4 * k + 2];
        lobe[k] = Number.isFinite(g) ? g : 0; // a division by zero would swamp every coefficient
      }
      this.cache = { model: this.panel.model, key: this.key, ...analyse(lobe) };
      this.probed = null;
    }
    // Not the cached series of other values: while the hand moves none (cleared, not stale).
    this.data = this.cache?.model === this.panel.model && this.cache.key === this.key ? this.cache : null;
    this.draw();
  }

  /** The harmonics at the polar plot's directions (θo = -90..90 in the plane of incidence
   * of azimuth φi, turned by φo). */
  plane(phiDeg, phiO) {
    const key = `${phiDeg},${phiO}`;
    if (!this.planeBasis.has(key)) {
      const rows = [];
      for (let t = -90; t <= 90; t++) {
        const [x, y, z] = direction(Math.abs(t), (t >= 0 ? phiDeg + 180 : phiDeg) + phiO);
        rows.push(realSh(maxOrder(), Math.acos(Math.min(Math.max(z, -1), 1)), Math.atan2(y, x)));
      }
      this.planeBasis.clear();
      this.planeBasis.set(key, rows);
    }
    return this.planeBasis.get(key);
  }

  draw() {
    const lab = this.lab;
    const C = lab.constants;
    const canvas = this.canvas;
    const { ctx, px } = clearedPlot(canvas);
    if (this.panel.model.delta) {
      ctx.fillText("an ideal mirror has no finite lobe to expand", 4, 2 * px);
      setText(this.note, "");
      return;
    }
    const order = lab.settings.sh_order;
    const light = lab.lights[0];
    // The lobe in the plane of incidence from the panel's polar plot probe (fr, 1° steps).
    const f = this.panel.lobe;
    const lum = (i) => (C.LUMA[0] * f[4 * i] + C.LUMA[1] * f[4 * i + 1] + C.LUMA[2] * f[4 * i + 2]) * Math.cos(((i - 90) * Math.PI) / 180);
    const plane = Array.from({ length: 181 }, (_, i) => (Number.isFinite(lum(i)) ? lum(i) : 0));
    const peak = Math.max(1e-9, ...plane.filter((_, i) => Math.abs(i - 90) <= C.GRAZING_DEG));
    const series = this.data ? this.plane(light.phi, lab.settings.phi_o).map((Y) => {
      let s = 0;
      for (let c = 0; c < count(order); c++) s += Y[c] * this.data.coefficients[c];
      return s;
    }) : null;
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
    ctx.fillText(`fᵣ cos θₒ, ${lab.settings.phi_o ? `plane turned φo = ${formatG(lab.settings.phi_o)}°` : "plane of incidence"}`, 2, px);
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
    ctx.fillStyle = this.panel.color;
    ctx.fillText("original (GLSL)", left + 4, top + 1.1 * px);
    if (!series) {
      const wait = "series and error follow when the slider stops";
      ctx.fillStyle = "#bbb";
      let line = "";
      let at = top + 1.1 * px;
      for (const word of wait.split(" ")) { // wrapped to the right part's width
        if (line && ctx.measureText(`${line} ${word}`).width > canvas.width - split - 8) {
          ctx.fillText(line, split + 4, at);
          [line, at] = [word, at + 1.1 * px];
        } else line = line ? `${line} ${word}` : word;
      }
      ctx.fillText(line, split + 4, at);
      setText(this.note, wait);
      return;
    }
    curve(series, SERIES, [6, 4]);
    ctx.fillStyle = SERIES;
    ctx.fillText(`SH series, L = ${order}`, left + 4, top + 2.2 * px);
    // Right: the error against the order, log scale.
    const errors = this.data.errors.map((e) => Math.max(e, 1e-6));
    const low = Math.floor(Math.log10(Math.min(...errors)));
    left = split + 3.2 * px;
    right = canvas.width - 6;
    const ex = (k) => left + ((right - left) * (k + 0.5)) / (maxOrder() + 1);
    const ey = (e) => top + ((bottom - top) * (0.2 - Math.log10(e))) / (0.2 - low);
    ctx.fillStyle = "#bbb";
    ctx.fillText("relative L2 error", split + 4, px);
    ctx.strokeStyle = "#666";
    ctx.strokeRect(left, top, right - left, bottom - top);
    ctx.textAlign = "right";
    const step = Math.max(1, Math.ceil(-low / 3));
    for (let k = 0; k >= low; k -= step) ctx.fillText(k ? `1e${k}` : "1", left - 3, ey(10 ** k) + 0.35 * px);
    ctx.textAlign = "center";
    for (const k of [0, Math.round(maxOrder() / 2), maxOrder()]) ctx.fillText(String(k), ex(k), bottom + 1.1 * px);
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
    setText(this.note, `L = ${order}: ${count(order)} coefficients, error ${formatG(Number((100 * this.data.errors[order]).toPrecision(2)))} %`);
  }

  /** Coefficients (luminance lobe), errors by order 0 to the highest, and the plane's curves. */
  read() {
    if (!this.data) return { coefficients: [], errors: [], plane: [], series: [] };
    return { coefficients: Array.from(this.data.coefficients), errors: this.data.errors, plane: this.planeValues, series: this.series };
  }
}

export const VIEW = { name: "sh", queue: 20, create: (panel) => new SHView(panel) };

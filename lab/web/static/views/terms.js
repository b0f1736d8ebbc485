// The microfacet terms on their own, as lab/views/terms.py draws them: D against θh (log),
// G against θo in light 1's plane of incidence, F against θd, from the model's own
// MICROFACET_TERMS through shaders/views/terms.glsl.
import { formatG } from "../header.js";
import { clearedPlot } from "../plotscale.js";
import { el, setText, viewBox } from "../dom.js";
import { direction } from "../geometry.js";

const TERMS_FUNCTION = /\bvoid\s+MICROFACET_TERMS\s*\(/;
const ANGLES = Array.from({ length: 91 }, (_, k) => k); // θh for D, θd for F (degrees)
export const hasTerms = (model) => TERMS_FUNCTION.test(model.code);

export class TermsView {
  constructor(panel) {
    this.panel = panel;
    this.lab = panel.lab;
    this.canvas = el("canvas", { class: "terms", width: 384, height: 200 });
    this.root = viewBox(this.canvas, "microfacet terms", () => `${panel.name}_terms.png`);
    this.note = el("div", { class: "view-note" });
    this.root.append(this.note);
  }

  /** The (L, V) pairs of the three families (lab/views/terms.py's term_pairs). */
  pairs() {
    const lab = this.lab;
    const { theta, phi } = lab.lights[0];
    const L = [];
    const V = [];
    for (const t of ANGLES) L.push(direction(t, phi)), V.push(direction(t, phi));
    for (let t = -90; t <= 90; t++) {
      L.push(direction(theta, phi));
      V.push(direction(Math.abs(t), t >= 0 ? phi + 180 : phi));
    }
    for (const t of ANGLES) L.push(direction(t, phi)), V.push(direction(t, phi + 180));
    return [L, V];
  }

  render() {
    this.submit();
    this.collect();
    this.process();
  }

  /** Queues the two passes (D and G; F) on direction textures kept while light 1 stays
   * (a moving parameter uploads nothing); both are read back after the other views queued
   * theirs. */
  submit() {
    this.passes = null;
    if (!hasTerms(this.panel.model)) return;
    const { theta, phi } = this.lab.lights[0];
    const n = 2 * ANGLES.length + 181;
    const texture = (which) => this.panel.heldTexture(`terms ${which}`, `${theta},${phi}`, n, 1, () => {
      const data = new Float32Array(4 * n);
      this.pairs()[which].forEach((d, k) => data.set(d, 4 * k));
      return data;
    });
    const textures = [texture(0), texture(1)];
    this.passes = [0, 1].map((part) => this.panel.draw("terms", n, 1, { u_L: 0, u_V: 1, u_part: part },
      { textures, tag: `terms ${part}` }));
  }

  collect() {
    this.parts = this.passes ? this.passes.map((pass) => this.panel.collect(pass)) : null;
  }

  process() {
    this.terms = null;
    if (this.parts) {
      const parts = this.parts;
      const k = ANGLES.length;
      const m = k + 181;
      this.terms = {
        theta: ANGLES,
        D: ANGLES.map((_, i) => parts[0][4 * i]),
        theta_o: Array.from({ length: 181 }, (_, i) => i - 90),
        G: Array.from({ length: 181 }, (_, i) => parts[0][4 * (k + i) + 1]),
        F: ANGLES.map((_, i) => Array.from(parts[1].subarray(4 * (m + i), 4 * (m + i) + 3))),
      };
    }
    this.draw();
  }

  draw() {
    const lab = this.lab;
    const C = lab.constants;
    const canvas = this.canvas;
    const { ctx, px } = clearedPlot(canvas);
    if (!this.terms) {
      ctx.fillText("no separate D, G and F:", 4, 2 * px);
      // A measured table cannot define them (as lab/measured/model.py's no_terms_reason).
      const table = Boolean(this.panel.model.table);
      ctx.fillText(table ? "a measured table" : "not written as a microfacet model", 4, 3.3 * px);
      setText(this.note, table
        ? `${this.panel.name}: a measured table has no D, G and F of its own: fit a microfacet model to it (brdf-lab fit) and view the fit's terms`
        : `${this.panel.name} does not define MICROFACET_TERMS (see shaders/README.md)`);
      return;
    }
    const t = this.terms;
    const color = this.panel.color;
    const width = canvas.width / 3;
    const top = 2.4 * px;
    const bottom = canvas.height - 2.6 * px;
    // One small plot: x over [x0, x1], y by `scale` (0 at the bottom, 1 at the top).
    const plot = (slot, title, label, x0, x1, xs, ys, scale, ticks, strokes = [[color, []]]) => {
      const room = Math.max(...ticks.map(([, text]) => ctx.measureText(text).width));
      const left = slot * width + room + 6;
      const right = (slot + 1) * width - 0.9 * px;
      const X = (x) => left + ((right - left) * (x - x0)) / (x1 - x0);
      const Y = (v) => bottom - (bottom - top) * Math.min(Math.max(scale(v), 0), 1);
      ctx.fillStyle = "#bbb";
      ctx.textAlign = "left";
      ctx.fillText(title, slot * width + 4, px);
      ctx.strokeStyle = "#666";
      ctx.lineWidth = 1;
      ctx.strokeRect(left, top, right - left, bottom - top);
      ctx.textAlign = "center";
      ctx.textAlign = "left";
      ctx.fillText(`${x0}°`, left, bottom + 1.1 * px);
      ctx.textAlign = "right";
      ctx.fillText(`${x1}°`, right, bottom + 1.1 * px);
      ctx.textAlign = "center";
      ctx.fillText(label, (left + right) / 2, bottom + 2.3 * px);
      ctx.textAlign = "right";
      for (const [v, text] of ticks) ctx.fillText(text, left - 2, Y(v) + 0.35 * px);
      ctx.textAlign = "left";
      strokes.forEach(([stroke, dash], c) => {
        ctx.strokeStyle = stroke;
        ctx.lineWidth = 1.8;
        ctx.setLineDash(dash);
        ctx.beginPath();
        let drawing = false;
        xs.forEach((x, i) => {
          const y = strokes.length > 1 ? ys[i][c] : ys[i];
          if (!Number.isFinite(y) || (scale.log && !(y > 0))) {
            drawing = false;
            return;
          }
          ctx[drawing ? "lineTo" : "moveTo"](X(x), Y(y));
          drawing = true;
        });
        ctx.stroke();
        ctx.setLineDash([]);
      });
      return X;
    };
    // D on a log scale: C.PLOT_DECADES + 1 decades below its largest finite value.
    const finite = t.D.filter((d) => Number.isFinite(d) && d > 0);
    const high = 10 ** Math.ceil(Math.log10(Math.max(...finite, 1e-6)));
    const decades = C.PLOT_DECADES + 1;
    const logScale = (v) => (Math.log10(v / high) + decades) / decades;
    logScale.log = true;
    plot(0, "D (sr⁻¹, log)", "θh: N to H", 0, 90, t.theta, t.D, logScale,
      [[high, formatG(high)], [high / 10 ** decades, formatG(high / 10 ** decades)]]);
    const unit = (v) => v / 1.05;
    const X = plot(1, `G, light at θi = ${formatG(lab.lights[0].theta)}°`, "θo (R dashed)", -90, 90, t.theta_o, t.G, unit,
      [[0, "0"], [1, "1"]]);
    ctx.strokeStyle = "#78c8ff";
    ctx.setLineDash([4, 4]);
    ctx.beginPath();
    ctx.moveTo(X(lab.lights[0].theta), top);
    ctx.lineTo(X(lab.lights[0].theta), bottom);
    ctx.stroke();
    ctx.setLineDash([]);
    const same = t.F.every(([r, g, b]) => r === g && g === b);
    // F of a grey f0 as one curve in the model's colour; a coloured one (a metal) per channel.
    plot(2, same ? "F" : "F (R, G, B)", "θd: V to H", 0, 90, t.theta, same ? t.F.map((f) => f[0]) : t.F, unit,
      [[0, "0"], [1, "1"]], same ? [[color, []]] : [["#ff5050", []], ["#50d050", [5, 3]], ["#6090ff", [2, 3]]]);
    const peak = Math.max(...finite);
    setText(this.note, `D peaks at ${formatG(Number(peak.toPrecision(3)))} sr⁻¹ (G = 1 means no shadowing or masking); ` +
      `F(0°) = ${t.F[0].map((c) => formatG(Number(c.toPrecision(3)))).join(", ")}`);
  }

  /** The terms ({theta, D, theta_o, G, F}), or null for a model without them. */
  read() {
    return this.terms ?? { theta: [], D: [], theta_o: [], G: [], F: [] };
  }
}

export const VIEW = { name: "terms", queue: 10, create: (panel) => new TermsView(panel) };

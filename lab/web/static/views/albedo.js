// Directional albedo against θi with energy gain flagged, from shaders/views/albedo.glsl:
// the GPU integrates wedges around the mirror direction, the host sums them.
import { formatG } from "../header.js";
import { font } from "../plotscale.js";
import { el, setText, viewBox } from "../dom.js";

// Its quality (θi from theta0 in count steps of step degrees, samples along each of wedges
// wedges around the mirror direction; fast while a slider or the light moves) is the
// desktop's, lab/views/albedo.py FULL and FAST, sent as the view's page data.

/** Directional albedo against θi, energy gain (albedo > 1) flagged in red. */
export class AlbedoView {
  constructor(panel) {
    this.panel = panel;
    this.lab = panel.lab;
    this.canvas = el("canvas", { class: "albedo", width: 384, height: 240 });
    this.root = viewBox(this.canvas, "albedo", () => `${panel.name}_albedo.png`);
    this.note = el("div", { class: "view-note" });
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
    const lab = this.lab;
    const { full, fast } = lab.viewData("albedo");
    const a = (this.quality = lab.fast ? fast : full);
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
    setText(this.note, this.gain ? "energy gain: the albedo exceeds 1 (×), more light leaves than arrives" : "");
    this.note.classList.toggle("bad", this.gain);
  }

  read() {
    return { thetas: this.thetas, rgb: this.rgb, gain: this.gain };
  }
}

export const VIEW = { name: "albedo", queue: 50, create: (panel) => new AlbedoView(panel) };

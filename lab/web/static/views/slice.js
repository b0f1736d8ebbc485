// The (θh, θd) slice of BRDF Explorer: f_r over the half and difference angles at the
// page's φd (setting phi_d), from shaders/views/slice.glsl as the desktop draws it.
import { formatG } from "../header.js";
import { font } from "../plotscale.js";
import { el, viewBox } from "../dom.js";
import { toImage, topFirst } from "../viewkit.js";

// While a slider or the light moves: a smaller slice; the full one once the hand stops.
export const SLICE_FAST = 96;
export const SLICE_MAX = 256;

/** f_r over (θh, θd) at the page's φd. */
export class SliceView {
  constructor(panel) {
    this.panel = panel;
    this.lab = panel.lab;
    this.canvas = el("canvas", { class: "slice", width: 384, height: 384 });
    this.root = viewBox(this.canvas, "slice", () => `${panel.name}_slice.png`);
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
    const lab = this.lab;
    const n = Math.min(lab.size, lab.fast ? SLICE_FAST : SLICE_MAX);
    this.size = n;
    this.pass = this.panel.draw("slice", n, n, { u_resolution: [n, n], u_phi_d: (lab.settings.phi_d * Math.PI) / 180 });
  }

  collect() {
    this.data = this.panel.collect(this.pass);
  }

  process() {
    const lab = this.lab;
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
    const image = toImage(this.data, n, n, lab.settings.exposure);
    const scratch = new OffscreenCanvas(n, n);
    scratch.getContext("2d").putImageData(image, 0, 0);
    ctx.imageSmoothingEnabled = false;
    ctx.drawImage(scratch, left, top, side, side);
    ctx.fillStyle = "#bbb";
    ctx.fillText(`fᵣ(θh, θd) at φd = ${formatG(lab.settings.phi_d)}°`, 2, f);
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

export const VIEW = { name: "slice", queue: 40, toolbar: ["phi_d"], create: (panel) => new SliceView(panel) };

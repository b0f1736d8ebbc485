// The test-only retroreflection view on the page: f_r(ω, ω) against θ (light and eye
// together) from the model's own GLSL through the probe template, one bar per degree,
// scaled by its setting retro_gain. Registered as retro.py is: by being here.
import { floatTexture } from "../assemble.js";
import { el, viewBox } from "../dom.js";
import { direction } from "../geometry.js";

const THETAS = Array.from({ length: 90 }, (_, k) => k);

class RetroView {
  constructor(panel) {
    this.panel = panel;
    this.lab = panel.lab;
    this.canvas = el("canvas", { class: "retro", width: 180, height: 100 });
    this.root = viewBox(this.canvas, "retroreflection", () => `${panel.name}_retro.png`);
  }

  render() {
    const lab = this.lab;
    const gl = this.panel.gl;
    const phi = lab.lights[0].phi;
    const data = new Float32Array(4 * THETAS.length);
    THETAS.forEach((t) => data.set(direction(t, phi), 4 * t));
    const texture = floatTexture(gl, THETAS.length, 1, data);
    const out = this.panel.run("probe", THETAS.length, 1, { u_L: 0, u_V: 0 }, { textures: [texture] });
    gl.deleteTexture(texture);
    const [r, g, b] = lab.constants.LUMA;
    this.lum = THETAS.map((t) => lab.settings.retro_gain * (r * out[4 * t] + g * out[4 * t + 1] + b * out[4 * t + 2]));
    const ctx = this.canvas.getContext("2d");
    const top = Math.max(...this.lum, 1e-12);
    ctx.clearRect(0, 0, this.canvas.width, this.canvas.height);
    ctx.fillStyle = this.panel.color;
    this.lum.forEach((f, t) => ctx.fillRect(2 * t, 100 - (100 * f) / top, 2, (100 * f) / top));
  }

  read() {
    return { thetas: THETAS, lum: this.lum };
  }
}

export const VIEW = { name: "retro", toolbar: ["retro_gain"], create: (panel) => new RetroView(panel) };

// A view added by a test: f_r over the hemisphere of view directions for light 1, from its
// template shaders/views/hemi.glsl, times its setting hemi_gain.
import { el, viewBox } from "../dom.js";
import { direction } from "../geometry.js";
import { toImage, topFirst } from "../viewkit.js";

const SIZE = 64;

class HemiView {
  constructor(panel) {
    this.panel = panel;
    this.lab = panel.lab;
    this.canvas = el("canvas", { class: "hemi", width: SIZE, height: SIZE });
    this.root = viewBox(this.canvas, "hemisphere", () => `${panel.name}_hemi.png`);
  }

  render() {
    const lab = this.lab;
    const { theta, phi } = lab.lights[0];
    this.data = this.panel.run("hemi", SIZE, SIZE, { u_resolution: [SIZE, SIZE], u_light: direction(theta, phi),
      u_gain: lab.settings.hemi_gain });
    this.canvas.getContext("2d").putImageData(toImage(this.data, SIZE, SIZE, lab.settings.exposure), 0, 0);
  }

  read() {
    return { width: SIZE, height: SIZE, data: topFirst(this.data, SIZE, SIZE) };
  }
}

export const VIEW = { name: "hemi", toolbar: ["hemi_gain"], create: (panel) => new HemiView(panel) };

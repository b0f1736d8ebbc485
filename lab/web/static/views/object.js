// The procedural object lit by every light, with the lecture's spatially varying steps
// (settings shape and mode), ray-marched by shaders/views/object.glsl; drag to orbit
// (settings yaw and pitch).
import { el, viewBox } from "../dom.js";
import { direction } from "../geometry.js";
import { toImage, topFirst } from "../viewkit.js";

// The object is ray-marched (about 1 µs a pixel on SwiftShader): at most 96 px square while
// the hand moves, the full render once it stops.
export const OBJECT_FAST = 96;

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

/** The procedural object lit by every light, with the lecture's spatially varying steps;
 * drag on it to orbit. */
export class ObjectView {
  constructor(panel) {
    this.panel = panel;
    this.lab = panel.lab;
    const size = panel.lab.size;
    this.canvas = el("canvas", { class: "object", width: size, height: size });
    this.root = viewBox(this.canvas, "object", () => `${panel.name}_object.png`);
    this.canvas.addEventListener("pointerdown", (e) => {
      this.canvas.setPointerCapture(e.pointerId);
      this.drag = [e.clientX, e.clientY];
    });
    this.canvas.addEventListener("pointermove", (e) => {
      if (!this.drag || !e.buttons) return;
      const rect = this.canvas.getBoundingClientRect();
      const lab = this.lab;
      lab.set("yaw", lab.settings.yaw + ((e.clientX - this.drag[0]) / rect.width) * Math.PI);
      lab.set("pitch", lab.settings.pitch + ((e.clientY - this.drag[1]) / rect.height) * Math.PI);
      this.drag = [e.clientX, e.clientY];
      lab.requestRender();
    });
    this.canvas.addEventListener("pointerup", () => (this.drag = null));
  }

  render() {
    this.submit();
    this.collect();
    this.process();
  }

  submit() {
    const lab = this.lab;
    const C = lab.constants;
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
      u_resolution: [n, n], u_light_dir: dirs, u_light_rgb: rgb, u_ambient: lab.ambient, u_yaw: lab.settings.yaw, u_pitch: lab.settings.pitch,
    }, { preamble: this.preamble(), transform: objectProgram, suffix: "_base" });
  }

  /** The shape and the step are constants of the program (one per choice), not uniforms. */
  preamble() {
    const lab = this.lab;
    return [`const int LIGHT_COUNT = ${lab.lights.length};`,
      `const int u_shape = ${Math.trunc(lab.settings.shape) || 0};`, `const int u_mode = ${Math.trunc(lab.settings.mode) || 0};`].join("\n");
  }

  warm() {
    this.panel.program("object", this.preamble(), objectProgram, { start: true });
  }

  collect() {
    this.data = this.panel.collect(this.pass);
  }

  process() {
    const lab = this.lab;
    const n = this.size;
    const ctx = this.canvas.getContext("2d");
    if (n === this.canvas.width) ctx.putImageData(toImage(this.data, n, n, lab.settings.exposure), 0, 0);
    else {
      const scratch = new OffscreenCanvas(n, n);
      scratch.getContext("2d").putImageData(toImage(this.data, n, n, lab.settings.exposure), 0, 0);
      ctx.clearRect(0, 0, this.canvas.width, this.canvas.height);
      ctx.drawImage(scratch, 0, 0, this.canvas.width, this.canvas.height);
    }
  }

  read() {
    return { width: this.size, height: this.size, data: topFirst(this.data, this.size, this.size) };
  }
}

export const VIEW = { name: "object", queue: 60, toolbar: ["shape", "mode"], create: (panel) => new ObjectView(panel) };

// The tables exercise 12's checks read (their `table` key, lab/grading/tables.py), made by
// the page on the panel's GPU as the grader makes them: the library model's own shader at
// every bin centre, times tabulate.py's counter-based noise (shaders/views/tabulate.glsl),
// one theta_h layer per draw straight into a 3D float texture, bound to the check's sampler
// as the grader binds it. Why not the grader's table itself: it is 1.46 M bins (17 MB) per
// check, while its recipe is a few numbers; tests/test_web_tables.py holds the page's table
// and verdicts to the grader's.
import { defaults } from "./header.js";
import { assembleFragment } from "./assemble.js";
import { compile, setUniform } from "./glkit.js";

/** The table a check reads in reference mode (the first of its list), or null. */
export const tableOf = (check) => (check.table?.length ? check.table[0] : null);

const keyOf = (spec) => JSON.stringify([spec.model, spec.params, spec.noise, spec.dims]);

/** The library model's values with the table's parameters (colours as arrays). */
function tableValues(model, spec) {
  const values = defaults(model);
  for (const [name, value] of spec.params) values[name] = Array.isArray(value) ? [...value] : value;
  return values;
}

/** Renders `spec`'s table into a new RGBA32F 3D texture (phi_d, theta_d, theta_h) on
 * `panel`'s context; throws an Error in words where the model or the browser cannot. */
export function buildTable(panel, spec) {
  const { gl, lab } = panel;
  const model = lab.models[spec.model];
  if (!model) throw new Error(`the table's model ${spec.model} is not among the page's models`);
  const [nH, nD, nP] = spec.dims;
  const limit = gl.getParameter(gl.MAX_3D_TEXTURE_SIZE);
  if (Math.max(nH, nD, nP) > limit) {
    throw new Error(`the table has (${spec.dims.join(", ")}) bins; this browser takes at most ${limit} per axis of a 3D texture`);
  }
  const values = tableValues(model, spec);
  const enums = Object.fromEntries(model.params.filter((p) => p.kind === "enum").map((p) => [p.name, values[p.name]]));
  // The grader's cos and sin (exactTrig), as a submission is drawn with.
  const source = assembleFragment({ ...model, exactTrig: true }, "tabulate", lab.files,
    { target: "300es", enums, constants: lab.constants });
  const compiled = compile(gl, source.text, source);
  const texture = gl.createTexture();
  gl.bindTexture(gl.TEXTURE_3D, texture);
  gl.texStorage3D(gl.TEXTURE_3D, 1, gl.RGBA32F, nP, nD, nH);
  gl.texParameteri(gl.TEXTURE_3D, gl.TEXTURE_MIN_FILTER, gl.NEAREST);
  gl.texParameteri(gl.TEXTURE_3D, gl.TEXTURE_MAG_FILTER, gl.NEAREST);
  gl.bindTexture(gl.TEXTURE_3D, null);
  const fbo = gl.createFramebuffer();
  try {
    gl.useProgram(compiled.program);
    gl.bindVertexArray(panel.vao);
    for (const p of model.params) {
      if (p.kind === "float") setUniform(gl, compiled, p.name, values[p.name]);
      else if (p.kind === "color") setUniform(gl, compiled, p.name, values[p.name]);
      else if (p.kind === "bool") setUniform(gl, compiled, p.name, values[p.name] ? 1 : 0);
    }
    setUniform(gl, compiled, "u_dims", [nH, nD, nP]);
    setUniform(gl, compiled, "u_noise", spec.noise);
    setUniform(gl, compiled, "u_seed", 0); // the grader's (tables.py: measure's default)
    gl.bindFramebuffer(gl.FRAMEBUFFER, fbo);
    gl.drawBuffers([gl.COLOR_ATTACHMENT0]);
    gl.viewport(0, 0, nP, nD);
    for (let layer = 0; layer < nH; layer++) {
      gl.framebufferTextureLayer(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, texture, 0, layer);
      if (layer === 0 && gl.checkFramebufferStatus(gl.FRAMEBUFFER) !== gl.FRAMEBUFFER_COMPLETE) {
        throw new Error("this browser cannot render into a 3D float texture (EXT_color_buffer_float)");
      }
      setUniform(gl, compiled, "u_layer", layer);
      gl.drawArrays(gl.TRIANGLES, 0, 3);
    }
  } catch (err) {
    gl.deleteTexture(texture);
    throw err;
  } finally {
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    gl.deleteFramebuffer(fbo);
    gl.deleteProgram(compiled.program);
  }
  return texture;
}

/** The tables of an exercise's checks on one panel, and the one its draws read now. */
export class Tables {
  constructor(panel, checks) {
    this.panel = panel;
    this.specs = new Map();
    for (const check of checks) {
      const spec = tableOf(check);
      if (spec) this.specs.set(keyOf(spec), spec);
    }
    this.textures = new Map();
    this.error = null;
    this.current = null;
    this.ms = 0;
  }

  get needed() {
    return this.specs.size > 0;
  }

  /** Makes every table (once); an error is kept in words, for the checks to report. */
  build() {
    const start = performance.now();
    try {
      for (const [key, spec] of this.specs) {
        if (!this.textures.has(key)) this.textures.set(key, buildTable(this.panel, spec));
      }
      this.panel.gl.finish(); // the time measured is the GPU's too
    } catch (err) {
      if (!(err instanceof Error)) throw err;
      this.error = `the page cannot make the table this check reads: ${err.message}`;
    }
    this.ms = performance.now() - start;
    // The panel's own pictures read the first table (the checks pick theirs).
    this.current = this.textures.keys().next().value ?? null;
  }

  /** Draws read `check`'s table until the next use(); false where it could not be made. */
  use(check) {
    const spec = tableOf(check);
    if (!spec) return true;
    const key = keyOf(spec);
    this.current = key;
    return this.textures.has(key);
  }

  /** `model` (a submission) binding the current table to each program that reads it. */
  bindTo(model) {
    if (!this.needed) return model;
    model.bind = (gl, compiled) => {
      const unit = this.panel.lab.measuredTable.unit; // the grader's unit for tables
      const texture = this.textures.get(this.current);
      const spec = this.specs.get(this.current);
      if (!texture || !(spec.uniform in compiled.uniforms)) return;
      gl.activeTexture(gl.TEXTURE0 + unit);
      gl.bindTexture(gl.TEXTURE_3D, texture);
      gl.uniform1i(compiled.uniforms[spec.uniform], unit);
      gl.activeTexture(gl.TEXTURE0);
    };
    return model;
  }

  /** The RGBA texels of theta_h layers `layers` of `check`'s table, layer after layer
   * (phi_d fastest): the tests compare them with the grader's table. */
  texels(check, layers) {
    const gl = this.panel.gl;
    const [, nD, nP] = tableOf(check).dims;
    const texture = this.textures.get(keyOf(tableOf(check)));
    const out = new Float32Array(4 * nP * nD * layers.length);
    const fbo = gl.createFramebuffer();
    gl.bindFramebuffer(gl.FRAMEBUFFER, fbo);
    layers.forEach((layer, k) => {
      gl.framebufferTextureLayer(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, texture, 0, layer);
      gl.readPixels(0, 0, nP, nD, gl.RGBA, gl.FLOAT, out.subarray(4 * nP * nD * k, 4 * nP * nD * (k + 1)));
    });
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    gl.deleteFramebuffer(fbo);
    return out;
  }

  release() {
    const gl = this.panel?.gl; // none: the panel went, and its textures with it
    for (const texture of this.textures.values()) gl?.deleteTexture(texture);
    this.textures.clear();
  }
}

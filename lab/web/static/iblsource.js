// What the web lab's IBL view (ibl.js) and the deck's Monte Carlo demo (ibl_demo.js) share:
// the program (the model in the lab's IBL template, with the sampling terms, the model's
// BRDF sampler and the environment terms put before the view, as lab/ibl/integrator.py
// assembles it) and the environment (the lab's procedural maps, served as
// environments/NAME.f32, with their sampling tables and textures).
import { assembleFragment } from "./assemble.js";

// As lab/ibl/integrator.py STRATEGIES (the index is the shader's u_strategy; "auto" is
// resolved per map before a pass, by the manifest's environments.auto).
export const STRATEGIES = ["uniform", "cosine", "environment", "brdf", "mis_balance", "mis_power", "auto"];
export const STRATEGY_TITLES = {
  uniform: "uniform hemisphere",
  cosine: "cosine-weighted",
  environment: "environment (CDF over the map)",
  brdf: "BRDF importance",
  mis_balance: "MIS, balance heuristic",
  mis_power: "MIS, power heuristic",
  auto: "auto: BRDF under uniform light, else MIS (power)",
};

/** The strategy a pass runs: "auto" resolved for the map as lab/ibl/integrator.py
 * chosen_strategy does (`info` is the manifest's environments, with its `auto` per map). */
export function chosenStrategy(strategy, environment, info) {
  return strategy === "auto" ? info.auto?.[environment] ?? "mis_power" : strategy;
}
const NO_SAMPLER = `const bool HAS_SAMPLER = false;
vec3 SAMPLE_BRDF(vec3 V, vec3 N, vec3 X, vec3 Y, vec3 u) { return N; }
float PDF_BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) { return 0.0; }`;

/** The model's BRDF sampler file text, or null (opened files, exercises, models without
 * one), as lab/ibl/integrator.py sampler_path decides. */
export function samplerText(model, files) {
  const text = files[`samplers/${model.name}.glsl`];
  return text !== undefined && model.path === `shaders/brdfs/${model.name}.glsl` ? text : null;
}

/** Puts `chunks` ([text, file label] each, in order) between the model and the IBL view
 * template of `source`, as lab/ibl/integrator.py insert_before_view does. */
export function insertBeforeView(source, chunks) {
  const marker = source.lines.lastIndexOf("#define main lab_view_main");
  const start = marker >= 0 ? marker : source.origins.findIndex(([f]) => f === "shaders/views/ibl.glsl");
  const lines = [];
  const origins = [];
  for (const [text, label] of chunks) {
    text.replace(/\r\n?/g, "\n").replace(/\n$/, "").split("\n").forEach((line, k) => {
      lines.push(line);
      origins.push([label, k + 1]);
    });
  }
  source.lines.splice(start, 0, ...lines);
  source.origins.splice(start, 0, ...origins);
}

/** Puts the sampling terms, the model's sampler and the environment terms (the Monte Carlo
 * estimator) between the model and the template, as lab/ibl/integrator.py does. */
export function withSampler(files) {
  return (source, model) => {
    const sampler = samplerText(model, files);
    insertBeforeView(source, [
      [files["terms/sampling.glsl"], "shaders/terms/sampling.glsl"],
      [sampler ?? NO_SAMPLER, sampler === null ? "<no sampler>" : `shaders/samplers/${model.name}.glsl`],
      [files["terms/environment.glsl"], "shaders/terms/environment.glsl"], // the estimator
    ]);
  };
}

/** The IBL fragment shader of a model (a Source, lines mapped to their files). */
export function iblSource(model, files, options) {
  const source = assembleFragment(model, "ibl", files, options);
  withSampler(files)(source, model);
  return source;
}

/** Importance sampling by luminance times sin θ (environments.sampling_tables): the
 * density over (u, v), the CDF over rows and one CDF over the columns of each row. */
export function samplingTables(image, width, height, luma) {
  const weight = new Float64Array(width * height);
  let sum = 0;
  for (let j = 0; j < height; j++) {
    const s = Math.sin(((j + 0.5) / height) * Math.PI);
    for (let i = 0; i < width; i++) {
      const k = j * width + i;
      const y = luma[0] * image[3 * k] + luma[1] * image[3 * k + 1] + luma[2] * image[3 * k + 2];
      weight[k] = Math.max(y, 0) * s;
      sum += weight[k];
    }
  }
  const sinRow = (j) => Math.sin(((j + 0.5) / height) * Math.PI);
  if (sum <= 0) for (let k = 0; k < weight.length; k++) weight[k] = sinRow(Math.floor(k / width));
  let total = 0;
  for (let k = 0; k < weight.length; k++) total += weight[k];
  const floor = (1e-4 * total) / weight.length; // keeps every pixel reachable
  for (let k = 0; k < weight.length; k++) weight[k] += floor * sinRow(Math.floor(k / width));
  total = 0;
  const rows = new Float64Array(height);
  for (let j = 0; j < height; j++) {
    for (let i = 0; i < width; i++) rows[j] += weight[j * width + i];
    total += rows[j];
  }
  const marginal = new Float32Array(height + 1);
  let run = 0;
  for (let j = 0; j < height; j++) marginal[j + 1] = (run += rows[j]) / total;
  marginal[height] = 1;
  const conditional = new Float32Array((width + 1) * height);
  const density = new Float32Array(width * height);
  for (let j = 0; j < height; j++) {
    let acc = 0;
    const last = Math.max(rows[j], 1e-300);
    for (let i = 0; i < width; i++) {
      acc += weight[j * width + i];
      conditional[j * (width + 1) + i + 1] = acc / last;
      density[j * width + i] = (weight[j * width + i] / total) * width * height;
    }
    conditional[j * (width + 1) + width] = 1;
  }
  return { density, marginal, conditional };
}

const maps = new Map(); // environment name -> Promise of {image, width, height, tables}

/** The environment's radiance (float32 RGB, row 0 the zenith) and its sampling tables. */
export function loadEnvironment(name, info, luma) {
  if (!maps.has(name)) {
    maps.set(name, fetch(`environments/${name}.f32`).then(async (response) => {
      if (!response.ok) throw new Error(`cannot load environments/${name}.f32 (HTTP ${response.status})`);
      const image = new Float32Array(await response.arrayBuffer());
      const { width, height } = info;
      if (image.length !== width * height * 3) throw new Error(`environments/${name}.f32 is not ${width}x${height} RGB floats`);
      return { image, width, height, tables: samplingTables(image, width, height, luma) };
    }));
  }
  return maps.get(name);
}

function texture(gl, format, width, height, data) {
  const t = gl.createTexture();
  gl.bindTexture(gl.TEXTURE_2D, t);
  const external = format === gl.RGB32F ? gl.RGB : gl.RED;
  gl.texImage2D(gl.TEXTURE_2D, 0, format, width, height, 0, external, gl.FLOAT, data);
  gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.NEAREST);
  gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.NEAREST);
  gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_WRAP_S, gl.CLAMP_TO_EDGE);
  gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_WRAP_T, gl.CLAMP_TO_EDGE);
  return t;
}

/** The four textures of the IBL template's environment (terms/environment.glsl): radiance,
 * density, the CDF over rows and the CDFs over each row's columns; and the map's size. */
export function environmentTextures(gl, map) {
  const { width: w, height: h, tables } = map;
  return {
    list: [texture(gl, gl.RGB32F, w, h, map.image), texture(gl, gl.R32F, w, h, tables.density),
      texture(gl, gl.R32F, h + 1, 1, tables.marginal), texture(gl, gl.R32F, w + 1, h, tables.conditional)],
    size: [w, h],
  };
}

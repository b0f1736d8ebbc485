// Measured BRDFs in the page: a MERL .binary table read as lab/measured/merl.py reads it
// (same checks, same messages) and drawn by the desktop's own model file
// (lab/measured/measured.glsl, from the manifest), whose lookup is 8 texelFetches: a float
// 3D texture needs no filtering extension that way.
// Why in JavaScript too: a table opened in the page never reaches Python.
import { ModelError, parseModel } from "./header.js";
import { parseBrdf } from "./explorer.js";

// The format's numbers are lab/measured/merl.py's and model.py's, the manifest's
// measured_table: header_bytes, max_dim (a header larger than this is not a BRDF table but
// a misread file), dims (MERL's own), scale (stored value x scale = f_r in 1/sr, R, G, B)
// and unit (the table's texture unit).

const tuple = (dims) => `(${dims.join(", ")})`;

/** The table of a .binary file: {dims: [n_h, n_d, n_p], texels: RGB float32 in the
 * texture's order (phi_d fastest), unmeasured values as 0}, read by `format` (the
 * manifest's measured_table). Throws ModelError. */
export function parseMerl(buffer, path, format) {
  const { header_bytes: HEADER_BYTES, max_dim: MAX_DIM, dims: MERL_DIMS, scale: SCALE } = format;
  const size = buffer.byteLength;
  if (size < HEADER_BYTES) {
    throw new ModelError(`file has ${size} bytes, too short for the 12-byte header: not a MERL .binary`, path);
  }
  const view = new DataView(buffer);
  const dims = [0, 4, 8].map((offset) => view.getInt32(offset, true));
  if (dims.some((n) => n < 1 || n > MAX_DIM)) {
    throw new ModelError(`header gives dimensions ${tuple(dims)}, expected ${tuple(MERL_DIMS)} (theta_h, theta_d, ` +
      "phi_d): not a MERL .binary file (or a big-endian one)", path);
  }
  const count = dims[0] * dims[1] * dims[2];
  const expected = HEADER_BYTES + 3 * 8 * count;
  if (size !== expected) {
    const what = size < expected ? "truncated" : "has extra bytes";
    throw new ModelError(`file ${what}: the header's dimensions ${tuple(dims)} need ${expected} bytes, the file has ` +
      `${size}; download it again or regenerate it with 'brdf-lab tabulate'`, path);
  }
  const texels = new Float32Array(3 * count);
  let bad = 0;
  let first = null;
  for (let c = 0; c < 3; c++) {
    const start = HEADER_BYTES + 8 * c * count;
    for (let i = 0; i < count; i++) {
      const v = view.getFloat64(start + 8 * i, true);
      if (!Number.isFinite(v)) {
        bad++;
        first ??= [c, i];
        continue;
      }
      texels[3 * i + c] = v > 0 ? v * SCALE[c] : 0;
    }
  }
  if (bad) {
    const [c, i] = first;
    const [h, d, p] = [Math.floor(i / (dims[1] * dims[2])), Math.floor(i / dims[2]) % dims[1], i % dims[2]];
    throw new ModelError(`${bad} value(s) are NaN or infinite, the first in channel ${"RGB"[c]} at bin ` +
      `(theta_h ${h}, theta_d ${d}, phi_d ${p}); mark missing samples with a negative value instead`, path);
  }
  return { dims, texels, path, unit: format.unit };
}

/** The measured model for a table: the header and GLSL of measured.glsl (`code`), named
 * after the file as in the desktop lab; `bind(gl, compiled)` gives the shader its table. */
export function measuredModel(table, code, name) {
  const model = parseModel(code, "lab/measured/measured.glsl", "measured");
  model.name = name;
  model.title = `Measured BRDF: ${table.path} (a table of ${tuple(table.dims)} bins)`;
  model.table = table;
  const textures = new WeakMap(); // one texture per WebGL context (each panel has its own)
  model.bind = (gl, compiled) => {
    if (!("u_measured" in compiled.uniforms)) return;
    const TABLE_UNIT = table.unit;
    let texture = textures.get(gl);
    if (!texture) {
      const [n_h, n_d, n_p] = table.dims;
      const limit = gl.getParameter(gl.MAX_3D_TEXTURE_SIZE);
      if (Math.max(n_h, n_d, n_p) > limit) {
        throw new ModelError(`the table has ${tuple(table.dims)} bins; this browser takes at most ${limit} per axis ` +
          "of a 3D texture: resample it", table.path);
      }
      texture = gl.createTexture();
      gl.activeTexture(gl.TEXTURE0 + TABLE_UNIT);
      gl.bindTexture(gl.TEXTURE_3D, texture);
      gl.pixelStorei(gl.UNPACK_ALIGNMENT, 4);
      gl.texImage3D(gl.TEXTURE_3D, 0, gl.RGB32F, n_p, n_d, n_h, 0, gl.RGB, gl.FLOAT, table.texels);
      // Float textures filter only with an extension: the shader fetches texels itself.
      gl.texParameteri(gl.TEXTURE_3D, gl.TEXTURE_MIN_FILTER, gl.NEAREST);
      gl.texParameteri(gl.TEXTURE_3D, gl.TEXTURE_MAG_FILTER, gl.NEAREST);
      textures.set(gl, texture);
    }
    gl.activeTexture(gl.TEXTURE0 + TABLE_UNIT);
    gl.bindTexture(gl.TEXTURE_3D, texture);
    gl.uniform1i(compiled.uniforms.u_measured, TABLE_UNIT);
    gl.activeTexture(gl.TEXTURE0);
  };
  return model;
}

// Why a measured table has no text to edit (the edit button says it).
export const TABLE_NOT_TEXT = "a measured table (.binary) is numbers, not text: there is nothing to edit in the page. " +
  "Its values are looked up by lab/measured/measured.glsl; to change the BRDF, fit a model to it " +
  "('brdf-lab fit') or edit the model it was tabulated from";

/** The page's name for an opened file: its stem as an identifier. */
export function fileModelName(fileName) {
  let name = fileName.replace(/\.[^.]*$/, "").replace(/\W/g, "_") || "model";
  if (/^\d/.test(name)) name = `m_${name}`;
  return name;
}

/** Opens a file the user chose: a MERL .binary table, a BRDF Explorer .brdf file or a model
 * .glsl; returns the model's name. A table or .brdf named like a library model gets a
 * suffix, so the library's stays; a .glsl of that name replaces it (the student's own
 * version). The model's `rebuild(text)` makes the model of an edited text (the editor);
 * a table has `notText` instead. */
export async function openModelFile(file, lab) {
  const binary = /\.binary$/i.test(file.name);
  const explorer = /\.brdf$/i.test(file.name);
  let name = fileModelName(file.name);
  if ((binary || explorer) && `brdfs/${name}.glsl` in lab.files) name = `${name}_${binary ? "measured" : "explorer"}`;
  const rebuild = (text) => {
    const model = explorer ? parseBrdf(text, file.name) : parseModel(text, file.name);
    return Object.assign(model, { name, rebuild, opened: file.name, text });
  };
  const data = binary ? await file.arrayBuffer() : await file.text();
  return putModel(lab, name, () => (binary
    ? Object.assign(measuredModel(parseMerl(data, file.name, lab.measuredTable), lab.measuredCode, name),
      { notText: TABLE_NOT_TEXT, opened: file.name })
    : rebuild(data)));
}

/** Puts the model `make()` returns in the page under `name`, or, where it throws a
 * ModelError, that error (the panels show it); returns the name. */
export function putModel(lab, name, make) {
  try {
    lab.models[name] = make();
    delete lab.modelErrors[name];
  } catch (err) {
    if (!(err instanceof ModelError)) throw err;
    delete lab.models[name];
    lab.modelErrors[name] = err.message;
  }
  if (!lab.order.includes(name)) lab.order.push(name);
  return name;
}

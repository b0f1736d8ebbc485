// An `object` check's draw in the page (practice mode, exercise 13): the grader's view
// (shaders/views/grade_object.glsl) with the check's textures bound as
// lab/grading/kinds/object.py binds them (RGBA8, bilinear, repeating, from unit first_unit
// on) and its shape and turn as that kind sets them. The image is then judged as a sphere
// check's (exercise.js).
//
// Why in JavaScript too: practice mode renders the student's text in the browser, which
// never reaches Python; tests/test_web_practice.py holds the verdicts to the grader's.
import { inflate, sentence } from "./diagnosis.js";
import { fill } from "./header.js";

/** Inflates an object check's textures once (check.texels: sampler -> RGBA bytes). */
export async function prepareObject(check) {
  if (check.kind !== "object" || check.texels) return;
  const texels = {};
  for (const [sampler, { data }] of Object.entries(check.textures)) texels[sampler] = await inflate(data, Uint8Array);
  check.texels = texels;
}

/** The check's textures on `gl`, made once per context (the bytes come from
 * ObjectKind.practice: first row at v = 0, as the grader uploads them). */
function checkTextures(gl, check) {
  if (check.glTextures?.gl === gl) return check.glTextures.list;
  const list = Object.entries(check.textures).map(([sampler, { width, height }]) => {
    const bytes = check.texels[sampler];
    const texture = gl.createTexture();
    gl.bindTexture(gl.TEXTURE_2D, texture);
    gl.pixelStorei(gl.UNPACK_ALIGNMENT, 1);
    gl.pixelStorei(gl.UNPACK_FLIP_Y_WEBGL, false);
    gl.texImage2D(gl.TEXTURE_2D, 0, gl.RGBA8, width, height, 0, gl.RGBA, gl.UNSIGNED_BYTE, bytes);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.LINEAR);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.LINEAR);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_WRAP_S, gl.REPEAT);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_WRAP_T, gl.REPEAT);
    gl.bindTexture(gl.TEXTURE_2D, null);
    return { sampler, texture };
  });
  check.glTextures = { gl, list };
  return list;
}

/** Uniforms and bound textures (index = unit) for panel.run(check.view, ...): the shape,
 * the turn and each sampler's unit, besides the lights the caller sets. */
export function objectInputs(gl, check) {
  const first = check.first_unit;
  const textures = new Array(first); // holes: draw() binds nothing there (a model's table keeps unit 0)
  const uniforms = { u_shape: check.shape_index, u_yaw: check.yaw_rad, u_pitch: check.pitch_rad };
  checkTextures(gl, check).forEach(({ sampler, texture }, i) => {
    textures.push(texture);
    uniforms[sampler] = first + i;
  });
  return { uniforms, textures };
}

/** The grader's explanation where no known mistake matched (ObjectKind.explain): the
 * samplers the student's program never reads (the compiler drops them from its uniforms). */
export function unreadTextures(panel, check) {
  const compiled = panel.program(check.view, `const int LIGHT_COUNT = ${check.lights.length};`);
  const unread = Object.keys(check.textures).sort().filter((name) => !(name in compiled.uniforms));
  return unread.length ? sentence(fill(check.unread_words, { names: unread.join(", ") })) : "";
}

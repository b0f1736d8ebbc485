// Editing a model in the page: the editor (edit.js, CodeMirror, loaded when first opened),
// the texts models came with (the editor's reset), the student's drafts kept in this
// browser, and practice mode (exercise.js), which edits an exercise's stub.
import { parseModel } from "./header.js";
import { assembleFragment } from "./assemble.js";
import { $, showTip } from "./dom.js";
import { compile } from "./glkit.js";
import { ExerciseMode } from "./exercise.js";
import { draft, keepDraft } from "./store.js";

let editor = null;
let exercises = null;
// Model or exercise name -> the text it came with (library file, opened file or stub): the
// editor's reset goes back to it, and an edited text equal to it is no draft to keep.
const originals = {};

export const currentEditor = () => editor;
export const currentExercises = () => exercises;

/** Records the text model `name` came with (an opened file's; null: the library's). */
export function setOriginal(lab, name) {
  originals[name] = lab.models[name]?.text ?? null;
}

export const originalText = (lab, name) => originals[name] ?? lab.files[`brdfs/${name}.glsl`] ?? null;

/** Embedded in a slide, the page shows the library as it is: the student's (or the
 * presenter's) kept files and edits of this browser stay out of the lecture's demos. */
export function embedded() {
  const value = new URLSearchParams(location.hash.slice(1)).get("embed");
  return value !== null && value !== "0";
}

/** The model of an edited text, as the editor builds it: an opened file's own rules, a
 * library file's header checked against its name. */
export function modelOfText(lab, name, text) {
  const model = lab.models[name];
  if (model?.rebuild) return model.rebuild(text);
  return parseModel(text, model?.path || `shaders/brdfs/${name}.glsl`, name);
}

/** Compiles the sphere program of `model` on the panel's context (throws CompileFailure). */
export function tryCompile(panel, model) {
  if (!panel.gl) return;
  const lab = panel.lab;
  const enums = Object.fromEntries(model.params.filter((p) => p.kind === "enum").map((p) => [p.name,
    p.choices.includes(panel.values[p.name]) ? panel.values[p.name] : p.default]));
  const assemble = model.assemble ?? assembleFragment; // a .brdf file assembles by its own rules
  const source = assemble(model, "sphere", lab.files, { target: "300es", enums, constants: lab.constants,
    preamble: `const int LIGHT_COUNT = ${lab.lights.length};` });
  panel.gl.deleteProgram(compile(panel.gl, source.text, source).program);
}

/** Shows an edited model that compiled in every panel of that name. A value the student
 * set is kept where the parameter is still there with the same kind and range; one at the
 * old default follows the file's new default. */
function installModel(panel, model) {
  const lab = panel.lab;
  lab.models[panel.name] = model;
  delete lab.modelErrors[panel.name];
  for (const other of lab.panels.filter((p) => p.name === panel.name)) {
    const kept = {};
    for (const p of model.params) {
      const old = other.model?.params.find((q) => q.name === p.name);
      const changed = old && JSON.stringify(other.values[p.name]) !== JSON.stringify(old.default);
      if (changed && old.kind === p.kind && JSON.stringify(old.choices) === JSON.stringify(p.choices) &&
        (p.kind !== "float" || (other.values[p.name] >= p.minimum && other.values[p.name] <= p.maximum))) {
        kept[p.name] = other.values[p.name];
      }
    }
    other.setModel(panel.name, kept);
  }
  lab.panels.forEach((p) => p.fillPicker());
  lab.requestRender();
}

/** Opens the editor on a panel's model; `options` (exercise mode): {path, build(text),
 * onResult(errors)} and `original` the stub. */
export async function openEditor(panel, original = null, options = {}) {
  const lab = panel.lab;
  const name = panel.name;
  if (!options.build && lab.exerciseList.some((e) => e.name === name)) return openExercise(lab, name);
  // A table has no text; a file with a header error has no model to edit yet.
  const why = panel.model?.notText ?? (panel.model ? "" : `${name} did not open: ${lab.modelErrors[name] || "no such model"}; ` +
    "fix the file and open it again");
  if (why) {
    showTip(why);
    return;
  }
  // The editor (CodeMirror, 400 kB) loads when first opened, not with the page.
  if (!editor) {
    const { ShaderEditor } = await import("./edit.js");
    const keepText = (p, text) => {
      if (!embedded()) keepDraft(p.name, text === originalText(lab, p.name) ? null : text);
    };
    editor ??= new ShaderEditor($("#editor"), { tryCompile, install: installModel, keepText });
  }
  originals[name] ??= original ?? originalText(lab, name) ?? panel.model?.code ?? "";
  // The student's unsaved text of an earlier visit comes back; else what the panel shows.
  const text = draft(name) ?? options.text ?? panel.model?.text ?? panel.model?.code;
  editor.open(panel, originals[name], { build: (t) => modelOfText(lab, name, t), path: panel.model?.opened, ...options, text });
  $("#editor").scrollIntoView({ block: "nearest" });
}

/** Closes the editor if it shows `panel` (the panel is going). */
export function closeEditorOf(panel) {
  if (editor?.panel === panel) editor.close();
}

/** Opens an exercise (folder name) in practice mode; resolves when its checks ran. */
export async function openExercise(lab, name) {
  exercises ??= new ExerciseMode($("#exercise"), lab, openEditor);
  await exercises.open(name);
  lab.requestRender();
}

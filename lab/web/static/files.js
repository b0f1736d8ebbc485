// Where the models come from: the manifest (the library's headers parsed by Python, the
// shader files, the registry of views and their page modules), files the student opens
// (kept in this browser for the next visit, store.js) and the editor's kept drafts.
import { ModelError, parseModel } from "./header.js";
import { $ } from "./dom.js";
import { CompileFailure } from "./glkit.js";
import { openModelFile, putModel } from "./measured.js";
import { draft, draftNames, forgetFile, keepDraft, keepFile, storeProblem } from "./store.js";
import { addPanel } from "./panels.js";
import { currentEditor, modelOfText, openEditor, originalText, setOriginal, tryCompile } from "./editing.js";
import { CORE_VIEWS } from "./state.js";

// The files kept in this browser: model name -> file name ("forget files" drops them).
const kept = new Map();

async function fetchText(path) {
  const response = await fetch(path);
  if (!response.ok) throw new Error(`cannot load ${path} (HTTP ${response.status})`);
  return response.text();
}

/** The manifest (lab/web/site.py) into `lab`: constants, the registry, presets, shader
 * texts and the library's headers. Returns the page modules still to load (loadViews). */
export async function load(lab) {
  const manifest = JSON.parse(await fetchText("manifest.json"));
  Object.assign(lab.constants, manifest.constants);
  lab.readRegistry(manifest.views);
  lab.presets = manifest.presets || [];
  lab.environments = manifest.environments; // the IBL view's maps: names and size
  lab.exerciseList = manifest.exercises || [];
  lab.measuredCode = manifest.measured_model; // lab/measured/measured.glsl
  lab.measuredTable = manifest.measured_table; // how merl.py reads a table (measured.js)
  // The texts come with the manifest (one request); a manifest without them, file by file.
  const sources = manifest.sources || {};
  const texts = await Promise.all(manifest.files.map((f) => sources[f] ?? fetchText(`shaders/${f}`)));
  manifest.files.forEach((f, i) => (lab.files[f] = texts[i]));
  // The library's headers come parsed (lab/models.py, checked against header.js by
  // tests/test_web_mirrors.py): the page parses only the files a user opens or edits.
  for (const name of manifest.models) {
    const path = `shaders/brdfs/${name}.glsl`;
    const header = manifest.library[name];
    if (header.error) lab.modelErrors[name] = header.error;
    else lab.models[name] = { ...header, path, code: lab.files[`brdfs/${name}.glsl`] };
    if (!lab.order.includes(name)) lab.order.push(name);
  }
}

/** Imports every view's page module (views/NAME.js, as the manifest names them) into
 * lab.modules; one that fails to load is named in the notes and left out. */
export async function loadViews(lab) {
  const pages = lab.registry.filter((v) => v.page && !CORE_VIEWS.includes(v.name));
  const modules = await Promise.all(pages.map((v) => import(`./${v.page}`).catch((err) => err)));
  pages.forEach((view, i) => {
    const module = modules[i];
    if (module instanceof Error || module.VIEW?.name !== view.name) {
      const why = module instanceof Error ? module.message : `it exports no VIEW named ${view.name}`;
      lab.notes.push(`the ${view.title} view is left out: ${view.page}: ${why}`);
    } else lab.modules[view.name] = module.VIEW;
  });
}

export function addModelText(lab, label, code, expectedName = null) {
  const name = expectedName || label.split("/").pop().replace(/\.glsl$/, "");
  return putModel(lab, name, () => parseModel(code, label, expectedName));
}

/** Opens a file the student chose and keeps it in this browser for the next visit. Panels
 * of its name show the new version (none: one is added); the edits of an earlier version
 * are dropped, and an open editor on it shows the file. */
export async function openFile(lab, file) {
  const name = await openModelFile(file, lab);
  setOriginal(lab, name);
  keepDraft(name, null);
  if (await keepFile(name, file)) keep(lab, name, file.name);
  lab.panels.forEach((p) => p.fillPicker());
  const showing = lab.panels.filter((p) => p.name === name);
  for (const panel of showing) panel.setModel(name);
  if (!showing.length) addPanel(lab, name);
  const editor = currentEditor();
  if (editor?.panel?.name === name && !editor.root.hidden) await openEditor(editor.panel);
  if (storeProblem && !lab.notes.includes(storeProblem)) lab.notes.push(storeProblem);
  return name;
}

/** The files opened in this browser on earlier visits (keptFiles()), before the address is
 * read. */
export async function restoreFiles(lab, keptList) {
  for (const { name, file } of keptList) {
    const opened = await openModelFile(file, lab);
    setOriginal(lab, opened);
    if (opened !== name) lab.notes.push(`${file.name}: kept as ${name}, now opens as ${opened}`);
    keep(lab, name, file.name);
  }
}

/** Records a kept file; one that replaces a library model says so (until forgotten). */
function keep(lab, name, fileName) {
  kept.set(name, fileName);
  if (`brdfs/${name}.glsl` in lab.files) {
    lab.notes.push(`${name}: your ${fileName} (kept in this browser) is shown instead of the library's ${name}; ` +
      `"forget files" brings the library's back`);
  }
  showForget();
}

function showForget() {
  const button = $("#forget-files");
  button.hidden = !kept.size;
  button.title = `forget the files this browser keeps for the page (${[...kept.values()].join(", ")}) and ` +
    "the edits made to them, and reload";
}

/** Drops every kept file and its edits, and starts the page again without them. */
export async function forgetFiles() {
  for (const name of kept.keys()) {
    await forgetFile(name);
    keepDraft(name, null);
  }
  location.reload();
}

/** The editor texts of earlier visits, shown in place of the files they edit. A text that
 * does not compile (any more) leaves the file's version on show; the editor brings it back. */
export function restoreDrafts(lab) {
  const panel = lab.panels.find((p) => p.gl);
  for (const name of draftNames()) {
    if (!lab.models[name] || lab.exerciseList.some((e) => e.name === name)) continue;
    const text = draft(name);
    if (text === originalText(lab, name)) {
      keepDraft(name, null);
      continue;
    }
    try {
      const model = modelOfText(lab, name, text);
      if (panel) tryCompile(panel, model);
      lab.models[name] = model;
      for (const p of lab.panels.filter((q) => q.name === name)) p.setModel(name, p.values);
      if (lab.panels.some((p) => p.name === name)) {
        lab.notes.push(`${name}: your edited version (kept in this browser) is shown; "edit" then "reset" goes back to the original`);
      }
    } catch (err) {
      if (!(err instanceof ModelError || err instanceof CompileFailure)) throw err;
      if (lab.panels.some((p) => p.name === name)) lab.notes.push(`${name}: your edited version (kept in this browser) has an error, so the original is shown; ` +
        `"edit" opens your version (${err.message.split("\n")[0]})`);
    }
  }
}

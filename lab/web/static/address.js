// Showing a state as a whole: an address typed, followed or bookmarked, a desktop preset,
// or "reset". Each rebuilds the panels and the page-wide controls from the state.
import { $, showNotes } from "./dom.js";
import { presetHash, readHash } from "./hash.js";
import { buildLights } from "./lights.js";
import { addPanel, fitEmbed } from "./panels.js";
import { openExercise } from "./editing.js";
import { showToolbar } from "./toolbar.js";
import { cancelFrame, renderNow, writeHash } from "./scheduler.js";

export const defaultModel = (lab) => (lab.order.includes("phong") ? "phong" : lab.order[0]);

/** The panels of an address; an exercise's (model=01_lambert) opens that exercise with the
 * student's kept text. */
export function addPanels(lab, panels) {
  for (const p of panels) {
    if (lab.exerciseList.some((e) => e.name === p.name)) openExercise(lab, p.name).then(() => showNotes(lab.notes));
    else addPanel(lab, p.name, p.values);
  }
}

/** Shows the state of an address (typed into the address bar, a link or a preset). */
export function applyHash(lab, hash = location.hash.slice(1), extraNotes = []) {
  if (`#${hash}` !== location.hash) history.replaceState(null, "", `#${hash}`);
  lab.notes = [];
  const panels = readHash(lab, hash);
  lab.notes.push(...extraNotes);
  if (!panels.length) panels.push({ name: defaultModel(lab), values: {} });
  while (lab.panels.length) lab.panels.pop().destroy();
  addPanels(lab, panels);
  showNotes(lab.notes);
  showToolbar(lab);
  buildLights(lab);
  fitEmbed(lab);
  cancelFrame();
  renderNow();
  writeHash();
}

/** Shows desktop preset `index` (lab.presets) and what of it the page cannot show. */
export function applyPreset(lab, index) {
  const preset = lab.presets[index];
  if (!preset) return;
  const skipped = [];
  const hash = presetHash(lab, preset, skipped);
  const notes = $("#preset-notes");
  notes.textContent = `${preset.title || preset.file}${preset.notes ? ": " + preset.notes : ""}`;
  notes.hidden = false;
  applyHash(lab, hash, skipped);
}

/** Every parameter and setting back to its default, one white light, no ambient; the
 * models and the views shown stay. */
export function reset(lab) {
  lab.resetLook();
  for (const panel of lab.panels) panel.setModel(panel.name);
  $("#preset").value = "";
  $("#preset-notes").hidden = true;
  showToolbar(lab);
  buildLights(lab);
  renderNow();
  writeHash();
}


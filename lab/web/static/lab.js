// The web lab's start-up: the manifest and the views' page modules, the address, the
// panels, then the first picture (every panel's sphere and polar plot), the views in sight
// the frame after, coarse, and at full quality the frame after that; views out of sight
// draw when the browser is idle or when they scroll in. Model files come from shaders/,
// assembled exactly as the desktop lab assembles them.
import { $, el, onCanvasResize, savePng, showNotes, showTip } from "./dom.js";
import { LabState } from "./state.js";
import { keptFiles, storeProblem } from "./store.js";
import { forgetFiles, load, loadViews, openFile, restoreDrafts, restoreFiles } from "./files.js";
import { readHash } from "./hash.js";
import { addLight, buildLights, setLight, showAmbient } from "./lights.js";
import { addPanel, fitEmbed, removePanel } from "./panels.js";
import { closeEditorOf, embedded, openEditor, openExercise } from "./editing.js";
import { addPanels, applyHash, applyPreset, defaultModel, reset } from "./address.js";
import { buildViewTools, forwardSlideKeys, showToolbar } from "./toolbar.js";
import { cancelFrame, renderNow, settleNow, startScheduler, writeHash } from "./scheduler.js";
import { installTestApi } from "./testapi.js";

/** The page's controls and what they do. */
function wire(lab) {
  document.body.classList.toggle("embed", lab.embed);
  if (lab.embed) forwardSlideKeys();
  buildViewTools(lab);
  $("#add-light").addEventListener("click", () => addLight(lab));
  $("#ambient").addEventListener("input", (e) => {
    const level = Number(e.target.value);
    lab.ambient = [level, level, level];
    showAmbient(lab);
    lab.requestRender();
  });
  addEventListener("resize", () => {
    fitEmbed(lab);
    lab.requestRender();
  });
  onCanvasResize(() => lab.requestRender()); // a plot's text follows its canvas's new size
  $("#add-model").addEventListener("click", () => {
    addPanel(lab, lab.panels[lab.panels.length - 1]?.name || lab.order[0]);
    lab.requestRender();
  });
  $("#forget-files").addEventListener("click", forgetFiles);
  $("#open-file").addEventListener("change", async (e) => {
    for (const file of e.target.files) await openFile(lab, file);
    e.target.value = ""; // the same file again (fixed on disk) must fire another change
    showNotes(lab.notes);
    lab.requestRender();
  });
  // What a panel asks of the page (panel.js ask()).
  const panels = $("#panels");
  panels.addEventListener("panel-remove", (e) => {
    closeEditorOf(e.detail.panel);
    removePanel(lab, e.detail.panel);
  });
  panels.addEventListener("panel-edit", (e) => openEditor(e.detail.panel));
  panels.addEventListener("panel-light", (e) => setLight(lab, e.detail.theta, e.detail.phi));
  $("#overlay").prepend(el("header", {}, "all models on one scale"));
  $("#overlay .view").append(el("button", { type: "button", class: "png", title: "save the overlaid polar plot as a PNG image",
    onclick: () => savePng($("#overlay canvas"), "polar_all.png") }, "PNG"));
  $("#exercise-pick").append(...lab.exerciseList.map((e) => el("option", { value: e.name }, e.title)));
  $("#exercise-pick").addEventListener("change", (e) => e.target.value && openExercise(lab, e.target.value));
  $("#preset").append(...lab.presets.map((p, i) => el("option", { value: i }, p.title || p.file)));
  $("#preset").addEventListener("change", (e) => e.target.value !== "" && applyPreset(lab, Number(e.target.value)));
  $("#reset").addEventListener("click", () => reset(lab));
  $("#tip button").addEventListener("click", () => showTip(""));
  // A tap (or click) on a label's words shows its meaning; a tap on its slider does not.
  document.addEventListener("click", (e) => {
    const label = e.target.closest?.("label[title], .param[title], .light-name");
    if (!label || e.target.closest("input, select, button")) return;
    const text = label.title || label.closest("[title]")?.title || "";
    if (text) showTip(text);
  });
  addEventListener("hashchange", () => applyHash(lab));
}

/** Waits for the browser to show the last frame (and to be free for the next task). */
const nextFrame = () => new Promise((resolve) => requestAnimationFrame(() => setTimeout(resolve)));

/** Draws the views out of sight one at a time while the browser is idle, each once, so
 * that they are ready when scrolled to (a progressive one, the IBL view, goes on when it
 * comes into sight). */
function drawWhenIdle(lab, drawn = new Set()) {
  const idle = window.requestIdleCallback ?? ((f) => setTimeout(f, 50));
  idle(() => {
    if (lab.fast) return drawWhenIdle(lab, drawn);
    for (const panel of lab.panels) {
      const view = Object.values(panel.extra).find((v) => v.stale && !drawn.has(v));
      if (view) {
        drawn.add(view);
        panel.renderView(view);
        return drawWhenIdle(lab, drawn);
      }
    }
    lab.idleDrawnMs ??= performance.now(); // every view drawn, in sight or not
  });
}

async function main(lab) {
  startScheduler(lab);
  // The kept files are looked up while the manifest loads.
  const [, keptList] = await Promise.all([load(lab), embedded() ? [] : keptFiles()]);
  await Promise.all([loadViews(lab), restoreFiles(lab, keptList)]);
  const panels = readHash(lab);
  // First every panel's sphere and polar plot (what the page is for), on screen at once;
  // then the views in sight, coarse, as while a slider moves; then their full quality.
  lab.coreOnly = lab.views.length > 0;
  wire(lab);
  showToolbar(lab);
  if (!panels.length) panels.push({ name: defaultModel(lab), values: {} });
  addPanels(lab, panels);
  if (!embedded()) restoreDrafts(lab);
  if (storeProblem) lab.notes.push(storeProblem);
  showNotes(lab.notes);
  buildLights(lab);
  fitEmbed(lab);
  cancelFrame();
  lab.builtMs = performance.now(); // manifest, page modules, address and panels ready
  renderNow();
  lab.firstRenderMs = performance.now(); // since navigation start
  lab.coreOnly = false;
  if (lab.views.length) {
    await nextFrame();
    lab.panels.forEach((panel) => panel.syncViews());
    lab.fast = true;
    renderNow();
    lab.viewsRenderMs = performance.now();
  } else lab.viewsRenderMs = lab.firstRenderMs;
  if (lab.embed) {
    fitEmbed(lab); // again, now that every view has drawn once
    renderNow();
  }
  writeHash();
  if (!lab.fast) lab.fullRenderMs = lab.firstRenderMs;
  else {
    await nextFrame();
    settleNow();
    lab.fullRenderMs = performance.now();
  }
  drawWhenIdle(lab);
}

const lab = new LabState();
installTestApi(lab, main(lab));

// The page-wide controls. The view choice and each view's own settings (VIEW.toolbar of its
// page module) are built from the registry: a menu for a setting with choices, a checkbox
// for a bool, a slider otherwise, with the registry's label, range, step, unit and meaning.
// The sphere's and polar plot's controls are in index.html; their ranges come from it too.
import { formatG } from "./header.js";
import { $, el } from "./dom.js";
import { showAmbient } from "./lights.js";
import { round } from "./state.js";

// The registry settings with a control here (the views' own and the polar plot's φo).
const controlled = [];

/** The id of a setting's control ("phi_d" -> "phi-d"; its value shows in "phi-d-text"). */
const controlId = (name) => name.replace(/_/g, "-");

/** The control of registry setting `name`, which sets it and draws again. */
function settingControl(lab, name) {
  const spec = lab.specs[name];
  const id = controlId(name);
  const changed = (value) => {
    lab.set(name, value);
    showToolbar(lab);
    lab.requestRender();
  };
  let input;
  if (spec.choices.length) {
    input = el("select", { id }, ...spec.choices.map((text, i) => el("option", { value: i }, text)));
    input.addEventListener("input", () => changed(Number(input.value)));
  } else if (spec.kind === "bool") {
    input = el("input", { id, type: "checkbox" });
    input.addEventListener("change", () => changed(input.checked));
  } else {
    input = el("input", { id, type: "range", min: spec.min ?? -10, max: spec.max ?? 10, step: spec.step });
    input.addEventListener("input", () => changed(Number(input.value)));
  }
  const shown = spec.choices.length || spec.kind === "bool" ? [] : [" ", el("span", { id: `${id}-text`, class: "deg" })];
  return el("label", { class: "group", title: spec.doc || spec.label, "data-view": spec.view }, `${spec.label} `, input, ...shown);
}

/** Builds the view choice and the views' own controls from the registry. */
export function buildViewTools(lab) {
  $("#view-choice").append(...lab.pageViews.map((name) => {
    const view = lab.registry.find((v) => v.name === name);
    const box = el("input", { type: "checkbox", value: name });
    box.addEventListener("change", () => {
      lab.views = lab.pageViews.filter((n) => (n === name ? box.checked : lab.views.includes(n)));
      showToolbar(lab);
      lab.requestRender();
    });
    return el("label", { title: view.title }, box, ` ${view.short_title}`);
  }));
  const tools = lab.pageViews.flatMap((name) => (lab.modules[name].toolbar || []).filter((s) => lab.specs[s]));
  $("#view-tools").append(...tools.map((name) => settingControl(lab, name)));
  controlled.push(...tools);
  // The sphere's and the polar plot's settings: controls in index.html, ranges from the registry.
  for (const name of ["exposure", "phi_o"]) {
    const input = $(`#${controlId(name)}`);
    const spec = lab.specs[name];
    if (!input || !spec) continue;
    if (name !== "exposure") controlled.push(name);
    Object.assign(input, { min: spec.min, max: spec.max, step: spec.step });
    if (spec.doc) input.closest("label").title = spec.doc;
    input.addEventListener("input", () => {
      lab.set(name, Number(input.value));
      showToolbar(lab);
      lab.requestRender();
    });
  }
  for (const [id, name] of [["cos-weighted", "polar_cos"], ["polar-log", "polar_log"]]) {
    $(`#${id}`).addEventListener("change", (e) => {
      lab.set(name, e.target.checked);
      lab.requestRender();
    });
  }
}

/** The page-wide controls show the state (after an address or a preset changed it). */
export function showToolbar(lab) {
  showAmbient(lab);
  $("#exposure").value = lab.settings.exposure;
  $("#exposure-text").textContent = `×${formatG(round(Math.pow(2, lab.settings.exposure)))}`;
  $("#cos-weighted").checked = lab.settings.polar_cos;
  $("#polar-log").checked = lab.settings.polar_log;
  for (const name of controlled) {
    const spec = lab.specs[name];
    const input = document.getElementById(controlId(name));
    if (input.type === "checkbox") input.checked = lab.settings[name];
    else input.value = lab.settings[name];
    const text = document.getElementById(`${controlId(name)}-text`);
    if (text) text.textContent = `${formatG(round(lab.settings[name]))}${spec.unit}`;
  }
  // A view's own controls show while the view does.
  for (const label of document.querySelectorAll("#view-tools label[data-view]")) {
    const hidden = Boolean(lab.modules[label.dataset.view]) && !lab.views.includes(label.dataset.view);
    label.style.display = hidden ? "none" : "";
  }
  document.querySelectorAll("#view-choice input").forEach((box) => (box.checked = lab.views.includes(box.value)));
  for (const name of lab.pageViews) document.body.classList.toggle(`with-${name}`, lab.views.includes(name));
  lab.panels.forEach((panel) => panel.syncViews());
}

// Keys a presenter's clicker or keyboard sends to move between slides.
const SLIDE_KEYS = { PageDown: "next", PageUp: "prev", ArrowRight: "next", ArrowLeft: "prev",
  " ": "next" };

/** Embedded in a slide, the frame keeps the keyboard focus after a click on a control: pass
 * the slide keys on to the deck, unless a text box or slider needs the key itself. */
export function forwardSlideKeys() {
  addEventListener("keydown", (e) => {
    const step = SLIDE_KEYS[e.key];
    if (!step || e.altKey || e.ctrlKey || e.metaKey || window.parent === window) return;
    const target = e.target;
    const typing = target instanceof HTMLInputElement && target.type === "text";
    const slider = target instanceof HTMLInputElement && target.type === "range";
    const owned = typing || target instanceof HTMLSelectElement || target instanceof HTMLTextAreaElement ||
      (slider && e.key.startsWith("Arrow")) || (e.key === " " && target instanceof HTMLButtonElement);
    if (owned) return;
    e.preventDefault();
    window.parent.postMessage({ brdfLab: "slide", step }, "*");
  });
}

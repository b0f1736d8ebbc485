// Owns: what assistive technology and the keyboard get from the page (WCAG 2.1 AA). Names tied
// to every control, sliders that speak their value in the parameter's unit, errors as text
// tied to their field, text alternatives for the canvases, one polite announcement per
// practice run, progress at most every PROGRESS_MS, pause for the Monte Carlo estimate,
// keyboard orbit and zoom, lists that open on Enter. It attaches by ids, classes and events
// to what lab.js builds (a MutationObserver follows the panels), so lab.js stays unaware.
import { readPlots, setting, settingName } from "./plotread.js";
import { readViews } from "./viewread.js";

const PROGRESS_MS = 5000;
let uid = 0;
const idOf = (node, stem) => node.id || (node.id = `${stem}-${++uid}`);

function el(tag, attrs = {}, ...children) {
  const node = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) node.setAttribute(k, v);
  node.append(...children);
  return node;
}

// -- announcements ---------------------------------------------------------------------------
const live = el("div", { id: "announce", role: "status", "aria-live": "polite", class: "sr-only" });
/** Says `text` once through the polite live region. */
export function announce(text) {
  live.textContent = "";
  setTimeout(() => (live.textContent = text), 50); // a change the reader notices
}

// -- values in words ---------------------------------------------------------------------------
/** "45°" -> "45 degrees", "×2" -> "times 2": what a slider's value box shows, spoken. */
export function spoken(text) {
  return text.trim().replace(/°/g, " degrees").replace(/^×/, "times ").replace(/−/g, "minus ");
}

/** The text that shows a slider's value: the row's box or the span after it. */
function valueShown(slider) {
  const row = slider.closest(".param");
  if (row) return row.querySelector("input.value")?.value ?? "";
  const text = document.getElementById(`${slider.id}-text`) ||
    slider.closest("label")?.nextElementSibling;
  return text?.classList.contains("deg") ? text.textContent : "";
}

function speakSlider(slider) {
  const text = valueShown(slider);
  if (text) slider.setAttribute("aria-valuetext", spoken(text));
}

/** A parameter row (lab.js Panel.control): label for the first control, names for the rest,
 * the meaning as description, errors tied to the box. */
function nameRow(row) {
  if (row.dataset.a11y) return;
  row.dataset.a11y = "1";
  const name = row.dataset.param;
  const label = row.querySelector("label");
  const controls = [...row.querySelectorAll("input, select")];
  if (!label || !controls.length) return;
  label.htmlFor = idOf(controls[0], `param-${name}`);
  const tip = el("span", { class: "sr-only", id: `${controls[0].id}-tip` }, row.title || label.title || "");
  row.append(tip);
  for (const control of controls) {
    control.setAttribute("aria-describedby", tip.id);
    if (control !== controls[0]) {
      const kind = row.classList.contains("param-color") ? "as r,g,b" : "value";
      control.setAttribute("aria-label", `${name} ${kind}`);
    }
  }
  if (controls[0].type === "color") controls[0].setAttribute("aria-label", `${name} colour`);
  row.querySelectorAll("input[type=range]").forEach(speakSlider);
}

/** A box marked bad (class "bad", its message in its title): aria-invalid and the message as
 * text beside it, tied by aria-describedby; cleared with the mark. */
function showInvalid(box) {
  const bad = box.classList.contains("bad");
  const errorId = `${idOf(box, "field")}-error`;
  let message = document.getElementById(errorId);
  const described = (box.getAttribute("aria-describedby") || "").split(" ").filter((d) => d && d !== errorId);
  if (bad) {
    if (!message) {
      message = el("span", { id: errorId, class: "field-error" });
      (box.closest(".param") || box.parentElement).after(message);
    }
    if (message.textContent !== box.title) announce(box.title);
    message.textContent = box.title;
    box.setAttribute("aria-invalid", "true");
    box.setAttribute("aria-describedby", [...described, errorId].join(" "));
  } else if (box.getAttribute("aria-invalid")) {
    message?.remove();
    box.removeAttribute("aria-invalid");
    box.setAttribute("aria-describedby", described.join(" "));
  }
}

// -- canvases ----------------------------------------------------------------------------------
function nameCanvases(lab) {
  lab.panels.forEach((panel, k) => {
    const light = lab.lights[0];
    const sphere = panel.canvas;
    if (sphere) {
      sphere.setAttribute("role", "img");
      const lights = lab.lights.length > 1 ? ` and ${lab.lights.length - 1} more lights` : "";
      sphere.setAttribute("aria-label", `Sphere ${k + 1}, ${panel.name}, lit from θi ${light.theta} degrees, ` +
        `φi ${light.phi} degrees${lights}; drag, or the light sliders, to move the light`);
    }
    for (const [name, view] of Object.entries(panel.extra || {})) {
      if (!view.canvas) continue;
      view.canvas.setAttribute("role", "img");
      if (view.canvas.matches("canvas.lobe3d, canvas.object")) view.canvas.tabIndex = 0;
      const title = view.root?.dataset?.view || name;
      const note = view.root?.querySelector(".view-note")?.textContent || "";
      view.canvas.setAttribute("aria-label", `${title} of ${panel.name}${note ? `: ${note}` : ""}`);
    }
  });
  document.querySelectorAll("#exercise canvas:not([role])").forEach((c) => {
    c.setAttribute("role", "img");
    c.setAttribute("aria-label", c.closest("figure")?.querySelector("figcaption")?.textContent || c.title);
  });
}

// -- keyboard ----------------------------------------------------------------------------------
/** Orbit and zoom by keys on the 3D lobe and the lit object (the mouse drags them). */
function orbitKeys(lab) {
  addEventListener("keydown", (e) => {
    const c = e.target;
    if (!(c instanceof HTMLCanvasElement) || e.altKey || e.ctrlKey || e.metaKey) return;
    const lobe = c.classList.contains("lobe3d");
    if (!lobe && !c.classList.contains("object")) return;
    const [yaw, pitch] = lobe ? ["lobe_yaw", "lobe_pitch"] : ["yaw", "pitch"];
    const get = (name) => setting(lab, name);
    const step = e.shiftKey ? 0.05 : 0.2;
    const change = {};
    const put = (name, value) => (change[settingName(lab, name)] = value);
    if (e.key === "ArrowLeft") put(yaw, get(yaw) - step);
    else if (e.key === "ArrowRight") put(yaw, get(yaw) + step);
    else if (e.key === "ArrowUp") put(pitch, Math.min(get(pitch) + step, 1.5));
    else if (e.key === "ArrowDown") put(pitch, Math.max(get(pitch) - step, -1.5));
    else if (lobe && (e.key === "+" || e.key === "=")) put("lobe_zoom", Math.min(get("lobe_zoom") * 1.2, 8));
    else if (lobe && (e.key === "-" || e.key === "_")) put("lobe_zoom", Math.max(get("lobe_zoom") / 1.2, 0.2));
    else return;
    e.preventDefault();
    e.stopPropagation();
    window.brdfLab.setSettings(change);
    if (document.activeElement !== c) c.focus(); // the views were put back in place: keep the focus
  }, true);
}

/** In a slide, the key that operates the focused control stays with it (Space ticks a box,
 * it does not turn the slide). */
function keysStayInControls() {
  addEventListener("keydown", (e) => {
    const t = e.target;
    if (window.parent === window || !(t instanceof HTMLInputElement)) return;
    if (e.key === " " && (t.type === "checkbox" || t.type === "radio" || t.type === "color")) e.stopPropagation();
  }, true);
}

/** Preset and exercise lists change on Enter, not on each arrow key: an arrow only moves
 * the choice (Enter opens it; leaving the list puts the old one back). */
function enterToOpen() {
  const lists = new Set(["preset", "exercise-pick"]);
  let arrowAt = -Infinity;
  addEventListener("focusin", (e) => {
    if (lists.has(e.target.id)) e.target.dataset.chosen = e.target.value;
  }, true);
  addEventListener("keydown", (e) => {
    const list = e.target;
    if (!lists.has(list.id)) return;
    if (e.key.startsWith("Arrow") || e.key === "Home" || e.key === "End" || e.key === "PageUp" || e.key === "PageDown") {
      arrowAt = performance.now();
    } else if (e.key === "Enter" && list.dataset.moved) {
      e.preventDefault();
      arrowAt = -Infinity;
      delete list.dataset.moved;
      list.dispatchEvent(new Event("change", { bubbles: true }));
    }
  }, true);
  addEventListener("change", (e) => {
    const list = e.target;
    if (!lists.has(list.id)) return;
    if (performance.now() - arrowAt < 500) {
      e.stopImmediatePropagation(); // moved through the list: it opens on Enter
      list.dataset.moved = "1";
      return;
    }
    list.dataset.chosen = list.value;
  }, true);
  addEventListener("focusout", (e) => {
    const list = e.target;
    if (!lists.has(list.id) || !list.dataset.moved) return;
    delete list.dataset.moved;
    list.value = list.dataset.chosen ?? "";
  }, true);
}

/** Monte Carlo estimates: the status line is no longer a live region (it changes every
 * frame); progress is announced at most every PROGRESS_MS; a pause button per estimate. */
function estimates(lab) {
  let said = -Infinity;
  for (const panel of lab.panels) {
    const view = panel.extra?.ibl;
    if (!view?.status || view.status.dataset.a11y) continue;
    view.status.dataset.a11y = "1";
    view.status.removeAttribute("role");
    const button = el("button", { type: "button", class: "pause", "aria-pressed": "false" }, "pause");
    const setPaused = (paused) => {
      view.root.classList.toggle("paused", paused);
      button.setAttribute("aria-pressed", String(paused));
      button.textContent = paused ? "continue" : "pause";
      if (!paused) view.schedule?.();
    };
    button.addEventListener("click", () => setPaused(!view.root.classList.contains("paused")));
    view.status.before(button);
    if (matchMedia("(prefers-reduced-motion: reduce)").matches) setPaused(true);
    new MutationObserver(() => {
      const now = performance.now();
      const done = /done/.test(view.status.textContent);
      if (now - said >= PROGRESS_MS || (done && !view.status.dataset.doneSaid)) {
        said = now;
        if (done) view.status.dataset.doneSaid = "1";
        announce(view.status.textContent);
      }
    }).observe(view.status, { childList: true, characterData: true, subtree: true });
  }
}

/** The editor's compile status changes as one types: said when it turns from compiling to
 * an error or back, not at every keystroke (the line stays on screen). */
function editorStatus() {
  const status = document.querySelector("#editor .editor-status");
  if (!status || status.dataset.a11y) return;
  status.dataset.a11y = "1";
  status.removeAttribute("role");
  let bad = status.classList.contains("bad");
  new MutationObserver(() => {
    const now = status.classList.contains("bad");
    if (now !== bad) announce(status.textContent);
    bad = now;
  }).observe(status, { attributes: true, attributeFilter: ["class"], childList: true, characterData: true, subtree: true });
}

/** One announcement per practice run: points, then each check that failed with its message. */
function practiceResults() {
  let said = 0;
  return () => {
    const ex = window.brdfLab.exercises;
    const root = document.getElementById("exercise");
    if (!ex || root.hidden || ex.runs === said || root.querySelector("li.pending:not(.graded)")) return;
    said = ex.runs;
    const tally = root.querySelector(".practice")?.textContent.split(": ").pop() || "";
    const failed = [...root.querySelectorAll("ul.checks li.fail")].map((li) => li.textContent.replace(/^✗\s*/, ""));
    announce(`Practice run ${said}: ${tally}. ${failed.length ? `Failed: ${failed.join(" ")}` : "Every check passed."}`);
  };
}

/** A control's meaning (its title) shown beside it when the keyboard reaches it. */
function focusTips() {
  const tip = el("div", { id: "focus-tip", "aria-hidden": "true", hidden: "" });
  document.body.append(tip);
  addEventListener("focusin", (e) => {
    const holder = e.target.closest?.("[title]");
    if (!holder || !e.target.matches(":focus-visible") || e.target.tagName === "CANVAS") return;
    const r = e.target.getBoundingClientRect();
    tip.textContent = holder.title;
    tip.hidden = false;
    tip.style.left = `${Math.max(4, Math.min(r.left, innerWidth - 320))}px`;
    tip.style.top = `${r.bottom + 4}px`;
  });
  addEventListener("focusout", () => (tip.hidden = true));
  // Dismissible without moving the focus (WCAG 1.4.13).
  addEventListener("keydown", (e) => e.key === "Escape" && !tip.hidden && (tip.hidden = true));
}

function setUp() {
  const { state: lab } = window.brdfLab;
  document.body.append(live);
  const named = () => {
    document.querySelectorAll(".param").forEach(nameRow);
    const code = document.querySelector("#editor .cm-content");
    if (code && !code.getAttribute("aria-label")) {
      code.setAttribute("aria-label", "GLSL source (compile errors are listed below the editor)");
    }
    document.querySelectorAll(".panel .model-picker:not([aria-label])").forEach((s, k) =>
      s.setAttribute("aria-label", `model ${k + 1}`));
  };
  const results = practiceResults();
  let pending = 0;
  const update = () => {
    pending = 0;
    named();
    nameCanvases(lab);
    estimates(lab);
    editorStatus();
    results();
  };
  new MutationObserver((records) => {
    for (const r of records) if (r.type === "attributes" && r.target.matches("input.value")) showInvalid(r.target);
    if (!pending) pending = requestAnimationFrame(update);
  }).observe(document.body, { childList: true, subtree: true, attributes: true, attributeFilter: ["class"] });
  const speak = (e) => {
    if (e.target.type === "range") speakSlider(e.target);
    else if (e.target.matches?.("input.value")) e.target.closest(".param")?.querySelectorAll("input[type=range]").forEach(speakSlider);
  };
  for (const type of ["input", "change", "focusin"]) addEventListener(type, (e) => setTimeout(() => speak(e)), true);
  const speakAll = () => document.querySelectorAll("input[type=range]").forEach(speakSlider);
  addEventListener("hashchange", () => setTimeout(speakAll, 300));
  orbitKeys(lab);
  enterToOpen();
  keysStayInControls();
  focusTips();
  update();
  speakAll();
  window.brdfLabA11y.views = readViews(lab);
  // The plots wait for the constants (luminance weights, grazing cut-off) from the manifest.
  fetch("manifest.json").then((r) => r.json()).then((m) => {
    window.brdfLabA11y.plots = readPlots(lab, m.constants, el);
  });
  window.brdfLabA11y.refresh = () => {
    update();
    speakAll();
    window.brdfLabA11y.plots?.refresh();
    window.brdfLabA11y.views.refresh();
  };
}

window.brdfLabA11y = { announce, spoken };
const start = () => window.brdfLab.ready.then(() => requestAnimationFrame(setUp));
if (window.brdfLab) start();
else addEventListener("load", start);

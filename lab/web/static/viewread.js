// Owns: the generated descriptions of the views other than the polar plot (plotread.js has
// that one). Once a change settles, each view canvas is described by what its view computed
// (describe_views.js, the mirror of lab/describe_views.py) in a text tied to the canvas by
// aria-describedby; a screen reader says it after the canvas's name. Attaches by DOM and the
// views' read(); the views know nothing of it.
import { albedo, imageSlice, lobe3d, picture, sh, sphere, terms } from "./describe_views.js";

const SETTLE_MS = 700; // after the scheduler's full-quality pass (200 ms after the hand stops)
let uid = 0;

/** What view `name` of `panel` shows, in words; "" while it has nothing to show. */
function words(lab, panel, name, view) {
  const C = lab.constants;
  const s = lab.settings;
  const light = lab.lights[0];
  const label = panel.name;
  if (name === "albedo") return view.albedo ? albedo(label, view.thetas, view.albedo) : "";
  if (name === "slice") return view.data ? imageSlice(label, view.read(), s.phi_d, C.LUMA, C.GRAZING_DEG) : "";
  if (name === "object") return view.data ? picture(label, "lit object", view.read(), C.LUMA) : "";
  if (name === "ibl") {
    if (!view.samples) return `image-based lighting of ${label}: no samples yet (the estimate runs while the view is in sight).`;
    return `${picture(label, "image-based lighting", view.read(), C.LUMA)} ${view.samples} samples per pixel so far.`;
  }
  if (name === "terms") {
    if (view.terms) return terms(label, view.terms, C.LUMA, C.GRAZING_DEG);
    const note = view.root?.querySelector(".view-note")?.textContent; // why there are none
    return note ? `No D, G, F terms: ${note}` : "";
  }
  if (name === "sh") {
    if (panel.model?.delta) return `${label}: no spherical harmonics for a δ model.`;
    return view.data ? sh(label, Array.from(view.data.errors), s.sh_order) : "";
  }
  if (name === "lobe3d") {
    const cache = view.peakCache;
    if (!cache?.values || !view.directions) return "";
    const what = s.polar_cos ? "f_r cos θo" : "f_r";
    return lobe3d(label, cache.values, view.directions.angles, light.theta, light.phi, what, C.GRAZING_DEG, cache.value[1]);
  }
  return "";
}

/** The sr-only text under `canvas` that describes it, made once. */
function descriptionOf(canvas) {
  let p = canvas.describedText;
  if (!p) {
    p = canvas.describedText = document.createElement("p");
    p.className = "sr-only view-description";
    p.id = `view-description-${++uid}`;
    canvas.after(p);
  }
  const ids = (canvas.getAttribute("aria-describedby") || "").split(" ").filter((d) => d && d !== p.id);
  canvas.setAttribute("aria-describedby", [...ids, p.id].join(" "));
  return p;
}

function say(canvas, text) {
  if (!text || !canvas?.isConnected) return;
  const p = descriptionOf(canvas);
  if (p.textContent !== text) p.textContent = text;
  canvas.dataset.description = text;
}

/** Calls `drawn` after each of the view's renders (a view off screen draws when it scrolls
 * into sight or the page is idle). The IBL estimate's refining frames are not followed: it
 * is described as the others settle, with its samples so far. */
function follow(view, drawn) {
  if (view.describedFollow) return;
  view.describedFollow = true;
  for (const method of ["render", "process"]) {
    if (typeof view[method] !== "function") continue;
    const original = view[method];
    view[method] = function (...args) {
      const out = original.apply(this, args);
      drawn();
      return out;
    };
  }
}

/** Describes every view of every panel now, as drawn (a view off screen shows, and is
 * described by, its last picture until it draws again).
 * `drawn`: called after a view draws (each view's render and draw are followed once). */
export function describeViews(lab, drawn = () => {}) {
  const light = lab.lights[0];
  for (const panel of lab.panels) {
    if (panel.canvas && panel.model && panel.target) {
      try {
        const more = lab.lights.slice(1).map((l) => [l.theta, l.phi]);
        say(panel.canvas, sphere(panel.name, panel.readSphere(), light.theta, light.phi, lab.constants.LUMA, more));
      } catch { /* a panel whose model does not compile has no sphere */ }
    }
    for (const [name, view] of Object.entries(panel.extra || {})) {
      if (!view.canvas) continue;
      follow(view, drawn);
      say(view.canvas, words(lab, panel, name, view));
    }
  }
}

/** Describes the views once each change settles; returns { refresh } for tests. */
export function readViews(lab) {
  let timer = 0;
  const refresh = () => {
    clearTimeout(timer);
    if (lab.fast) timer = setTimeout(refresh, SETTLE_MS); // still moving: the coarse pass
    else describeViews(lab, soon);
  };
  const soon = () => {
    clearTimeout(timer);
    timer = setTimeout(refresh, SETTLE_MS);
  };
  for (const type of ["input", "change", "pointerup", "keyup", "hashchange", "click"]) addEventListener(type, soon, true);
  refresh();
  return { refresh };
}

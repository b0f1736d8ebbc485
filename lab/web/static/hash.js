// The address: the whole state of the page after the '#', so that a link, a bookmark or a
// slide shows the same thing. model=NAME&PARAM=VALUE...&model=NAME2...&light=THETA,PHI[,R,G,B]
// ...&ambient=R,G,B, and every registry setting under its own name (lab/views: phi_d=,
// lobe_yaw=, ...), the same name the desktop's presets use. A view's page module may own a
// key of its own (VIEW.address: the IBL view's ibl=).
import { formatG } from "./header.js";
import { parseRgb, parseValue } from "./values.js";
import { valueText } from "./controls.js";
import { DEFAULT_SIZE, MAX_PANELS, round } from "./state.js";

// Keys of older addresses (links and slides made before the settings took the registry's
// names): still read, never written.
const OLD_KEYS = { cos: "polar_cos", log: "polar_log", phio: "phi_o", phid: "phi_d", lyaw: "lobe_yaw",
  lpitch: "lobe_pitch", lzoom: "lobe_zoom", sh: "sh_order" };
// Desktop settings the page keeps otherwise: the light (light=), the ambient level (the
// page's is R,G,B) and the object's light count (the page's lights are its own).
const NOT_ADDRESS = ["theta_i", "phi_i", "ambient", "lights"];

export const clampTheta = (theta) => round(Math.min(Math.max(theta, 0), 90));
export const wrapPhi = (phi) => round(((phi % 360) + 540) % 360 - 180);

/** A registry setting's value from address text, or a note saying what to write. */
function readSetting(spec, name, text) {
  if (spec.kind === "bool") return { value: text !== "0" && text !== "false" };
  const index = spec.choices.indexOf(text);
  const number = index >= 0 ? index : Number(text);
  const lo = spec.min ?? -Infinity;
  const hi = spec.max ?? Infinity;
  if (text === "" || !Number.isFinite(number) || number < lo || number > hi || (spec.choices.length && number !== Math.round(number))) {
    const choices = spec.choices.map((c, i) => `${i} (${c})`).join(", ");
    const what = spec.choices.length ? `one of ${choices}` : spec.min === null ? "a number" : `a number from ${formatG(lo)} to ${formatG(hi)}`;
    return { note: `${name}=${text}: give ${what}` };
  }
  return { value: spec.kind === "int" ? Math.round(number) : number };
}

/** Reads location.hash into `lab` (what it leaves out has its default) and returns the
 * panels it names: [{name, values}] with values checked against each model's header. */
export function readHash(lab, hash = location.hash.slice(1)) {
  lab.resetLook();
  lab.views = [];
  lab.show = null;
  lab.plot = "polar";
  lab.scaleEach = false;
  const owned = {}; // key -> the page module that reads it
  for (const name of lab.pageViews) if (lab.modules[name].address) owned[lab.modules[name].address.key] = lab.modules[name];
  const ownedValues = {};
  const panels = [];
  const lights = [];
  const C = lab.constants;
  for (const [rawKey, value] of new URLSearchParams(hash)) {
    const key = OLD_KEYS[rawKey] ?? rawKey;
    if (key === "model") panels.push({ name: value, values: {} });
    else if (key === "light") {
      const [theta, phi, ...rest] = value.split(",").map(Number);
      const rgb = rest.length ? parseRgb(rest.join(",")) : [1, 1, 1];
      if (!Number.isFinite(theta) || (rest.length && !rgb)) {
        lab.notes.push(`light=${value}: write THETA,PHI in degrees, optionally ,R,G,B`);
      } else if (lights.length < C.MAX_LIGHTS) {
        lights.push({ theta: clampTheta(theta), phi: wrapPhi(Number.isFinite(phi) ? phi : 0), rgb });
      }
    } else if (key === "ambient") {
      const rgb = parseRgb(value);
      if (rgb) lab.ambient = rgb;
      else lab.notes.push(`ambient=${value}: write R,G,B (each 0 or more)`);
    } else if (key === "size" && lab.panels.length) {
      // The float targets have their size: a new size needs a reload.
      if (Math.round(Number(value)) !== lab.size) lab.notes.push("size=: reload the page to change the render size");
    } else if (key === "size") lab.size = Math.min(Math.max(Math.round(Number(value)) || DEFAULT_SIZE, 32), 1024);
    else if (key === "embed") lab.embed = value !== "0";
    else if (key === "show") lab.show = value.split(",").filter(Boolean);
    else if (key === "scale") {
      if (value === "each" || value === "shared") lab.scaleEach = value === "each";
      else lab.notes.push(`scale=${value}: write scale=each (each plot on its own scale) or scale=shared`);
    } else if (key === "plot") {
      if (value === "theta" || value === "polar") lab.plot = value;
      else lab.notes.push(`plot=${value}: write plot=polar or plot=theta (the lobe against θo)`);
    } else if (key === "views") {
      const names = value.split(",").filter(Boolean);
      const unknown = names.filter((n) => !lab.modules[n]);
      if (unknown.length) lab.notes.push(`views=${value}: unknown ${unknown.join(", ")}; choose from ${lab.pageViews.join(", ")}`);
      lab.views = lab.pageViews.filter((n) => names.includes(n));
    } else if (key in owned) ownedValues[key] = value;
    else if (key in lab.specs && !NOT_ADDRESS.includes(key)) {
      const { value: read, note } = readSetting(lab.specs[key], key, value);
      if (note) lab.notes.push(note);
      else lab.settings[key] = read;
    } else if (panels.length) panels[panels.length - 1].values[key] = value;
    else lab.notes.push(`${key}=${value}: give model=NAME before its parameters`);
  }
  for (const [key, module] of Object.entries(owned)) module.address.read(ownedValues[key] ?? null, lab);
  if (lights.length) lab.lights = lights;
  const kept = checkPanels(lab, panels);
  if (kept.length > MAX_PANELS) {
    const left = kept.slice(MAX_PANELS).map((p) => p.name);
    lab.notes.push(`at most ${MAX_PANELS} models side by side; left out: ${left.join(", ")}`);
  }
  return kept.slice(0, MAX_PANELS);
}

/** Each panel's values checked against its model's header; bad ones are noted and left out,
 * a model the page does not know is noted and its panel dropped. */
function checkPanels(lab, panels) {
  for (const panel of panels) {
    const model = lab.models[panel.name];
    if (lab.exerciseList.some((e) => e.name === panel.name)) continue; // exercise mode
    if (!model) {
      // An address keeps a model's name only: an opened file must be in this browser.
      lab.notes.push(lab.modelErrors[panel.name] ? `${panel.name}: ${lab.modelErrors[panel.name]}`
        : `unknown model ${panel.name}: it is not in the library and no file of that name was opened in ` +
        `this browser (an address keeps a model's name, not its file). Open its file (.glsl, .brdf or .binary) ` +
        `with "open file" to see it, or choose one of ${lab.order.join(", ")}`);
      panel.name = null;
      continue;
    }
    const checked = {};
    for (const [key, text] of Object.entries(panel.values)) {
      const p = model.params.find((q) => q.name === key);
      try {
        if (!p) throw new Error(`model ${model.name} has no parameter ${key}`);
        checked[key] = parseValue(p, text);
      } catch (err) {
        lab.notes.push(err.message);
      }
    }
    panel.values = checked;
  }
  return panels.filter((p) => p.name);
}

/** A registry setting as the address writes it. */
const settingText = (spec, value) => (spec.kind === "bool" ? (value ? "1" : "0") : formatG(round(value)));

/** The address of the page's state (the inverse of readHash). */
export function hashOf(lab) {
  const parts = [];
  for (const panel of lab.panels) {
    if (!panel.model) continue;
    parts.push(`model=${panel.name}`);
    for (const p of panel.model.params) {
      const v = panel.values[p.name];
      if (valueText(p, v) !== valueText(p, p.default)) parts.push(`${p.name}=${valueText(p, v)}`);
    }
  }
  for (const light of lab.lights) {
    const white = light.rgb.every((c) => c === 1);
    const rgb = white ? "" : `,${light.rgb.map(formatG).join(",")}`;
    parts.push(`light=${formatG(light.theta)},${formatG(light.phi)}${rgb}`);
  }
  if (lab.ambient.some((c) => c)) parts.push(`ambient=${lab.ambient.map(formatG).join(",")}`);
  if (lab.size !== DEFAULT_SIZE) parts.push(`size=${lab.size}`);
  if (lab.views.length) parts.push(`views=${lab.views.join(",")}`);
  for (const name of lab.pageViews) {
    const text = lab.modules[name].address?.write(lab);
    if (text) parts.push(text);
  }
  for (const [name, spec] of Object.entries(lab.specs)) {
    if (!NOT_ADDRESS.includes(name) && lab.settings[name] !== spec.default) parts.push(`${name}=${settingText(spec, lab.settings[name])}`);
  }
  if (lab.show) parts.push(`show=${lab.show.join(",")}`);
  if (lab.plot !== "polar") parts.push(`plot=${lab.plot}`);
  if (lab.scaleEach) parts.push("scale=each");
  if (lab.embed) parts.push("embed=1");
  return parts.join("&");
}

/** The address of a desktop preset: its models (library names), its light and its
 * settings under their own names; what the page cannot show is listed in `skipped`. */
export function presetHash(lab, preset, skipped = []) {
  const s = preset.settings || {};
  const parts = [];
  for (const entry of preset.model || []) {
    if (!lab.models[entry.model]) {
      skipped.push(`${entry.label || entry.model}: ${entry.model} opens in the desktop lab only`);
      continue;
    }
    parts.push(`model=${entry.model}`);
    for (const [k, v] of Object.entries(entry.values || {})) {
      parts.push(`${k}=${Array.isArray(v) ? v.map(formatG).join(",") : typeof v === "boolean" ? Number(v) : v}`);
    }
  }
  parts.push(`light=${formatG(s.theta_i ?? 30)},${formatG(s.phi_i ?? 0)}`);
  const views = (preset.views || []).filter((v) => lab.modules[v]);
  if (views.length) parts.push(`views=${views.join(",")}`);
  for (const [name, value] of Object.entries(s)) {
    if (name in lab.specs && !NOT_ADDRESS.includes(name)) parts.push(`${name}=${typeof value === "boolean" ? Number(value) : formatG(value)}`);
  }
  if (typeof s.ambient === "number" && s.ambient > 0) parts.push(`ambient=${formatG(s.ambient)}`);
  if (lab.size !== DEFAULT_SIZE) parts.push(`size=${lab.size}`);
  if (lab.embed) parts.push("embed=1");
  return parts.join("&");
}

// The lights' row of controls: θi and φi sliders, a colour and a remove button per light,
// the active light (the one dragging on a sphere moves) and the ambient level.
import { formatG } from "./header.js";
import { $, el } from "./dom.js";
import { fromHex, toHex } from "./controls.js";
import { clampTheta, wrapPhi } from "./hash.js";
import { fitEmbed } from "./panels.js";

/** Moves light `index` (the active one unless given) and shows it in its row. */
export function setLight(lab, theta, phi, index = lab.active) {
  const light = lab.lights[index];
  light.theta = clampTheta(theta);
  light.phi = wrapPhi(phi);
  const row = $(`.light-row[data-light="${index}"]`);
  if (row) {
    $(".theta", row).value = light.theta;
    $(".phi", row).value = light.phi;
    $(".theta-text", row).textContent = `${formatG(light.theta)}°`;
    $(".phi-text", row).textContent = `${formatG(light.phi)}°`;
  }
  lab.requestRender();
}

function setActiveLight(lab, index) {
  lab.active = index;
  document.querySelectorAll(".light-row").forEach((row) => {
    row.classList.toggle("active", lab.lights.length > 1 && Number(row.dataset.light) === index);
  });
}

/** One row of controls per light: theta_i, phi_i (degrees), colour, remove. */
export function buildLights(lab) {
  const rows = lab.lights.map((light, i) => {
    const first = i === 0;
    const thetaBox = el("input", { type: "range", class: "theta", min: 0, max: 90, step: 0.5,
      ...(first ? { id: "light-theta" } : {}) });
    const phiBox = el("input", { type: "range", class: "phi", min: -180, max: 180, step: 1,
      ...(first ? { id: "light-phi" } : {}) });
    thetaBox.addEventListener("input", () => setLight(lab, Number(thetaBox.value), lab.lights[i].phi, i));
    phiBox.addEventListener("input", () => setLight(lab, lab.lights[i].theta, Number(phiBox.value), i));
    const color = el("input", { type: "color", class: "light-color", value: toHex(light.rgb),
      title: "colour of this light (its radiance, before exposure)" });
    color.addEventListener("input", () => {
      lab.lights[i].rgb = fromHex(color.value);
      lab.requestRender();
    });
    const thetaTip = "θi: angle between the light and the view direction, which is the normal at " +
      "the sphere's centre (0° = light at the eye)";
    const phiTip = "φi: azimuth of the light around the view direction (0° = from the right, " +
      "90° = from the top)";
    const row = el("span", { class: "light-row group", "data-light": i,
      title: lab.lights.length > 1 ? "dragging on a sphere moves the framed light: click a row to choose" : "" },
      el("span", { class: "light-name" }, lab.lights.length > 1 ? `light ${i + 1}` : "light"),
      el("label", { title: thetaTip }, el("span", { class: "name" }, "θi"), " ", thetaBox),
      el("span", { class: "theta-text deg" }),
      el("label", { title: phiTip }, el("span", { class: "name" }, "φi"), " ", phiBox),
      el("span", { class: "phi-text deg" }), color);
    if (!first) {
      row.append(el("button", { type: "button", class: "close", title: "remove this light",
        onclick: () => {
          lab.lights.splice(i, 1);
          lab.active = 0;
          buildLights(lab);
          fitEmbed(lab);
          lab.requestRender();
        } }, "×"));
    }
    row.addEventListener("pointerdown", () => setActiveLight(lab, i));
    return row;
  });
  $("#lights").replaceChildren(...rows);
  lab.lights.forEach((light, i) => setLight(lab, light.theta, light.phi, i));
  $("#add-light").disabled = lab.lights.length >= lab.constants.MAX_LIGHTS;
  setActiveLight(lab, Math.min(lab.active, lab.lights.length - 1));
}

/** Another light (at most MAX_LIGHTS): by default opposite the first, 60° out. */
export function addLight(lab, light = null) {
  if (lab.lights.length >= lab.constants.MAX_LIGHTS) return;
  const first = lab.lights[0];
  lab.lights.push(light || { theta: 60, phi: wrapPhi(first.phi + 180), rgb: [1, 1, 1] });
  buildLights(lab);
  setActiveLight(lab, lab.lights.length - 1);
  fitEmbed(lab);
  lab.requestRender();
}

/** The ambient slider shows a grey level (an address may give any r,g,b). */
export function showAmbient(lab) {
  const [r, g, b] = lab.ambient;
  $("#ambient").value = Math.max(r, g, b);
  $("#ambient-text").textContent = r === g && g === b ? formatG(r) : lab.ambient.map(formatG).join(",");
}

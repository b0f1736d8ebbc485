// The controls of a model's parameters, built from its header: a slider with a text box
// (float), a colour picker (color), a checkbox (bool) or a menu (enum).
import { formatG } from "./header.js";
import { parseValue, sliderToValue, valueToSlider } from "./values.js";
import { el } from "./dom.js";
import { round } from "./state.js";

/** A value as the address and the text boxes write it. */
export function valueText(p, value) {
  if (p.kind === "color") return value.map((c) => formatG(c)).join(",");
  if (p.kind === "bool") return value ? "1" : "0";
  if (p.kind === "float") return formatG(value);
  return String(value);
}
export const toHex = (rgb) => "#" + rgb.map((c) => Math.round(Math.min(Math.max(c, 0), 1) * 255).toString(16).padStart(2, "0")).join("");
export const fromHex = (hex) => [1, 3, 5].map((i) => round(parseInt(hex.slice(i, i + 2), 16) / 255));

/** The row of controls of parameter `p` (slider and text box, colour, checkbox or menu),
 * showing `values[p.name]`; `set(value)` takes what the student chose. */
export function paramControl(p, values, set, steps) {
  const range = p.kind === "float"
    ? ` (${formatG(p.minimum)} to ${formatG(p.maximum)}${p.scale === "log" ? ", log slider" : ""})`
    : p.kind === "color" ? " (r,g,b each 0 to 1)" : "";
  const tip = `${p.name}: ${p.doc || "no description in the model's header"}${range}`;
  const label = el("label", { title: tip }, p.name);
  const row = el("div", { class: `param param-${p.kind}`, "data-param": p.name, title: tip }, label);
  if (p.kind === "float") {
    const slider = el("input", { type: "range", min: 0, max: steps, step: 1 });
    const box = el("input", { type: "text", class: "value", size: 6 });
    const show = () => {
      slider.value = valueToSlider(p, values[p.name], steps);
      box.value = formatG(round(values[p.name]));
    };
    slider.addEventListener("input", () => {
      set(round(sliderToValue(p, Number(slider.value), steps)));
      box.value = formatG(values[p.name]);
    });
    box.addEventListener("change", () => {
      try {
        set(parseValue(p, box.value));
        box.classList.remove("bad");
      } catch (err) {
        box.classList.add("bad");
        box.title = err.message;
      }
      show();
    });
    show();
    row.append(slider, box);
    if (p.scale === "log") row.append(el("span", { class: "scale" }, "log"));
  } else if (p.kind === "color") {
    const picker = el("input", { type: "color", value: toHex(values[p.name]) });
    const box = el("input", { type: "text", class: "value", size: 12, value: valueText(p, values[p.name]) });
    picker.addEventListener("input", () => {
      set(fromHex(picker.value));
      box.value = valueText(p, values[p.name]);
    });
    box.addEventListener("change", () => {
      try {
        set(parseValue(p, box.value));
        picker.value = toHex(values[p.name]);
        box.classList.remove("bad");
      } catch (err) {
        box.classList.add("bad");
        box.title = err.message;
      }
    });
    row.append(picker, box);
  } else if (p.kind === "bool") {
    const box = el("input", { type: "checkbox" });
    box.checked = values[p.name];
    box.addEventListener("change", () => set(box.checked));
    row.append(box);
  } else {
    const select = el("select", {}, ...p.choices.map((c) => el("option", { value: c }, c)));
    select.value = values[p.name];
    select.addEventListener("change", () => set(select.value));
    row.append(select);
  }
  return row;
}

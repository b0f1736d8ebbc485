// The row of panels: adding and removing one (at most MAX_PANELS), and fitting them into a
// slide's frame when the page is embedded in the lecture deck.
import { fitPlotAspect, showOnly } from "./deck.js";
import { $ } from "./dom.js";
import { Panel } from "./panel.js";
import { MAX_PANELS } from "./state.js";

/** "+ model" is off once the page shows as many models as it can. */
function showAddModel(lab) {
  const button = $("#add-model");
  button.disabled = lab.panels.length >= MAX_PANELS;
  button.title = button.disabled ? `at most ${MAX_PANELS} models side by side`
    : "show another model beside the others";
}

/** A new panel of model `name` at the end of the row (null when the row is full). */
export function addPanel(lab, name, values) {
  if (lab.panels.length >= MAX_PANELS) return null;
  const panel = new Panel(lab, name, values);
  lab.panels.push(panel);
  $("#panels").append(panel.root);
  panel.syncViews();
  showAddModel(lab);
  fitEmbed(lab);
  return panel;
}

/** Removes a panel (never the last one) and gives its WebGL context back. */
export function removePanel(lab, panel) {
  if (lab.panels.length <= 1) return;
  lab.panels.splice(lab.panels.indexOf(panel), 1);
  panel.destroy();
  showAddModel(lab);
  fitEmbed(lab);
  lab.requestRender();
}

/** Embedded in a slide: shrink the canvases until the page fits the frame unscrolled. */
export function fitEmbed(lab) {
  if (!lab.embed) return;
  document.body.classList.toggle("single", lab.panels.length === 1);
  showOnly(lab.show);
  lab.panels.forEach((panel) => fitPlotAspect(panel.polar, lab.panels.length));
  const root = document.documentElement;
  const apply = (px) => lab.panels.forEach((panel) => panel.displaySize(px));
  let px = lab.size;
  apply(px);
  for (let k = 0; k < 6; k++) {
    const over = Math.max(root.scrollHeight - innerHeight,
      (root.scrollWidth - innerWidth) / Math.max(1, lab.panels.length));
    if (over <= 0 || px <= 96) break;
    px = Math.max(96, Math.floor(px - over - 2));
    apply(px);
  }
}

// Small DOM helpers every page module uses: elements, PNG downloads, the box a view's
// canvas sits in, and the page's notes and tip lines.

export const $ = (selector, root = document) => root.querySelector(selector);

/** An element with attributes (on* become listeners) and children. */
export function el(tag, attrs = {}, ...children) {
  const node = document.createElement(tag);
  for (const [key, value] of Object.entries(attrs)) {
    if (key === "class") node.className = value;
    else if (key.startsWith("on")) node.addEventListener(key.slice(2), value);
    else node.setAttribute(key, value);
  }
  for (const child of children) node.append(child);
  return node;
}

/** Downloads a canvas as a PNG file (what is on screen: exposure and sRGB applied). */
export function savePng(canvas, filename) {
  canvas.toBlob((blob) => {
    const a = el("a", { href: URL.createObjectURL(blob), download: filename });
    document.body.append(a);
    a.click();
    a.remove();
    setTimeout(() => URL.revokeObjectURL(a.href), 1000);
  }, "image/png");
}

/** A canvas in a box with its own "PNG" button. */
export function viewBox(canvas, what, filename) {
  const button = el("button", { type: "button", class: "png", title: `save the ${what} as a PNG image` }, "PNG");
  button.addEventListener("click", () => savePng(canvas, filename()));
  return el("div", { class: "view", "data-view": what }, canvas, button);
}

/** Sets a node's text only when it changes: the same text written again still replaces the
 * node, so that the next read of a size (a plot's font) forces a layout mid-frame, and an
 * assistive technology may hear it again. */
export function setText(node, text) {
  if (node.textContent !== text) node.textContent = text;
}

const widths = new WeakMap(); // canvas -> its CSS width, kept by `resized`
let resized = null;
let redraw = () => {}; // onCanvasResize

/** Calls `callback` when a canvas whose width cssWidth keeps changes size (drawn since at
 * the old width: the page draws again with the new one). */
export function onCanvasResize(callback) {
  redraw = callback;
}

/** A canvas's CSS width (0 while hidden), read once and then kept by a ResizeObserver: a
 * read of clientWidth while a frame draws forces a layout of the page (most of a slider
 * frame's time, once the views' notes have changed). */
export function cssWidth(canvas) {
  if (!widths.has(canvas)) {
    resized ??= new ResizeObserver((entries) => {
      let changed = false;
      for (const entry of entries) {
        const width = entry.target.clientWidth; // laid out now: no layout forced
        changed ||= width !== widths.get(entry.target);
        widths.set(entry.target, width);
      }
      if (changed) redraw();
    });
    resized.observe(canvas);
    widths.set(canvas, canvas.clientWidth);
  }
  return widths.get(canvas);
}

/** The short name of a model for pickers: its title up to the first colon. */
export const shortTitle = (model, name) => (model?.title ? model.title.split(":")[0].trim() : name);

/** The page's notes (bad address values, kept files) under the toolbar. */
export function showNotes(notes) {
  $("#notes").textContent = notes.join("\n");
  $("#notes").hidden = !notes.length;
}

/** Help on tap: a label's meaning (its title) in a box at the bottom of the screen, for
 * phones and tablets, which show no tooltips. */
export function showTip(text) {
  $("#tip-text").textContent = text;
  $("#tip").hidden = !text;
}

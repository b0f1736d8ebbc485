// When the page draws: at most once a frame after a change (scheduleRender), coarse while
// the hand moves a slider or drags (the costly views), at full quality SETTLE_MS after it
// stops; the address follows, but while the hand moves at most every HASH_MS.
import { drawPolars } from "./polar.js";
import { hashOf } from "./hash.js";

const SETTLE_MS = 200;
const HASH_MS = 250;

let lab = null; // the page's LabState (startScheduler)
let pending = 0; // requestAnimationFrame id of the next frame, 0: none
let settle = 0;
let handMoving = false; // a slider or a drag moved within SETTLE_MS
let hashWritten = -Infinity; // performance.now() of the last address update
let hashTimer = 0;

/** Takes `state`'s render requests from now on (its views call state.requestRender()). */
export function startScheduler(state) {
  lab = state;
  lab.renderListener = scheduleRender;
  addEventListener("input", (e) => e.target.type === "range" && moving(), true);
  addEventListener("pointermove", (e) => e.buttons && e.target.tagName === "CANVAS" && moving(), true);
}

/** While the hand moves (slider input, drag) a large sphere draws at half resolution and
 * the costly views coarse; the full version follows SETTLE_MS after the last move. */
function moving() {
  clearTimeout(settle);
  lab.fast = true;
  handMoving = true;
  settle = setTimeout(() => {
    handMoving = false;
    writeHash();
    if (!lab.fast) return;
    lab.fast = false;
    scheduleRender();
  }, SETTLE_MS);
}

/** The address shows the page's state now. */
export function writeHash() {
  clearTimeout(hashTimer);
  hashTimer = 0;
  hashWritten = performance.now();
  history.replaceState(null, "", `#${hashOf(lab)}`);
}

/** The address follows the page: at once, but while the hand moves at most every HASH_MS
 * (and once it stops). An update per frame would cost the frame milliseconds now and
 * then, and browsers stop taking them after a few hundred in ten seconds. */
function writeHashSoon() {
  if (!handMoving) return writeHash();
  if (hashTimer) return;
  const wait = hashWritten + HASH_MS - performance.now();
  if (wait <= 0) writeHash();
  else hashTimer = setTimeout(writeHash, wait);
}

function scheduleRender() {
  writeHashSoon();
  if (!pending) pending = requestAnimationFrame(() => {
    pending = 0;
    renderAll();
  });
}

/** Drops a frame already asked for (the caller draws now). */
export function cancelFrame() {
  if (pending) cancelAnimationFrame(pending);
  pending = 0;
}

export function renderAll() {
  for (const panel of lab.panels) panel.render();
  drawPolars(lab);
}

/** Renders every panel now and waits until the GPU is done; returns milliseconds. */
export function renderNow() {
  const start = performance.now();
  renderAll();
  for (const panel of lab.panels) panel.gl?.finish();
  return performance.now() - start;
}

/** Full quality now (readers want what the page shows once the hand stops). */
export function settleNow() {
  if (!lab.fast) return;
  clearTimeout(settle);
  handMoving = false;
  lab.fast = false;
  renderNow();
  writeHash();
}

/** No settling pending (a benchmark drives the coarse frames itself). */
export function stopSettling() {
  clearTimeout(settle);
}

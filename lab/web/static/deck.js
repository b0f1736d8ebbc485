// The lab embedded in a slide (embed=1): text sized for the back of a hall, only the controls
// the slide names (show=), and a lobe plot against θo (plot=theta) that shows where a peak is.
import { formatG } from "./header.js";

/** Names that `show=` accepts besides the models' parameters: groups of the toolbar. */
export const TOOLBAR_GROUPS = {
  exposure: "label:has(#exposure)",
  ambient: "label:has(#ambient)",
  cos: "label:has(#cos-weighted)",
  lights: "#add-light, .light-color, .light-row .close",
};

/** The text size (CSS px) of the page: the canvases draw their labels at this size on screen. */
export const pageFontPx = () => parseFloat(getComputedStyle(document.body).fontSize) || 14;

/** Hides every parameter row and toolbar group the address's `show=` list leaves out (the
 * light's own sliders always stay); with no list, everything shows. */
export function showOnly(names) {
  for (const row of document.querySelectorAll(".panel .param")) {
    row.hidden = Boolean(names) && !names.includes(row.dataset.param);
  }
  for (const [name, selector] of Object.entries(TOOLBAR_GROUPS)) {
    for (const node of document.querySelectorAll(selector)) {
      node.classList.toggle("deck-hidden", Boolean(names) && !names.includes(name));
    }
  }
}

/** Embedded with several models side by side, a panel is narrow and the frame has room
 * below: the plot's canvas is taller than alone (0.8 of its width, not 0.62), so the half
 * disc grows and its ring values fit in a row under the baseline, clear of the L mark. */
export function fitPlotAspect(canvas, panels) {
  const height = Math.round(canvas.width * (panels > 1 ? 0.8 : 0.62));
  if (canvas.height !== height) canvas.height = height; // cleared: the next render draws it
}

/** The angle (whole degrees, -90..90) where a lobe peaks, leaving out grazing as the scale does. */
export function peakAngle(lum, grazingDeg) {
  let best = -1;
  lum.forEach((f, i) => {
    if (Math.abs(i - 90) <= grazingDeg && (best < 0 || f > lum[best])) best = i;
  });
  return best - 90;
}

/** The θo range [lo, hi] where a lobe is above 5% of its peak, with the mirror direction
 * (in the plane of incidence) or the peak in it. */
export function lobeRange(lum, thetaI, grazingDeg, inPlane) {
  const peak = peakAngle(lum, grazingDeg);
  const top = Math.max(...lum.filter((_, i) => Math.abs(i - 90) <= grazingDeg), 0);
  let lo = inPlane ? thetaI : peak;
  let hi = lo;
  lum.forEach((f, i) => {
    if (top > 0 && f >= 0.05 * top) {
      lo = Math.min(lo, i - 90);
      hi = Math.max(hi, i - 90);
    }
  });
  return [lo, hi];
}

/** One θo range for lobes plotted side by side (plot=theta): their axes match, so the
 * mirror and peak marks of two plots line up. */
export function sharedRange(lums, thetaI, grazingDeg, inPlane) {
  const ranges = lums.map((lum) => lobeRange(lum, thetaI, grazingDeg, inPlane));
  return [Math.min(...ranges.map((r) => r[0])), Math.max(...ranges.map((r) => r[1]))];
}

/** A tick step of whole degrees that gives at most `room` gaps over `span`. */
const niceStep = (span, room) => [5, 10, 15, 30, 45, 90].find((s) => span / s <= Math.min(room, 6)) || 90;

/**
 * One lobe against θo on linear axes, zoomed to where it is above 5% of its peak (always with
 * the mirror direction in view): the peak and the mirror direction are marked and named, so a
 * peak past the mirror direction shows as a gap between two lines. `lum` holds the values at
 * θo = -90..90 in 1-degree steps (positive: the mirror side); `scale` is the top of the axis.
 */
export function drawCurve(canvas, curve, thetaI, scale, { fontPx, what, grazingDeg, inPlane, range }) {
  const ctx = canvas.getContext("2d");
  const w = canvas.width;
  const h = canvas.height;
  const font = Math.round((fontPx * w) / (canvas.clientWidth || w));
  ctx.clearRect(0, 0, w, h);
  ctx.font = `${font}px system-ui, sans-serif`;
  const { lum } = curve;
  const peak = peakAngle(lum, grazingDeg);
  // The θo range: where the lobe is above 5% of its peak, and the mirror direction (or the
  // range given, shared with the plots beside it).
  let [lo, hi] = range || lobeRange(lum, thetaI, grazingDeg, inPlane);
  // Ticks far enough apart for their labels ("-30°" is the widest).
  const room = Math.max(1, Math.floor((w - 1.5 * font) / (ctx.measureText("-30°").width + font)));
  const step = niceStep(Math.max(hi - lo, 10), room);
  lo = Math.max(-90, Math.floor(lo / step) * step);
  hi = Math.min(90, Math.max(Math.ceil(hi / step) * step, lo + step));
  const left = Math.round(0.4 * font);
  const right = w - Math.round(0.6 * font);
  const x = (deg) => left + ((deg - lo) / (hi - lo)) * (right - left);
  // The peak (solid line) and the mirror direction (dashed), named above the plot.
  const labels = [];
  if (inPlane && !(scale > 0 && peak === thetaI)) labels.push([thetaI, `mirror ${formatG(thetaI)}°`, "#ccc"]);
  if (scale > 0) labels.push([peak, inPlane && peak === thetaI ? `peak = mirror ${peak}°` : `peak ${peak}°`, curve.color]);
  const placed = placeLabels(ctx, labels, x, w, 0.6 * font);
  const rows = Math.max(0, ...placed.map((p) => p.row));
  const plotTop = Math.round((2.6 + 1.1 * rows) * font);
  const bottom = h - Math.round(1.4 * font);
  const y = (f) => bottom - Math.min(Math.max(f / scale, 0), 1) * (bottom - plotTop);
  // Axes and θo ticks.
  ctx.strokeStyle = "#8888";
  ctx.lineWidth = 1;
  ctx.beginPath();
  ctx.moveTo(left, plotTop);
  ctx.lineTo(left, bottom);
  ctx.lineTo(right, bottom);
  ctx.stroke();
  ctx.fillStyle = "#bbb";
  ctx.textBaseline = "top";
  for (let deg = lo; deg <= hi; deg += step) {
    const text = `${deg}°`;
    const width = ctx.measureText(text).width;
    ctx.fillText(text, Math.min(Math.max(x(deg) - width / 2, 0), w - width), bottom + 0.15 * font);
  }
  ctx.textBaseline = "alphabetic";
  // The lobe.
  if (scale > 0) {
    ctx.strokeStyle = curve.color;
    ctx.fillStyle = `${curve.color}33`;
    ctx.lineWidth = Math.max(2, font / 8);
    ctx.beginPath();
    ctx.moveTo(x(lo), bottom);
    for (let deg = lo; deg <= hi; deg++) ctx.lineTo(x(deg), y(lum[deg + 90]));
    ctx.lineTo(x(hi), bottom);
    ctx.fill();
    ctx.stroke();
  }
  const mark = (deg, color, dash) => {
    ctx.strokeStyle = color;
    ctx.lineWidth = Math.max(2, font / 10);
    ctx.setLineDash(dash);
    ctx.beginPath();
    ctx.moveTo(x(deg), plotTop - 0.2 * font);
    ctx.lineTo(x(deg), bottom);
    ctx.stroke();
    ctx.setLineDash([]);
  };
  if (inPlane) mark(thetaI, "#aaa", [6, 5]);
  if (scale > 0) mark(peak, curve.color, []);
  for (const p of placed) {
    ctx.fillStyle = p.color;
    ctx.fillText(p.text, p.at, plotTop - (0.45 + 1.1 * (rows - p.row)) * font);
  }
  ctx.fillStyle = "#bbb";
  const value = `${formatG(Number(scale.toPrecision(2)))} sr⁻¹`;
  const title = [`${what}, top: ${value}`, `top: ${value}`, value].find((t) => ctx.measureText(t).width <= w) || value;
  ctx.fillText(title, 0, 0.95 * font);
  return { peakDeg: peak, mirrorDeg: thetaI, range: [lo, hi], scale, font };
}

/** Labels [deg, text, colour] over their lines at x(deg): centred; two that would overlap go
 * either side of their lines, and the second onto a row of its own if the canvas is too narrow. */
function placeLabels(ctx, labels, x, w, gap) {
  const placed = [...labels].sort((a, b) => a[0] - b[0]).map(([deg, text, color]) => {
    const width = ctx.measureText(text).width;
    return { text, color, width, line: x(deg), at: x(deg) - width / 2, row: 0 };
  });
  const clamp = (p) => (p.at = Math.min(Math.max(p.at, 0), w - p.width));
  placed.forEach(clamp);
  if (placed.length === 2 && placed[0].at + placed[0].width + gap > placed[1].at) {
    const [a, b] = placed;
    a.at = a.line - a.width;
    b.at = b.line;
    clamp(b);
    a.at = Math.min(a.at, b.at - gap - a.width);
    clamp(a);
    if (a.at + a.width + gap > b.at) {
      a.at = a.line - a.width / 2;
      clamp(a);
      b.row = 1;
    }
  }
  return placed;
}

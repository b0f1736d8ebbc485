// The page's part of the one scaling rule of every plot of f_r (lab/plotscale.py): the
// scale's top leaves out values beyond the grazing cut-off, and the log scale spans a fixed
// number of decades below the top. tests/test_web_mirrors.py runs these against the Python.
// Why in JavaScript too: the page scales its own plots of models Python never sees (opened or
// edited files).
import { cssWidth } from "./dom.js";

/** The largest finite value of `values` (sampled at thetaO, degrees) with |thetaO| within
 * grazingDeg; 0 when there is none (plotscale.peak_value). */
export function peakValue(thetaO, values, grazingDeg) {
  let peak = -Infinity;
  values.forEach((v, i) => {
    if (Math.abs(thetaO[i]) <= grazingDeg && Number.isFinite(v)) peak = Math.max(peak, v);
  });
  return peak === -Infinity ? 0 : peak;
}

/** Radius (0..1 of the plot's) of value f on a scale whose outer circle is `top`
 * (plotscale.Scale.radius): linear, or `decades` decades below the top on a log scale. */
export function polarRadius(f, top, log, decades) {
  const v = Number.isNaN(f) ? 0 : f;
  let r;
  if (log) {
    const floor = top * Math.pow(10, -decades);
    r = Math.log10(Math.max(v, floor) / floor) / decades;
  } else {
    r = v / top;
  }
  return Math.min(Math.max(r, 0), 1);
}

/** Axes text for a canvas plot: a small font in canvas pixels. */
export function font(ctx, canvas, px = 12) {
  const size = Math.round((px * canvas.width) / (cssWidth(canvas) || canvas.width));
  ctx.font = `${size}px system-ui, sans-serif`;
  return size;
}

/** A canvas's 2D context cleared for a new plot, with the axes font (font()) and grey text:
 * {ctx, px}. */
export function clearedPlot(canvas) {
  const ctx = canvas.getContext("2d");
  const px = font(ctx, canvas);
  ctx.clearRect(0, 0, canvas.width, canvas.height);
  ctx.fillStyle = "#bbb";
  return { ctx, px };
}

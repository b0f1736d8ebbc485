// The polar plots: each panel's lobe in the plane of incidence of light 1 (or the plane
// turned by φo), every panel on one scale, and all models overlaid when there are several.
// The scale's rule is lab/plotscale.py's (plotscale.js, with its parity test).
import { formatG } from "./header.js";
import { drawCurve, pageFontPx, sharedRange } from "./deck.js";
import { peakValue, polarRadius as scaleRadius } from "./plotscale.js";
import { $, cssWidth } from "./dom.js";
import { POLAR_STEPS } from "./panel.js";
import { round } from "./state.js";

/** Luminance with the lab's weights (lab/constants.py LUMA). */
const luma = (C, r, g, b) => C.LUMA[0] * r + C.LUMA[1] * g + C.LUMA[2] * b;

/** A panel's lobe as plotted: luminance of f_r (times cos θo when asked), its peak away from
 * grazing (where some models diverge) and its delta spike's luminance. */
function lobeLuminance(lab, panel) {
  const C = lab.constants;
  const values = panel.lobe;
  const lum = [];
  const thetaO = [];
  for (let i = 0; i < POLAR_STEPS; i++) {
    let f = luma(C, values[4 * i], values[4 * i + 1], values[4 * i + 2]);
    if (lab.settings.polar_cos) f *= Math.cos(((i - 90) * Math.PI) / 180);
    f = Number.isFinite(f) ? Math.max(f, 0) : 0;
    lum.push(f);
    thetaO.push(i - 90);
  }
  const peak = peakValue(thetaO, lum, C.GRAZING_DEG);
  return { lum, peak, spike: panel.spike ? luma(C, ...panel.spike) : null, color: panel.color, name: panel.name };
}

/** Every polar plot on one scale: each panel's, and all models overlaid when there are
 * several. The outer circle is the largest peak; with a delta spike at least 1, so a
 * spike's length is its reflectance (the whole circle = all the light). */
export function drawPolars(lab) {
  const C = lab.constants;
  const curves = lab.panels.filter((p) => p.lobe && p.model).map((p) => [p, lobeLuminance(lab, p)]);
  const scale = Math.max(0, ...curves.map(([, c]) => (c.spike !== null ? Math.max(c.peak, 1) : c.peak)));
  const theta = lab.lights[0].theta;
  const own = (curve) => (curve.spike !== null ? Math.max(curve.peak, 1) : curve.peak);
  for (const [panel, curve] of curves) {
    const each = lab.scaleEach ? own(curve) : scale;
    panel.polarGeometry = lab.plot === "theta"
      ? drawCurve(panel.polar, curve, theta, each, { fontPx: pageFontPx(), grazingDeg: C.GRAZING_DEG,
        what: lab.settings.polar_cos ? "fᵣ cos θₒ" : "fᵣ", inPlane: lab.settings.phi_o === 0,
        range: sharedRange(curves.map(([, c]) => c.lum), theta, C.GRAZING_DEG, lab.settings.phi_o === 0) })
      : drawPolar(lab, panel.polar, [curve], theta, each);
  }
  const overlay = $("#overlay");
  overlay.hidden = curves.length < 2;
  if (!overlay.hidden) lab.overlayGeometry = drawPolar(lab, $("#overlay canvas"), curves.map(([, c]) => c), theta, scale, true);
}


/** Lobes on a half disc, 0 deg = the normal, rings labelled with their values. */
function drawPolar(lab, canvas, curves, thetaI, scale, legend = false) {
  const C = lab.constants;
  const log = lab.settings.polar_log;
  // Radius (0..1 of the plot's) of value f on a scale whose outer circle is `scale`.
  const polarRadius = (f, top) => scaleRadius(f, top, log, C.PLOT_DECADES);
  const ctx = canvas.getContext("2d");
  const w = canvas.width;
  const h = canvas.height;
  // Text the same size on screen whatever the canvas is scaled to (embedded demos shrink it).
  const shown = cssWidth(canvas) || w;
  const font = lab.embed ? Math.round((pageFontPx() * w) / shown) : Math.min(Math.round((12 * w) / shown), Math.round(w / 14));
  const ringFont = Math.round(font * (lab.embed ? 1 : 0.85));
  const cx = w / 2;
  // Ring values clear of the lobes: in a row below the baseline, or (where that gives the
  // larger disc: a short canvas, a slide's) only the rim's, beside the rim.
  ctx.font = `${ringFont}px system-ui, sans-serif`;
  const rimText = formatG(Number(scale.toPrecision(2)));
  const rimRoom = ctx.measureText(rimText).width + 0.3 * ringFont + 2;
  const above = (lab.embed ? 3.8 : 3.5) * font;
  const bottom = Math.round(ringFont * 1.25);
  const below = Math.min(w / 2 - 2.2 * font, h - bottom - above);
  const beside = Math.min(w / 2 - Math.max(2.2 * font, rimRoom), h - Math.round(font * 0.6) - above);
  const rowBelow = below >= beside;
  const cy = h - (rowBelow ? bottom : Math.round(font * 0.6));
  const radius = Math.max(rowBelow ? below : beside, 8);
  ctx.clearRect(0, 0, w, h);
  ctx.font = `${font}px system-ui, sans-serif`;
  ctx.lineWidth = 1.5; // a thinner line's antialiased pixels fall under 3:1
  // Rings: quarters of the scale, or one per decade on the log scale; values beside them.
  const rings = log
    ? Array.from({ length: C.PLOT_DECADES }, (_, k) => [(C.PLOT_DECADES - k) / C.PLOT_DECADES, scale * Math.pow(10, -k)])
    : [0.25, 0.5, 0.75, 1].map((r) => [r, r * scale]);
  ctx.strokeStyle = "#a0a6b0"; // axes and rings at 3:1 or more against the panel, antialiased (WCAG 1.4.11)
  ctx.beginPath();
  ctx.moveTo(cx - radius, cy);
  ctx.lineTo(cx + radius, cy);
  ctx.moveTo(cx, cy);
  ctx.lineTo(cx, cy - radius);
  ctx.stroke();
  // Negative angles (toward the light) on the right: the light on the same side as on the
  // spheres and the 3D lobe.
  const at = (angleDeg, r) => {
    const a = (angleDeg * Math.PI) / 180;
    return [cx - r * Math.sin(a), cy - r * Math.cos(a)];
  };
  ctx.fillStyle = "#999";
  ctx.font = `${ringFont}px system-ui, sans-serif`;
  // Each value centred under its ring, from the rim inward (the rim's always shows, kept
  // inside the canvas); one that would run into the last one drawn is left out.
  let end = w - 2;
  const ringLabels = []; // [text, left, top, right, bottom] of each value drawn
  for (const [r, value] of [...rings].sort((a, b) => b[0] - a[0])) {
    ctx.strokeStyle = r === 1 ? "#a0a6b0" : "#8a909c";
    ctx.beginPath();
    ctx.arc(cx, cy, radius * r, Math.PI, 2 * Math.PI);
    ctx.stroke();
    const text = formatG(Number(value.toPrecision(2)));
    const width = ctx.measureText(text).width;
    if (scale <= 0) continue;
    if (!rowBelow) {
      const x = cx + radius + 0.3 * ringFont;
      if (r === 1) {
        ctx.fillText(text, x, cy - 3);
        ringLabels.push([text, x, cy - 3 - ringFont, x + width, cy - 3]);
      }
      continue;
    }
    const centred = cx + radius * r - width / 2;
    const x = r === 1 ? Math.min(centred, end - width) : centred;
    if (x + width <= end) {
      ctx.textBaseline = "top";
      ctx.fillText(text, x, cy + 2);
      ctx.textBaseline = "alphabetic";
      ringLabels.push([text, x, cy + 2, x + width, cy + 2 + ringFont]);
      end = x - 0.5 * ringFont;
    }
  }
  ctx.font = `${font}px system-ui, sans-serif`;
  const ray = (angleDeg, r, color, dash) => {
    ctx.strokeStyle = color;
    ctx.setLineDash(dash);
    ctx.beginPath();
    ctx.moveTo(cx, cy);
    ctx.lineTo(...at(angleDeg, r));
    ctx.stroke();
    ctx.setLineDash([]);
  };
  const label = (text, angleDeg, r, color, dx = 0) => {
    ctx.fillStyle = color;
    ctx.textAlign = "center";
    ctx.textBaseline = "middle";
    const [x, y] = at(angleDeg, r);
    ctx.fillText(text, x + dx, y);
    ctx.textAlign = "left";
    ctx.textBaseline = "alphabetic";
  };
  const inPlane = lab.settings.phi_o === 0;
  if (inPlane) {
    ray(-thetaI, radius, "#e0a030", []); // toward the light
    ray(thetaI, radius, "#a0a6b0", [4, 4]); // mirror direction
  }
  // Near normal incidence L and R sit on N: one merged label instead of three on top of
  // each other; a little further out, L and R pushed apart either side.
  if (!inPlane) label("N", 0, radius + 0.7 * font, "#aaa");
  else if (thetaI < 4) label("N = L = R", 0, radius + 0.7 * font, "#e0a030");
  else {
    if (thetaI >= 12) label("N", 0, radius + 0.7 * font, "#aaa");
    label("L", -thetaI, radius + 0.8 * font, "#e0a030", thetaI < 12 ? 0.6 * font : 0);
    label("R", thetaI, radius + 0.8 * font, "#aaa", thetaI < 12 ? -0.6 * font : 0);
  }
  const what = lab.settings.polar_cos ? "fᵣ cos θₒ" : "fᵣ";
  ctx.fillStyle = "#bbb";
  const plane = inPlane ? "plane of incidence" : `plane turned φo = ${formatG(lab.settings.phi_o)}°`;
  const title = `${what}, ${plane}${lab.lights.length > 1 ? " of light 1" : ""}`;
  ctx.fillText(ctx.measureText(title).width < w - 4 ? title : `${what}, light 1`, 2, font);
  const spikes = curves.some((c) => c.spike !== null);
  const peak = Math.max(0, ...curves.map((c) => c.peak));
  const circle = spikes && peak < 1 ? "1 (all the light)" : `${formatG(round(scale))} sr⁻¹`;
  const logText = log ? `, log: ${C.PLOT_DECADES} decades` : "";
  // The shared rule (lab/plotscale.py): grazing values beyond GRAZING_DEG stay out of the
  // scale; what exceeds it is drawn at the rim, marked, and its largest value named.
  const over = [];
  for (const curve of curves) {
    curve.lum.forEach((f, i) => scale > 0 && f > scale * (1 + 1e-6) && over.push([curve, i]));
  }
  const clippedMax = over.length ? Math.max(...over.map(([c, i]) => c.lum[i])) : 0;
  const clipped = over.length ? `; ▼ clipped: up to ${formatG(round(clippedMax))} sr⁻¹` : "";
  // The longest wording that fits (large text in a slide leaves little room).
  const fit = (...texts) => texts.find((t) => ctx.measureText(t).width <= w - 4) || texts[texts.length - 1];
  ctx.fillText(scale > 0 ? fit(`outer circle: ${circle}${logText}${clipped}`, `outer circle: ${circle}${logText}`,
    `outer: ${circle}`) : "fᵣ = 0 in this plane", 2, 2.2 * font);
  let spikeLength = 0;
  let spikeLabel = null; // [left, top, right, bottom] of the spike's value
  for (const curve of curves) {
    if (curve.peak > 0 || curve.lum.some((f) => f > 0)) {
      ctx.strokeStyle = curve.color;
      ctx.fillStyle = `${curve.color}33`;
      ctx.lineWidth = 2;
      ctx.beginPath();
      ctx.moveTo(cx, cy);
      curve.lum.forEach((f, i) => ctx.lineTo(...at(i - 90, radius * polarRadius(f, scale))));
      ctx.closePath();
      if (curves.length === 1) ctx.fill();
      ctx.stroke();
    }
    if (curve.spike !== null) {
      ctx.lineWidth = 4;
      spikeLength = radius * polarRadius(curve.spike, scale);
      ray(thetaI, spikeLength, curves.length === 1 ? "#ff5a5a" : curve.color, []);
      ctx.lineWidth = 1;
      ctx.fillStyle = "#ff7a7a";
      // Below the spike's middle, on its outer side: clear of the spike (it leans outward
      // above there), the normal and the light's ray; kept inside the canvas.
      const text = `δ spike, ρ = ${formatG(round(curve.spike))}`;
      const [x, y] = at(thetaI, spikeLength * 0.5);
      const width = ctx.measureText(text).width;
      const [left, base] = [Math.min(Math.max(x - 6 - width, 2), w - width - 2), Math.max(y + font, 3.2 * font)];
      ctx.fillText(text, left, base);
      spikeLabel = [left, base - font, left + width, base];
    }
  }
  ctx.fillStyle = "#dc283c";
  for (const [, i] of over) {
    const [x, y] = at(i - 90, radius);
    ctx.beginPath();
    ctx.moveTo(x - 4, y - 6);
    ctx.lineTo(x + 4, y - 6);
    ctx.lineTo(x, y);
    ctx.fill();
  }
  ctx.lineWidth = 1;
  if (legend) {
    curves.forEach((curve, k) => {
      // Names in the text colour (4.5:1), each after a bar of its curve's colour.
      const text = curve.name;
      const [x, y] = [w - ctx.measureText(text).width - 4, (k + 2.6) * 1.2 * font];
      ctx.fillStyle = "#e6e6e6";
      ctx.fillText(text, x, y);
      ctx.fillStyle = curve.color;
      ctx.fillRect(x - 1.6 * font, y - 0.45 * font, 1.2 * font, 0.3 * font);
    });
  }
  return { radius, scale, spikeLength, centre: [cx, cy], ringLabels, spikeLabel };
}

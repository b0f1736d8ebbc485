// Owns: the views other than the polar plot in words (lit sphere, lit object, IBL picture,
// albedo, image slice, 3D lobe, D/G/F terms, spherical harmonics), for readers who cannot see
// them. The mirror of lab/describe_views.py; tests/test_a11y_views.py holds both to one
// fixture. Why in JavaScript too: the page works alone (a file opened, a slide's demo) and
// describes the numbers its own views computed, as the desktop app says them.
// Images: { width, height, data } (float RGBA, row 0 at the top).
import { UNIT, deg, fmt, pyRound } from "./describe.js";

const NEAR_DEG = 2;
const FLAT = 0.97; // describe.js: a lowest value this share of the largest is constant
const LIT = 0.01;
const GAIN = 1e-3;
const SH_GOOD = 0.05;
const RAD = Math.PI / 180;

const share = (count, total) => `${total ? pyRound((100 * count) / total) : 0} %`;
const angle = (a, b) => Math.acos(Math.min(Math.max(a[0] * b[0] + a[1] * b[1] + a[2] * b[2], -1), 1)) / RAD;
const light = (t, p) => [Math.sin(t * RAD) * Math.cos(p * RAD), Math.sin(t * RAD) * Math.sin(p * RAD), Math.cos(t * RAD)];
const nonfinite = (count) => (count ? ` ${count} pixels are not finite (NaN or ∞).` : "");

/** Luminance of every pixel, whether it is drawn (alpha > 0), and the first brightest finite
 * drawn pixel (index, value), the lit and bad counts. */
function scan({ width, height, data }, luma, everyPixel = false) {
  const n = width * height;
  const lum = new Float64Array(n);
  let k = -1;
  let drawn = 0;
  let bad = 0;
  for (let j = 0; j < n; j++) {
    lum[j] = luma[0] * data[4 * j] + luma[1] * data[4 * j + 1] + luma[2] * data[4 * j + 2];
    if (!everyPixel && !(data[4 * j + 3] > 0)) continue;
    drawn++;
    if (!Number.isFinite(lum[j])) bad++;
    else if (k < 0 || lum[j] > lum[k]) k = j;
  }
  const inside = (j) => (everyPixel || data[4 * j + 3] > 0) && Number.isFinite(lum[j]);
  return { lum, k, peak: k < 0 ? -Infinity : lum[k], drawn, bad, inside };
}

function litCount(s, n) {
  let lit = 0;
  for (let j = 0; j < n; j++) if (s.inside(j) && s.lum[j] >= LIT * s.peak) lit++;
  return lit;
}

/** A lit sphere: its brightest point, that point's normal against the halfway vector and the
 * light, the share of the disc lit (describe_views.py: sphere). */
export function sphere(name, image, thetaI, phiI, luma, more = []) {
  const { width, height } = image;
  const s = scan(image, luma);
  const lights = [[thetaI, phiI], ...more];
  const where = more.length ? `${lights.length} lights, light 1` : "light";
  const head = `${name} on a sphere, ${where} at θi ${deg(thetaI)}, φi ${deg(phiI)}: `;
  const bad = nonfinite(s.bad);
  if (!s.drawn || s.peak <= 0) return `${head}black everywhere.${bad}`;
  const row = Math.floor(s.k / width);
  const col = s.k % width;
  const x = ((col + 0.5) / width) * 2 - 1;
  const y = 1 - ((row + 0.5) / height) * 2;
  const normal = [x, y, Math.sqrt(Math.max(1 - x * x - y * y, 0))];
  let best = null; // [angle to the halfway vector, light number, angle to the light]
  lights.forEach(([t, p], j) => {
    const L = light(t, p);
    const h = [L[0], L[1], L[2] + 1];
    const len = Math.hypot(...h);
    const toHalf = angle(normal, h.map((c) => c / len));
    if (best === null || toHalf < best[0]) best = [toHalf, j + 1, angle(normal, L)];
  });
  const which = more.length ? [`the halfway vector of light ${best[1]}`, "that light"] : ["the halfway vector", "the light"];
  return `${head}brightest ${fmt(s.peak)} where the normal is ${deg(best[0])} from ${which[0]} ` +
    `and ${deg(best[2])} from ${which[1]}; ` +
    `${share(litCount(s, width * height), s.drawn)} of the disc lit.${bad}`;
}

function where(row, col, height, width) {
  const v = ["top", "middle", "bottom"][Math.min(Math.floor((3 * row) / height), 2)];
  const h = ["left", "centre", "right"][Math.min(Math.floor((3 * col) / width), 2)];
  if (v === "middle") return h === "centre" ? "centre" : h;
  return h === "centre" ? v : `${v} ${h}`;
}

/** A rendered picture (lit object, IBL): brightest point and where, mean, share lit. */
export function picture(name, what, image, luma) {
  const { width, height } = image;
  const s = scan(image, luma);
  const head = `${what} of ${name}: `;
  const bad = nonfinite(s.bad);
  if (s.k < 0 || s.peak <= 0) return `${head}black everywhere.${bad}`;
  let sum = 0;
  let count = 0;
  for (let j = 0; j < width * height; j++) if (s.inside(j)) { sum += s.lum[j]; count++; }
  const row = Math.floor(s.k / width);
  return `${head}brightest ${fmt(s.peak)} at the ${where(row, s.k % width, height, width)}; ` +
    `mean ${fmt(sum / count)}; ${share(litCount(s, width * height), s.drawn)} of it lit.${bad}`;
}

/** The directional albedo against θi: ends, largest value, energy gain. */
export function albedo(name, thetas, values) {
  const head = `${name}: directional albedo `;
  if (!thetas.length) return `${head}not computed yet.`;
  let top = -1;
  values.forEach((a, k) => { if (Number.isFinite(a) && (top < 0 || a > values[top])) top = k; });
  if (top < 0) return `${head}not finite at any θi.`;
  const n = values.length;
  const text = `${head}${fmt(values[0])} at θi ${deg(thetas[0])} to ${fmt(values[n - 1])} at θi ${deg(thetas[n - 1])}; ` +
    `largest ${fmt(values[top])} at θi ${deg(thetas[top])}; `;
  const gain = values.map((a, k) => (a <= 1 + GAIN ? -1 : k)).filter((k) => k >= 0);
  if (!gain.length) return `${text}above 1 nowhere.`;
  return `${text}above 1 (energy gain, not physical) at ${gain.length} of ${n} angles, ` +
    `θi ${deg(thetas[gain[0]])} to ${deg(thetas[gain[gain.length - 1]])}.`;
}

/** The (θh, θd) slice: range, median, largest value and where, θh where f_r halves along θd 0°. */
export function imageSlice(name, image, phiD, luma, grazingDeg) {
  const { width, height } = image;
  const s = scan(image, luma, true);
  const head = `${name}, image slice at φd ${deg(phiD)}: `;
  const bad = nonfinite(s.bad);
  if (s.k < 0) return `${head}no finite value.${bad}`;
  const row = Math.floor(s.k / width);
  const thetaH = (((s.k % width) + 0.5) / width) * 90;
  const thetaD = ((height - 1 - row + 0.5) / height) * 90;
  const finite = Array.from(s.lum).filter(Number.isFinite).sort((a, b) => a - b);
  if (finite[0] >= FLAT * finite[finite.length - 1]) {
    return `${head}f_r ${fmt(finite[finite.length - 1])} ${UNIT} over the whole slice, no peak.${bad}`;
  }
  const grazing = thetaD > grazingDeg ? " (near grazing)" : "";
  const text = `${head}f_r from ${fmt(finite[0])} to ${fmt(s.peak)} ${UNIT}, ` +
    `median ${fmt(finite[Math.floor(finite.length / 2)])}; largest at θh ${deg(thetaH)}, ` +
    `θd ${deg(thetaD)}${grazing}; `;
  const bottom = (height - 1) * width;
  const start = s.lum[bottom];
  if (!(Number.isFinite(start) && start > 0)) return `${text}at θh 0°, θd 0° it is 0.${bad}`;
  for (let c = 1; c < width; c++) {
    if (s.lum[bottom + c] < start / 2) {
      return `${text}along θd 0° it falls to half its θh 0° value by θh ${deg(((c + 0.5) / width) * 90)}.${bad}`;
    }
  }
  return `${text}along θd 0° it stays above half its θh 0° value.${bad}`;
}

/** The 3D lobe from its grid (angles: (θo, φo) pairs in radians): peak direction and value
 * away from grazing, f_r at the normal. */
export function lobe3d(name, values, angles, thetaI, phiI, what, grazingDeg, spike = 0) {
  const head = `${name}, 3D lobe, light at θi ${deg(thetaI)}, φi ${deg(phiI)}: `;
  const grazing = grazingDeg * RAD;
  let k = -1;
  for (let j = 0; j < values.length; j++) {
    if (angles[2 * j] <= grazing && Number.isFinite(values[j]) && (k < 0 || values[j] > values[k])) k = j;
  }
  const spiked = spike ? `a δ spike in the mirror direction, reflectance ${fmt(spike)}; ` : "";
  if (k < 0 || values[k] <= 0) return `${head}${spiked}${what} is 0 everywhere.`;
  const [theta, phi] = [angles[2 * k], angles[2 * k + 1]];
  const d = [Math.sin(theta) * Math.cos(phi), Math.sin(theta) * Math.sin(phi), Math.cos(theta)];
  let toward = "";
  if (angle(d, light(thetaI, phiI + 180)) <= NEAR_DEG && thetaI >= NEAR_DEG) toward = ", the mirror direction";
  else if (angle(d, light(thetaI, phiI)) <= NEAR_DEG && thetaI >= NEAR_DEG) toward = ", back toward the light";
  else if (theta / RAD <= NEAR_DEG) toward = ", the normal";
  const phiDeg = ((pyRound(phi / RAD) % 360) + 360) % 360;
  const normal = Number.isFinite(values[0]) ? values[0] : 0;
  return `${head}${spiked}peak of ${what} ${fmt(values[k])} ${UNIT} toward θo ${deg(theta / RAD)}, ` +
    `φo ${phiDeg}°${toward}; at the normal ${fmt(Math.max(normal, 0))}.`;
}

/** D against θh, G against θo, F's luminance against θd. */
export function terms(name, t, luma, grazingDeg) {
  if (!t.theta.length) return `${name}: no D, G, F terms.`;
  const { theta, D, G, F } = t;
  const thetaO = t.theta_o;
  let d = `D ${fmt(D[0])} ${UNIT} at θh 0°, above half of that to θh 90°`;
  for (let k = 1; k < D.length; k++) {
    if (D[k] < D[0] / 2) { d = `D ${fmt(D[0])} ${UNIT} at θh 0°, half of that at θh ${deg(theta[k])}`; break; }
  }
  let normal = -1;
  let low = -1;
  thetaO.forEach((o, k) => {
    if (Math.abs(o) > grazingDeg) return;
    if (normal < 0 || Math.abs(o) < Math.abs(thetaO[normal])) normal = k;
    if (Number.isFinite(G[k]) && (low < 0 || G[k] < G[low])) low = k;
  });
  if (low < 0) low = normal;
  const f = F.map((c) => luma[0] * c[0] + luma[1] * c[1] + luma[2] * c[2]);
  return `${name}: ${d}; G ${fmt(G[normal])} at the normal, lowest ${fmt(G[low])} at θo ${deg(thetaO[low])}; ` +
    `F ${fmt(f[0])} at θd 0° to ${fmt(f[f.length - 1])} at θd ${deg(theta[theta.length - 1])}.`;
}

/** The SH fit: its error at the chosen order, from which order it is below SH_GOOD. */
export function sh(name, errors, order) {
  if (!errors.length) return `${name}: no spherical harmonics (a δ model, or not computed yet).`;
  const n = Math.min(Math.max(Math.trunc(order), 0), errors.length - 1);
  const good = errors.findIndex((e) => e < SH_GOOD);
  const limit = `${fmt(100 * SH_GOOD)} %`;
  const reach = good >= 0 ? `below ${limit} from order ${good}` : `above ${limit} up to order ${errors.length - 1}`;
  return `${name}: spherical harmonics to order ${n}, relative error ${fmt(100 * errors[n])} %; ` +
    `order 0: ${fmt(100 * errors[0])} %; ${reach}.`;
}

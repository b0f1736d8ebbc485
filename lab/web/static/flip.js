// Mean LDR-FLIP between two 8-bit sRGB images, as the grader computes it (lab/grading/
// checks.py mean_flip: both images averaged over 2x2 blocks, then flip-evaluator's LDR
// FLIP). Written from the papers: Andersson et al., "FLIP: A Difference Evaluator for
// Alternating Images", HPG 2020, and "Visualizing Errors in Rendered High Dynamic Range
// Images", Eurographics 2021 (observer: a 0.7 m wide 4K screen seen from 0.7 m).
// Why in JavaScript too: practice mode compares the student's picture in the browser.

const PPD = ((0.7 * 3840) / 0.7) * (Math.PI / 180); // pixels per degree of visual angle
const QC = 0.7; // colour error exponent
const QF = 0.5; // feature error exponent
const PC = 0.4; // share of cmax mapped to PT
const PT = 0.95;
const WHITE = [0.950428545, 1.0, 1.088900371]; // D65 in XYZ
// Linear sRGB <-> XYZ (D65).
const RGB2XYZ = [
  [10135552 / 24577794, 8788810 / 24577794, 4435075 / 24577794],
  [2613072 / 12288897, 8788810 / 12288897, 887015 / 12288897],
  [1425312 / 73733382, 8788810 / 73733382, 70074185 / 73733382],
];
const XYZ2RGB = [
  [3.241003275, -1.537398934, -0.498615861],
  [-0.969224334, 1.875930071, 0.041554224],
  [0.055639423, -0.204011202, 1.057148933],
];
// Contrast sensitivity of the achromatic, red-green and blue-yellow channels: sums of
// Gaussians a1 sqrt(pi/b1) exp(-pi^2 r^2 / b1) + a2 ... (r in degrees).
const CSF = [
  [1, 0.0047, 0, 1e-5],
  [1, 0.0053, 0, 1e-5],
  [34.1, 0.04, 13.5, 0.025],
];
const EDGE_WIDTH = 0.082; // degrees: peak to trough of the human edge detector

const mul = (m, v) => m.map((row) => row[0] * v[0] + row[1] * v[1] + row[2] * v[2]);
const srgbToLinear = (c) => (c > 0.04045 ? Math.pow((c + 0.055) / 1.055, 2.4) : c / 12.92);

function xyzToYcxcz(xyz) {
  const [x, y, z] = xyz.map((v, i) => v / WHITE[i]);
  return [116 * y - 16, 500 * (x - y), 200 * (y - z)];
}

function ycxczToLinear([Y, cx, cz]) {
  const y = (Y + 16) / 116;
  const xyz = [(y + cx / 500) * WHITE[0], y * WHITE[1], (y - cz / 200) * WHITE[2]];
  return mul(XYZ2RGB, xyz).map((c) => Math.min(Math.max(c, 0), 1));
}

/** Linear RGB -> CIELAB, then the Hunt adjustment (a and b scaled by L/100). */
function huntLab(rgb) {
  const delta = 6 / 29;
  const f = (t) => (t > delta * delta * delta ? Math.cbrt(t) : t / (3 * delta * delta) + 4 / 29);
  const [fx, fy, fz] = mul(RGB2XYZ, rgb).map((v, i) => f(v / WHITE[i]));
  const L = 116 * fy - 16;
  return [L, 0.01 * L * 500 * (fx - fy), 0.01 * L * 200 * (fy - fz)];
}

const hyab = (p, q) => Math.abs(p[0] - q[0]) + Math.hypot(p[1] - q[1], p[2] - q[2]);

/** The contrast sensitivity filters: per channel a list of separable terms [kx, ky]
 * (each Gaussian of the CSF is the product of two 1D ones), normalised to sum to 1. */
function csfKernels() {
  const r = Math.ceil(3 * Math.sqrt(0.04 / (2 * Math.PI * Math.PI)) * PPD);
  const offsets = Array.from({ length: 2 * r + 1 }, (_, i) => i - r);
  return CSF.map(([a1, b1, a2, b2]) => {
    const terms = [[a1, b1], [a2, b2]].filter(([a]) => a > 0).map(([a, b]) => {
      const g = offsets.map((x) => Math.exp((-Math.PI * Math.PI * x * x) / (b * PPD * PPD)));
      return [a * Math.sqrt(Math.PI / b), g];
    });
    const total = terms.reduce((s, [c, g]) => s + c * g.reduce((t, v) => t + v, 0) ** 2, 0);
    return terms.map(([c, g]) => [g.map((v) => (v * c) / total), g]);
  });
}

/** Edge (first derivative) or point (second derivative) detector along x, as [kx, ky]:
 * its positive and negative weights each sum to +1 and -1 over the square. */
function featureKernel(kind) {
  const sd = 0.5 * EDGE_WIDTH * PPD;
  const r = Math.ceil(3 * sd);
  const offsets = Array.from({ length: 2 * r + 1 }, (_, i) => i - r);
  const g = offsets.map((x) => Math.exp(-(x * x) / (2 * sd * sd)));
  const h = offsets.map((x, i) => (kind === "edge" ? -x : (x * x) / (sd * sd) - 1) * g[i]);
  const gSum = g.reduce((s, v) => s + v, 0);
  const positive = h.reduce((s, v) => s + (v > 0 ? v : 0), 0);
  const negative = -h.reduce((s, v) => s + (v < 0 ? v : 0), 0);
  return [h.map((v) => (v < 0 ? v / negative : v / positive)), g.map((v) => v / gSum)];
}

/** One 1D pass along x (dx = 1) or y, edge pixels repeated. */
function pass(channel, w, h, k, alongX) {
  const out = new Float64Array(w * h);
  const r = (k.length - 1) / 2;
  for (let y = 0; y < h; y++) {
    for (let x = 0; x < w; x++) {
      let sum = 0;
      for (let i = -r; i <= r; i++) {
        const xx = alongX ? Math.min(Math.max(x + i, 0), w - 1) : x;
        const yy = alongX ? y : Math.min(Math.max(y + i, 0), h - 1);
        sum += k[i + r] * channel[yy * w + xx];
      }
      out[y * w + x] = sum;
    }
  }
  return out;
}

/** Convolution by a separable kernel kx(x) ky(y) (turned 90° with `transpose`). */
function convolve(channel, w, h, [kx, ky], transpose = false) {
  return transpose ? pass(pass(channel, w, h, ky, true), w, h, kx, false)
    : pass(pass(channel, w, h, kx, true), w, h, ky, false);
}

/** A sum of separable convolutions. */
function convolveTerms(channel, w, h, terms) {
  const out = new Float64Array(w * h);
  for (const term of terms) convolve(channel, w, h, term).forEach((v, i) => (out[i] += v));
  return out;
}

/** An 8-bit RGBA image (size x size) averaged over 2x2 blocks, in YCxCz, one array per
 * channel. */
function halfYcxcz(image8, size) {
  const w = Math.floor(size / 2);
  const channels = [new Float64Array(w * w), new Float64Array(w * w), new Float64Array(w * w)];
  for (let y = 0; y < w; y++) {
    for (let x = 0; x < w; x++) {
      const srgb = [0, 0, 0];
      for (const [dx, dy] of [[0, 0], [1, 0], [0, 1], [1, 1]]) {
        const i = 4 * ((2 * y + dy) * size + 2 * x + dx);
        for (let c = 0; c < 3; c++) srgb[c] += image8[i + c] / 255 / 4;
      }
      const ycxcz = xyzToYcxcz(mul(RGB2XYZ, srgb.map((c) => srgbToLinear(Math.min(Math.max(c, 0), 1)))));
      ycxcz.forEach((v, c) => (channels[c][y * w + x] = v));
    }
  }
  return { channels, w };
}

/** Mean FLIP of `test8` against `reference8` (RGBA bytes, size x size, rows from the top). */
export function meanFlip(reference8, test8, size) {
  const ref = halfYcxcz(reference8, size);
  const test = halfYcxcz(test8, size);
  const w = ref.w;
  const csf = csfKernels();
  const filtered = (img) => img.channels.map((ch, c) => convolveTerms(ch, w, w, csf[c]));
  const fr = filtered(ref);
  const ft = filtered(test);
  const cmax = Math.pow(hyab(huntLab([0, 1, 0]), huntLab([0, 0, 1])), QC);
  const edge = featureKernel("edge");
  const point = featureKernel("point");
  const features = (img) => {
    const y = img.channels[0].map((v) => (v + 16) / 116);
    const norm = (a, b) => a.map((v, i) => Math.hypot(v, b[i]));
    return [norm(convolve(y, w, w, edge), convolve(y, w, w, edge, true)),
      norm(convolve(y, w, w, point), convolve(y, w, w, point, true))];
  };
  const [edgeR, pointR] = features(ref);
  const [edgeT, pointT] = features(test);
  let total = 0;
  for (let i = 0; i < w * w; i++) {
    const p = huntLab(ycxczToLinear([fr[0][i], fr[1][i], fr[2][i]]));
    const q = huntLab(ycxczToLinear([ft[0][i], ft[1][i], ft[2][i]]));
    const e = Math.pow(hyab(p, q), QC);
    const colour = e < PC * cmax ? (PT / (PC * cmax)) * e : PT + ((e - PC * cmax) / (cmax - PC * cmax)) * (1 - PT);
    const feature = Math.pow(Math.max(Math.abs(edgeR[i] - edgeT[i]), Math.abs(pointR[i] - pointT[i])) / Math.SQRT2, QF);
    total += Math.pow(colour, 1 - feature);
  }
  return total / (w * w);
}

// Spherical harmonics for the page's SH view (views/sh.js), as lab/measured/sh.py computes
// them: Gauss-Legendre quadrature, real harmonics up to order 16 and the projection of a
// lobe as an odd function of z; check_sh.mjs and tests/test_web_sh_mirror.py hold the two
// to the same numbers.
// Why in JavaScript too: the page projects the lobes of models Python never sees (opened or
// edited files).

export const MAX_ORDER = 16;
export const GRID = [48, 96]; // Gauss-Legendre nodes in cos θ × uniform φ (sh_view.GRID)
export const count = (order) => (order + 1) ** 2;

/** Gauss-Legendre nodes and weights on [-1, 1] (n nodes, ascending), by Newton's method. */
export function gaussLegendre(n) {
  const x = new Float64Array(n);
  const w = new Float64Array(n);
  // P_n(z) and its derivative, by the three-term recurrence.
  const legendre = (z) => {
    let p0 = 1;
    let p1 = z;
    for (let l = 2; l <= n; l++) {
      const p2 = ((2 * l - 1) * z * p1 - (l - 1) * p0) / l;
      p0 = p1;
      p1 = p2;
    }
    return [p1, (n * (z * p1 - p0)) / (z * z - 1)];
  };
  for (let k = 0; k < Math.ceil(n / 2); k++) {
    let z = Math.cos((Math.PI * (k + 0.75)) / (n + 0.5));
    for (let it = 0; it < 100; it++) {
      const [p, slope] = legendre(z);
      const step = p / slope;
      z -= step;
      if (Math.abs(step) < 1e-16) break;
    }
    const dp = legendre(z)[1]; // at the root itself, for the weight
    x[n - 1 - k] = z;
    x[k] = -z;
    w[k] = w[n - 1 - k] = 2 / ((1 - z * z) * dp * dp);
  }
  return { x, w };
}

const lgamma = (n) => { // log((n - 1)!) for whole n >= 1
  let s = 0;
  for (let k = 2; k < n; k++) s += Math.log(k);
  return s;
};

// sqrt((2l + 1) / 4π · (l - m)! / (l + m)!) at l * (MAX_ORDER + 1) + m: the same for every
// direction, computed once (as sh.real_sh computes it).
const NORM = new Float64Array((MAX_ORDER + 1) ** 2);
for (let l = 0; l <= MAX_ORDER; l++) {
  for (let m = 0; m <= l; m++) {
    NORM[l * (MAX_ORDER + 1) + m] = Math.sqrt(((2 * l + 1) / (4 * Math.PI)) * Math.exp(lgamma(l - m + 1) - lgamma(l + m + 1)));
  }
}

/** Real orthonormal harmonics up to `order` (at most MAX_ORDER) at (θ, φ), index l² + l + m
 * (sh.real_sh). */
export function realSh(order, theta, phi) {
  const out = new Float64Array(count(order));
  const x = Math.cos(theta);
  const sine = Math.sqrt(Math.max(1 - x * x, 0));
  const stride = order + 1;
  const P = new Float64Array(stride * stride); // P[l * stride + m]
  let diagonal = 1;
  for (let m = 0; m <= order; m++) {
    if (m) diagonal = -(2 * m - 1) * sine * diagonal;
    P[m * stride + m] = diagonal;
    if (m < order) P[(m + 1) * stride + m] = (2 * m + 1) * x * diagonal;
    for (let l = m + 2; l <= order; l++) {
      P[l * stride + m] = ((2 * l - 1) * x * P[(l - 1) * stride + m] - (l + m - 1) * P[(l - 2) * stride + m]) / (l - m);
    }
  }
  for (let m = 0; m <= order; m++) {
    const c = Math.SQRT2 * Math.cos(m * phi);
    const s = Math.SQRT2 * Math.sin(m * phi);
    for (let l = m; l <= order; l++) {
      const p = NORM[l * (MAX_ORDER + 1) + m] * P[l * stride + m];
      if (m === 0) out[l * l + l] = p;
      else {
        out[l * l + l + m] = c * p;
        out[l * l + l - m] = s * p;
      }
    }
  }
  return out;
}

/** The harmonics odd in z (l + |m| odd): the only ones the odd extension of a lobe has. */
export const ODD = [];
for (let index = 0; index < count(MAX_ORDER); index++) {
  const l = Math.floor(Math.sqrt(index));
  if ((l + Math.abs(index - l * l - l)) % 2 === 1) ODD.push(index);
}

let projector = null; // the grid and its harmonics: the same for every model and light

/** The quadrature grid on the upper hemisphere (rows of θ, then φ; as sh.hemisphere_grid):
 * directions V (RGBA floats), solid angles, and the harmonics split as they separate,
 * Y_lm(θ, φ) = N_lm P_lm(cos θ) trig(mφ): per row of θ, 2·w·N·P of each odd harmonic (√2
 * folded in for m ≠ 0), per column of φ, cos(mφ) and sin(mφ). */
export function quadrature() {
  if (projector) return projector;
  const [nTheta, nPhi] = GRID;
  const { x, w } = gaussLegendre(2 * nTheta);
  const n = nTheta * nPhi;
  const V = new Float32Array(4 * n);
  const weight = new Float64Array(n);
  const K = ODD.length;
  const rows = new Float64Array(nTheta * K);
  const M = MAX_ORDER + 1;
  const cos = new Float64Array(nPhi * M);
  const sin = new Float64Array(nPhi * M);
  for (let j = 0; j < nPhi; j++) {
    const phi = ((j + 0.5) * 2 * Math.PI) / nPhi;
    for (let m = 0; m < M; m++) {
      cos[j * M + m] = Math.cos(m * phi);
      sin[j * M + m] = Math.sin(m * phi);
    }
  }
  for (let i = 0; i < nTheta; i++) {
    const c = x[nTheta + i]; // the nodes with cos θ > 0
    const theta = Math.acos(c);
    const solid = (w[nTheta + i] * 2 * Math.PI) / nPhi;
    // The harmonics at φ = 0 give N·P (m >= 0, times √2 for m > 0).
    const Y = realSh(MAX_ORDER, theta, 0);
    ODD.forEach((index, o) => {
      const l = Math.floor(Math.sqrt(index));
      const m = index - l * l - l;
      rows[i * K + o] = 2 * solid * Y[l * l + l + Math.abs(m)];
    });
    const sine = Math.sin(theta);
    for (let j = 0; j < nPhi; j++) {
      const k = i * nPhi + j;
      V[4 * k] = sine * cos[j * M + 1];
      V[4 * k + 1] = sine * sin[j * M + 1];
      V[4 * k + 2] = c;
      weight[k] = solid;
    }
  }
  projector = { V, weight, rows, cos, sin, n, nTheta, nPhi };
  return projector;
}

/** Coefficients of the odd extension of `lobe` (values at the quadrature's nodes), and the
 * relative L2 error over the hemisphere of the series of every order.
 *
 * The errors come from Parseval's identity: the grid integrates products of harmonics up
 * to order 16 exactly, so over the hemisphere the odd harmonics are orthogonal with norm
 * 1/2 and the series' error is ||g||² - Σ a² / 2 over its coefficients (no sum over the
 * nodes per order; the same as summing (series - g)² there, to rounding). */
export function analyse(lobe) {
  const { weight, rows, cos, sin, n, nTheta, nPhi } = quadrature();
  const K = ODD.length;
  const M = MAX_ORDER + 1;
  const odd = new Float64Array(K);
  const C = new Float64Array(M);
  const S = new Float64Array(M);
  for (let i = 0; i < nTheta; i++) {
    // The row's Fourier sums, then each harmonic's share of them.
    C.fill(0);
    S.fill(0);
    for (let j = 0; j < nPhi; j++) {
      const g = lobe[i * nPhi + j];
      if (g === 0) continue;
      for (let m = 0; m < M; m++) {
        C[m] += g * cos[j * M + m];
        S[m] += g * sin[j * M + m];
      }
    }
    for (let o = 0; o < K; o++) {
      const index = ODD[o];
      const l = Math.floor(Math.sqrt(index));
      const m = index - l * l - l;
      odd[o] += rows[i * K + o] * (m >= 0 ? C[m] : S[-m]);
    }
  }
  const coefficients = new Float64Array(count(MAX_ORDER));
  ODD.forEach((index, o) => (coefficients[index] = odd[o]));
  let norm2 = 0;
  for (let k = 0; k < n; k++) norm2 += weight[k] * lobe[k] * lobe[k];
  const norm = Math.max(Math.sqrt(norm2), 1e-300);
  const errors = [];
  let captured = 0;
  for (let order = 0; order <= MAX_ORDER; order++) {
    for (let c = order * order; c < count(order); c++) captured += (coefficients[c] * coefficients[c]) / 2;
    errors.push(Math.sqrt(Math.max(norm2 - captured, 0)) / norm);
  }
  return { coefficients, errors };
}

// Spherical harmonics for the page's SH view (views/sh.js), as lab/measured/sh.py computes
// them: Gauss-Legendre quadrature, real harmonics up to the view's highest order and the
// projection of a lobe as an odd function of z; check_sh.mjs and
// tests/test_web_sh_mirror.py hold the two to the same numbers. The highest order and the
// grid are lab/views/sh.py's (MAX_ORDER, GRID), sent as the view's page data: useGrid().
// Why in JavaScript too: the page projects the lobes of models Python never sees (opened or
// edited files).

export const count = (order) => (order + 1) ** 2;

let SHAPE = null; // { maxOrder, grid, norm, odd, projector }: useGrid

const shape = () => {
  if (!SHAPE) throw new Error("sh.js: no grid yet (useGrid with the sh view's page data)");
  return SHAPE;
};

/** The highest order and the quadrature grid (nodes in cos θ × φ) of lab/views/sh.py. */
export const maxOrder = () => shape().maxOrder;
export const grid = () => shape().grid;

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

/** Takes the sh view's page data ({max_order, grid}); the tables follow once per grid. */
export function useGrid({ max_order: top, grid: [nTheta, nPhi] }) {
  if (SHAPE && SHAPE.maxOrder === top && SHAPE.grid[0] === nTheta && SHAPE.grid[1] === nPhi) return;
  // sqrt((2l + 1) / 4π · (l - m)! / (l + m)!) at l * (top + 1) + m: the same for every
  // direction, computed once (as sh.real_sh computes it).
  const norm = new Float64Array((top + 1) ** 2);
  for (let l = 0; l <= top; l++) {
    for (let m = 0; m <= l; m++) {
      norm[l * (top + 1) + m] = Math.sqrt(((2 * l + 1) / (4 * Math.PI)) * Math.exp(lgamma(l - m + 1) - lgamma(l + m + 1)));
    }
  }
  // The harmonics odd in z (l + |m| odd): the only ones the odd extension of a lobe has.
  const odd = [];
  for (let index = 0; index < count(top); index++) {
    const l = Math.floor(Math.sqrt(index));
    if ((l + Math.abs(index - l * l - l)) % 2 === 1) odd.push(index);
  }
  SHAPE = { maxOrder: top, grid: [nTheta, nPhi], norm, odd, projector: null };
}

/** Real orthonormal harmonics up to `order` (at most maxOrder()) at (θ, φ), index l² + l + m
 * (sh.real_sh). */
export function realSh(order, theta, phi) {
  const { maxOrder: top, norm } = shape();
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
      const p = norm[l * (top + 1) + m] * P[l * stride + m];
      if (m === 0) out[l * l + l] = p;
      else {
        out[l * l + l + m] = c * p;
        out[l * l + l - m] = s * p;
      }
    }
  }
  return out;
}

/** The quadrature grid on the upper hemisphere (rows of θ, then φ; as sh.hemisphere_grid):
 * directions V (RGBA floats), solid angles, and the harmonics split as they separate,
 * Y_lm(θ, φ) = N_lm P_lm(cos θ) trig(mφ): per row of θ, 2·w·N·P of each odd harmonic (√2
 * folded in for m ≠ 0), per column of φ, cos(mφ) and sin(mφ). */
export function quadrature() {
  const { maxOrder: top, grid: [nTheta, nPhi], odd: ODD } = shape();
  if (SHAPE.projector) return SHAPE.projector; // the same for every model and light
  const { x, w } = gaussLegendre(2 * nTheta);
  const n = nTheta * nPhi;
  const V = new Float32Array(4 * n);
  const weight = new Float64Array(n);
  const K = ODD.length;
  const rows = new Float64Array(nTheta * K);
  const M = top + 1;
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
    const Y = realSh(top, theta, 0);
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
  SHAPE.projector = { V, weight, rows, cos, sin, n, nTheta, nPhi };
  return SHAPE.projector;
}

/** Coefficients of the odd extension of `lobe` (values at the quadrature's nodes), and the
 * relative L2 error over the hemisphere of the series of every order.
 *
 * The errors come from Parseval's identity: the grid integrates products of harmonics up
 * to the highest order exactly, so over the hemisphere the odd harmonics are orthogonal with norm
 * 1/2 and the series' error is ||g||² - Σ a² / 2 over its coefficients (no sum over the
 * nodes per order; the same as summing (series - g)² there, to rounding). */
export function analyse(lobe) {
  const { weight, rows, cos, sin, n, nTheta, nPhi } = quadrature();
  const { maxOrder: top, odd: ODD } = shape();
  const K = ODD.length;
  const M = top + 1;
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
  const coefficients = new Float64Array(count(top));
  ODD.forEach((index, o) => (coefficients[index] = odd[o]));
  let norm2 = 0;
  for (let k = 0; k < n; k++) norm2 += weight[k] * lobe[k] * lobe[k];
  const norm = Math.max(Math.sqrt(norm2), 1e-300);
  const errors = [];
  let captured = 0;
  for (let order = 0; order <= top; order++) {
    for (let c = order * order; c < count(order); c++) captured += (coefficients[c] * coefficients[c]) / 2;
    errors.push(Math.sqrt(Math.max(norm2 - captured, 0)) / norm);
  }
  return { coefficients, errors };
}

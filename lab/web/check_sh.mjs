// Runs the page's spherical harmonics (static/sh.js) on a table of cases and prints the
// results as JSON, for tests/test_web_sh_mirror.py to compare with lab/measured/sh.py.
// Usage: node lab/web/check_sh.mjs CASES.json
import { readFileSync } from "node:fs";

import { analyse, gaussLegendre, grid, maxOrder, quadrature, realSh, useGrid } from "./static/sh.js";

const cases = JSON.parse(readFileSync(process.argv[2], "utf8"));
useGrid(cases.shape); // lab/views/sh.py's page data, as the page receives it
const { x, w } = gaussLegendre(2 * grid()[0]);
const { V, weight } = quadrature();
const out = {
  legendre: { x: Array.from(x), w: Array.from(w) },
  grid: { V: Array.from(V), weight: Array.from(weight) },
  real_sh: cases.directions.map(([theta, phi]) => Array.from(realSh(maxOrder(), theta, phi))),
  analyse: cases.lobes.map((lobe) => {
    const { coefficients, errors } = analyse(Float64Array.from(lobe));
    return { coefficients: Array.from(coefficients), errors };
  }),
};
process.stdout.write(JSON.stringify(out));

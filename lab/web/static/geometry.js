// Directions and the plane of incidence, as lab/geometry.py makes them (angles in degrees,
// theta from the normal z, phi from x). Pure functions: tests/test_web_mirrors.py checks
// them against the Python on a table of cases.
// Why in JavaScript too: every view of the page makes its directions in the browser, at every
// frame.

/** Unit vector for angles in degrees, as lab.geometry.direction. */
export function direction(thetaDeg, phiDeg) {
  const t = (thetaDeg * Math.PI) / 180;
  const p = (phiDeg * Math.PI) / 180;
  // cos(90 deg) is 6e-17: snapped to 0 so theta = 90 lies on the horizon, as in Python.
  const snap = (x) => (Math.abs(x) < 1e-12 ? 0 : x);
  return [Math.sin(t) * Math.cos(p), Math.sin(t) * Math.sin(p), Math.cos(t)].map(snap);
}

/** theta_o from -90 to 90 degrees in `step`s and the viewing directions V in the plane of
 * incidence of a light at azimuth `phiDeg`, as lab.geometry.plane_of_incidence: positive
 * theta_o lies on the far side from the light (theta_o = theta_i is the mirror direction). */
export function planeOfIncidence(phiDeg, step = 1) {
  // As numpy's arange(-90, 90 + step / 2, step): its length, then start + k * step.
  const count = Math.ceil((180 + step / 2) / step);
  const thetaO = Array.from({ length: count }, (_, k) => -90 + k * step);
  const V = thetaO.map((t) => direction(Math.abs(t), t >= 0 ? phiDeg + 180 : phiDeg));
  return { thetaO, V };
}

// Owns: a lobe plot in words, as a table and at a cursor, for readers who cannot see it.
// The mirror of lab/describe.py (the page works alone from a file); tests/test_a11y_describe.py
// holds both to one fixture. A lobe: { name, thetaO: [deg], values: [luminance], spike }.
// Positive θo is the far side from the light: θo = θi is the mirror direction.

export const UNIT = "sr⁻¹";
const NEAR_DEG = 2;
const FLAT = 0.97;
const SAME = 1.01;
export const TABLE_STEP = 5;

/** Three significant digits, no exponent, no trailing zeros (describe.py: fmt). */
export function fmt(x) {
  if (!Number.isFinite(x)) return x > 0 ? "∞" : "not a number";
  if (x === 0) return "0";
  const digits = Math.max(0, 2 - Math.floor(Math.log10(Math.abs(x))));
  let text = x.toFixed(digits);
  if (text.includes(".")) text = text.replace(/0+$/, "").replace(/\.$/, "");
  return text === "-0" || text === "0" ? "0" : text.replace("-", "−");
}

/** Rounds halves to even, as Python's round() does. */
export function pyRound(x) {
  const value = Math.round(x);
  return Math.abs(x % 1) === 0.5 && value % 2 !== 0 ? value - 1 : value;
}

/** An angle in whole degrees with a real minus sign. */
export function deg(x) {
  const value = pyRound(x);
  return value ? `${value}°`.replace("-", "−") : "0°";
}

const clean = (v) => (Number.isNaN(v) || v === Infinity ? 0 : Math.max(v, 0));

/** Peak (away from grazing), half width at half maximum and the lowest value. */
export function summarise(lobe, grazingDeg) {
  const t = lobe.thetaO;
  const v = Array.from(lobe.values, clean);
  let k = -1;
  let floor = Infinity;
  for (let j = 0; j < t.length; j++) {
    if (Math.abs(t[j]) > grazingDeg) continue;
    if (k < 0 || v[j] > v[k]) k = j;
    floor = Math.min(floor, v[j]);
  }
  const peak = v[k];
  if (peak <= 0 || floor >= FLAT * peak) return { peakTheta: t[k], peak, floor, halfWidth: null, wide: false };
  const half = peak / 2;
  let wide = false;
  const crossing = (stepDir) => {
    let previous = k;
    for (let j = k + stepDir; j >= 0 && j < t.length; j += stepDir) {
      if (v[j] < half) {
        const a = (v[previous] - half) / (v[previous] - v[j]);
        return t[previous] + a * (t[j] - t[previous]);
      }
      previous = j;
    }
    wide = true;
    return t[previous];
  };
  const left = crossing(-1);
  const right = crossing(1);
  return { peakTheta: t[k], peak, floor, halfWidth: (right - left) / 2, wide };
}

function where(theta, thetaI) {
  if (Math.abs(theta - thetaI) <= NEAR_DEG && thetaI >= NEAR_DEG) return ", the mirror direction";
  if (Math.abs(theta + thetaI) <= NEAR_DEG && thetaI >= NEAR_DEG) return ", back toward the light";
  if (Math.abs(theta) <= NEAR_DEG) return ", the normal";
  return "";
}

/** One lobe in words: peak, where it is, half width, floor (and a δ spike). */
export function sentence(lobe, thetaI, what, grazingDeg) {
  const s = summarise(lobe, grazingDeg);
  const parts = [];
  if (lobe.spike !== null && lobe.spike !== undefined) {
    parts.push(`a δ spike at θo ${deg(thetaI)}, the mirror direction, reflectance ${fmt(lobe.spike)}`);
  }
  if (s.peak <= 0) parts.push(`${what} is 0 in this plane`);
  else if (s.halfWidth === null) parts.push(`${what} ${fmt(s.peak)} ${UNIT} in every direction, no lobe`);
  else {
    parts.push(`peak of ${what} at θo ${deg(s.peakTheta)}${where(s.peakTheta, thetaI)}, ` +
      `${fmt(s.peak)} ${UNIT}; half width ${s.wide ? "at least " : ""}${deg(s.halfWidth)}; floor ${fmt(s.floor)}`);
  }
  return `${lobe.name}, θi ${deg(thetaI)}: ${parts.join("; ")}.`;
}

/** The plot in words; with several lobes a comparison follows the sentences. */
export function describe(lobes, thetaI, what, grazingDeg) {
  const text = lobes.map((l) => sentence(l, thetaI, what, grazingDeg)).join(" ");
  if (lobes.length < 2) return text;
  const s = lobes.map((l) => summarise(l, grazingDeg));
  const order = lobes.map((_, i) => i).sort((a, b) => s[b].peak - s[a].peak || a - b);
  const top = order[0];
  const words = [`Highest peak: ${lobes[top].name}, ${fmt(s[top].peak)} ${UNIT}`];
  for (const i of order.slice(1)) {
    if (s[i].peak <= 0) continue;
    const ratio = s[top].peak / s[i].peak;
    words.push(`${lobes[i].name} ${ratio >= SAME ? `${fmt(ratio)} times lower` : "the same height"}`);
  }
  const lobed = lobes.map((_, i) => i).filter((i) => s[i].halfWidth !== null);
  if (lobed.length >= 2) {
    const narrow = lobed.reduce((a, b) => (s[b].halfWidth < s[a].halfWidth ? b : a));
    words.push(`narrowest: ${lobes[narrow].name}`);
  }
  return `${text} ${words.join("; ")}.`;
}

const nearest = (lobe, theta) => {
  let k = 0;
  lobe.thetaO.forEach((t, j) => { if (Math.abs(t - theta) < Math.abs(lobe.thetaO[k] - theta)) k = j; });
  return k;
};
const roundStep = (x, step) => pyRound(x / step) * step;

/** Rows [θo, one value per lobe, mark] every `step` degrees; the header row first. */
export function table(lobes, thetaI, grazingDeg, step = TABLE_STEP) {
  const rows = [["θo (deg)", ...lobes.map((l) => l.name), "mark"]];
  const summaries = lobes.map((l) => summarise(l, grazingDeg));
  // Only a lobe has a peak to mark (a constant's largest value is noise at its edge).
  const peaks = summaries.map((s) => (s.halfWidth !== null ? roundStep(s.peakTheta, step) : null));
  const mirror = roundStep(thetaI, step);
  for (let theta = -90; theta <= 90; theta += step) {
    const cells = [String(theta)];
    for (const lobe of lobes) {
      const v = lobe.values[nearest(lobe, theta)];
      cells.push(fmt(Number.isNaN(v) ? 0 : Math.max(v, 0)));
    }
    const marks = lobes.filter((l, i) => peaks[i] === theta).map((l) => `peak ${l.name}`);
    if (theta === mirror) marks.push("mirror");
    cells.push(marks.join(", "));
    rows.push(cells);
  }
  return rows;
}

/** The table as CSV (ASCII minus signs, cells with commas quoted). */
export function csvText(rows) {
  const cell = (text) => {
    const t = text.replace(/−/g, "-");
    return t.includes(",") || t.includes('"') ? `"${t}"` : t;
  };
  return rows.map((r) => r.map(cell).join(",")).join("\n") + "\n";
}

/** What the keyboard cursor says at θo: "θo −40°, f_r 0.52, 88 % of the peak". */
export function cursor(lobe, theta, what, grazingDeg) {
  const k = nearest(lobe, theta);
  const value = clean(lobe.values[k]);
  const peak = summarise(lobe, grazingDeg).peak;
  const share = peak > 0 ? `, ${pyRound((100 * value) / peak)} % of the peak` : "";
  return `θo ${deg(lobe.thetaO[k])}, ${what} ${fmt(value)}${share}`;
}

// Runs the web lab's pure mirrors of Python code on a table of cases and prints the results
// as JSON, for tests/test_web_mirrors.py to compare with the Python.
// Usage: node lab/web/check_mirrors.mjs CASES.json
import { readFileSync } from "node:fs";

import { direction, planeOfIncidence } from "./static/geometry.js";
import { fill, formatDigits, parseModel } from "./static/header.js";
import { peakValue, polarRadius } from "./static/plotscale.js";
import { parseRgb, parseValue, sliderToValue, valueToSlider } from "./static/values.js";

const cases = JSON.parse(readFileSync(process.argv[2], "utf8"));
const attempt = (f) => {
  try {
    return { value: f() };
  } catch (err) {
    return { error: err.message };
  }
};

const out = {
  direction: cases.direction.map(([theta, phi]) => direction(theta, phi)),
  plane: cases.plane.map(([phi, step]) => planeOfIncidence(phi, step)),
  values: cases.values.map(([p, text]) => attempt(() => parseValue(p, text))),
  rgb: cases.rgb.map((text) => parseRgb(text)),
  slider_value: cases.slider_value.map(([p, position]) => sliderToValue(p, position, cases.slider_steps)),
  slider_position: cases.slider_position.map(([p, value]) => valueToSlider(p, value, cases.slider_steps)),
  peak: cases.peak.map(([thetaO, values, grazing]) => peakValue(thetaO, values, grazing)),
  radius: cases.radius.map(([f, top, log, decades]) => polarRadius(f, top, log, decades)),
  g: cases.g.map(([x, digits]) => formatDigits(x, digits)),
  // {"float": "nan"} for what JSON cannot write (nan, inf, -inf).
  fill: cases.fill.map(([template, values]) => fill(template, Object.fromEntries(Object.entries(values).map(([k, v]) =>
    [k, v?.float === undefined ? v : Number(v.float.replace("inf", "Infinity"))])))),
  // The library's headers as the page would parse them (the manifest carries the Python's).
  headers: Object.fromEntries(Object.entries(cases.library).map(([name, { path, code }]) => {
    const parsed = attempt(() => parseModel(code, path, name));
    if (parsed.error !== undefined) return [name, { error: parsed.error }];
    const { code: _, path: __, ...header } = parsed.value;
    return [name, header];
  })),
};
process.stdout.write(JSON.stringify(out));

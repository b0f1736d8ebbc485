// Parameter values as text and on sliders, as the Python does it: Param.parse
// (lab/models.py), parse_rgb (lab/errors.py) and the app's sliders (lab/app/params.py).
// Pure functions: tests/test_web_mirrors.py checks them against the Python on a table of
// cases. The messages are the page's own (shorter than the command line's).
// Why in JavaScript too: every slider and text box of the page parses as the desktop's does,
// without a server.
import { PY_FLOAT, formatG } from "./header.js";

// A slider has `steps` positions: lab/constants.py SLIDER_STEPS, the manifest's constants.

/** Python's float() of one token: surrounding blanks allowed, NaN where Python raises. */
export function pyNumber(token) {
  const text = token.trim();
  if (!PY_FLOAT.test(text)) return NaN;
  return Number(text.replace(/_/g, "").replace(/^([+-]?)inf(inity)?$/i, "$1Infinity"));
}

/** Text (address or text box) -> checked value of parameter `p`; throws Error with a
 * one-line message where Param.parse raises. */
export function parseValue(p, text) {
  text = text.trim();
  if (p.kind === "enum") {
    if (!p.choices.includes(text)) throw new Error(`${p.name} must be one of ${p.choices.join(", ")}`);
    return text;
  }
  if (p.kind === "bool") {
    if (["1", "true", "yes", "on"].includes(text.toLowerCase())) return true;
    if (["0", "false", "no", "off"].includes(text.toLowerCase())) return false;
    throw new Error(`${p.name} is a bool: use 1 or 0`);
  }
  let numbers = text.split(",").map(pyNumber);
  if (numbers.some((x) => !Number.isFinite(x))) throw new Error(`${p.name} needs numbers, not '${text}'`);
  const inRange = (x) => x >= p.minimum && x <= p.maximum;
  if (p.kind === "color") {
    if (numbers.length === 1) numbers = [numbers[0], numbers[0], numbers[0]];
    if (numbers.length !== 3 || !numbers.every(inRange)) throw new Error(`${p.name} is a color: r,g,b each in 0..1`);
    return numbers;
  }
  if (numbers.length !== 1 || !inRange(numbers[0])) {
    throw new Error(`${p.name} must be a number in [${formatG(p.minimum)}, ${formatG(p.maximum)}]`);
  }
  return numbers[0];
}

/** "r,g,b" (or one grey value), each finite and 0 or more -> [r, g, b]; null otherwise
 * (lab.errors.parse_rgb, which raises instead). */
export function parseRgb(text) {
  let rgb = text.split(",").map(pyNumber);
  if (rgb.length === 1) rgb = [rgb[0], rgb[0], rgb[0]];
  return rgb.length === 3 && rgb.every((c) => Number.isFinite(c) && c >= 0) ? rgb : null;
}

/** A slider's position (0..steps) -> the value, linear or log as the header says. */
export function sliderToValue(p, position, steps) {
  const t = position / steps;
  if (p.scale === "log") return Math.exp(Math.log(p.minimum) + t * (Math.log(p.maximum) - Math.log(p.minimum)));
  return p.minimum + t * (p.maximum - p.minimum);
}

/** Where `value` sits on a slider of `steps` positions (clamped to its ends). */
export function valueToSlider(p, value, steps) {
  const t = p.scale === "log"
    ? (Math.log(value) - Math.log(p.minimum)) / (Math.log(p.maximum) - Math.log(p.minimum))
    : (value - p.minimum) / (p.maximum - p.minimum);
  return Math.round(Math.min(Math.max(t, 0), 1) * steps);
}

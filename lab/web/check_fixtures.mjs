// Checks the web lab's header parser and assembly (static/header.js, static/assemble.js)
// against the shared fixtures in tests/fixtures/headers/, which the Python side is
// checked against too. Usage: node lab/web/check_fixtures.mjs [LIBRARY.json]
// LIBRARY.json (written by the Python test) maps "model/view" to the Python assembly of
// each library model, for a second, fixture-free comparison. Prints a JSON report.
import { readFileSync, readdirSync, statSync } from "node:fs";
import { dirname, join, relative } from "node:path";
import { fileURLToPath } from "node:url";

import { assembleFragment, translateLog } from "./static/assemble.js";
import { ModelError, parseModel } from "./static/header.js";

const ROOT = join(dirname(fileURLToPath(import.meta.url)), "..", "..");
const FIXTURES = join(ROOT, "tests", "fixtures", "headers");
const SHADERS = join(ROOT, "shaders");

function shaderFiles(dir = SHADERS, files = {}) {
  for (const name of readdirSync(dir)) {
    const path = join(dir, name);
    if (statSync(path).isDirectory()) shaderFiles(path, files);
    else if (name.endsWith(".glsl")) files[relative(SHADERS, path).split("\\").join("/")] = readFileSync(path, "utf8");
  }
  return files;
}

function runs(origins, sharedCounts = true) {
  const out = [];
  for (const [file, line] of origins) {
    const last = out[out.length - 1];
    if (last && last[0] === file && last[1] + last[2] === line) last[2] += 1;
    else out.push([file, line, 1]);
  }
  if (!sharedCounts) for (const run of out) if (run[0].startsWith("shaders/")) run[2] = 0;
  return out;
}

// The assembled text with each file from shaders/ reduced to a marker (as regenerate.py).
function skeleton(source) {
  const out = [];
  source.lines.forEach((line, i) => {
    const file = source.origins[i][0];
    if (file.startsWith("shaders/")) {
      const marker = `//@@ ${file} @@`;
      if (out[out.length - 1] !== marker) out.push(marker);
    } else out.push(line);
  });
  return out.join("\n") + "\n";
}

// {FILE:LINE} -> the assembled line that came from FILE:LINE.
function fillLog(log, source) {
  return log.replace(/\{([^{}]+):(\d+)\}/g, (_, file, line) =>
    String(source.origins.findIndex(([f, l]) => f === file && l === Number(line)) + 1));
}

function modelObject(model) {
  const { name, title, formula, source, includes, delta, ambient, properties } = model;
  const params = model.params.map((p) => ({
    name: p.name, kind: p.kind, default: p.default, doc: p.doc, minimum: p.minimum,
    maximum: p.maximum, scale: p.scale, choices: p.choices, line: p.line,
  }));
  return { name, title, formula, source, includes, delta, ambient, properties, params };
}

// Key order must not matter when comparing with Python's JSON.
function canonical(value) {
  if (Array.isArray(value)) return value.map(canonical);
  if (value && typeof value === "object") {
    return Object.fromEntries(Object.keys(value).sort().map((k) => [k, canonical(value[k])]));
  }
  return value;
}
const same = (a, b) => JSON.stringify(canonical(a)) === JSON.stringify(canonical(b));

const expected = JSON.parse(readFileSync(join(FIXTURES, "expected.json"), "utf8"));
const files = shaderFiles();
const mismatches = [];
let checked = 0;
for (const [fileName, want] of Object.entries(expected.files)) {
  const label = `${expected.label_dir}/${fileName}`;
  const code = readFileSync(join(FIXTURES, fileName), "utf8");
  let model;
  try {
    model = parseModel(code, label, want.expected_name ?? null);
  } catch (err) {
    if (!(err instanceof ModelError)) throw err;
    const got = { file: err.file.split("/").pop(), line: err.line, message: err.detail };
    if (!same(got, want.error)) mismatches.push({ file: fileName, what: "parse error", got, want: want.error ?? want.model });
    checked++;
    continue;
  }
  checked++;
  if (!want.model) {
    mismatches.push({ file: fileName, what: "parse", got: "no error", want: want.error });
    continue;
  }
  const got = modelObject(model);
  if (!same(got, want.model)) mismatches.push({ file: fileName, what: "model", got, want: want.model });
  for (const [view, wantView] of Object.entries(want.assembly)) {
    let source;
    try {
      source = assembleFragment(model, view, files, { target: "300es", constants: expected.constants });
    } catch (err) {
      if (!(err instanceof ModelError)) throw err;
      const gotErr = { file: err.file, line: err.line, message: err.detail };
      if (!same(gotErr, wantView.error)) mismatches.push({ file: fileName, what: `${view} error`, got: gotErr, want: wantView.error ?? "assembled" });
      continue;
    }
    if (wantView.error) {
      mismatches.push({ file: fileName, what: `${view}`, got: "assembled", want: wantView.error });
      continue;
    }
    const text = readFileSync(join(FIXTURES, wantView.text), "utf8");
    if (skeleton(source) !== text) mismatches.push({ file: fileName, what: `${view} text`, got: skeleton(source), want: text });
    if (!same(runs(source.origins, false), wantView.origins)) mismatches.push({ file: fileName, what: `${view} origins`, got: runs(source.origins), want: wantView.origins });
    if (want.logs && view === "sphere") {
      for (const [kind, log] of Object.entries(expected.logs)) {
        const gotLog = translateLog(fillLog(log, source), source).map((e) => [e.file, e.line, e.message]);
        if (!same(gotLog, want.logs[kind])) mismatches.push({ file: fileName, what: `${kind} log`, got: gotLog, want: want.logs[kind] });
      }
    }
  }
}

let library = 0;
if (process.argv[2]) {
  const programs = JSON.parse(readFileSync(process.argv[2], "utf8"));
  for (const [key, want] of Object.entries(programs)) {
    const [name, view, enumText] = key.split("/");
    const enums = enumText ? Object.fromEntries(enumText.split(",").map((kv) => kv.split("="))) : {};
    const path = `shaders/brdfs/${name}.glsl`;
    const model = parseModel(files[`brdfs/${name}.glsl`], path, name);
    const source = assembleFragment(model, view, files, { target: "300es", enums, constants: expected.constants });
    if (source.text !== want.text || !same(runs(source.origins), want.origins)) {
      mismatches.push({ file: key, what: "library assembly", got: source.text, want: want.text });
    }
    library++;
  }
}
console.log(JSON.stringify({ checked, library, mismatches }, null, 1));
process.exit(mismatches.length ? 1 : 0);

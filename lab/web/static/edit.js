// The shader editor of the web lab: CodeMirror 6 (editor.js, bundled from npm) on a panel's
// model file. Every edit is checked as the student types (header, then a compile of the
// sphere program); errors are marked at the file's own lines and the panel keeps showing
// the last version that compiled. Open a file, save (download) it, or go back to the
// library's version.
import { createEditor } from "./editor.js";
import { ModelError, parseModel } from "./header.js";
import { el } from "./dom.js";

const DEBOUNCE_MS = 250;

export class ShaderEditor {
  /** The editor in `root`; `actions` (editing.js): tryCompile(panel, model) throws where a
   * text does not compile, install(panel, model) shows it, keepText(panel, text) keeps the
   * student's text in this browser. */
  constructor(root, actions) {
    this.root = root;
    this.actions = actions;
    this.panel = null;
    this.timer = 0;
    this.checks = 0; // finished checks (tests wait for them)
    this.title = el("strong", { class: "editor-title" });
    this.status = el("div", { class: "editor-status", role: "status" });
    const open = el("input", { type: "file", accept: ".glsl", hidden: "" });
    this.fileInput = open;
    open.addEventListener("change", async () => {
      const file = open.files[0];
      if (file) this.editor.setText(await file.text());
      open.value = "";
    });
    const button = (text, title, onclick) => el("button", { type: "button", title, onclick }, text);
    this.host = el("div", { class: "editor-host" });
    root.append(
      el("header", {}, this.title, el("span", { class: "editor-buttons" },
        button("open…", "replace the text by a file from your computer", () => open.click()),
        button("save", "download this text as a .glsl file", () => this.save()),
        button("reset", "go back to the version the lab came with", () => this.reset()),
        button("×", "close the editor (the panel keeps the last version that compiled)", () => this.close()),
        open)),
      this.host, this.status);
    this.editor = createEditor(this.host, { onChange: () => this.schedule() });
  }

  /** Edits the model of `panel`; `original` is what reset goes back to. `build(text)`
   * makes the model of a text (a library file, an opened file, an exercise's submission);
   * `path` is the file's name in messages; exercise mode gives `onResult(errors)`. */
  open(panel, original, { build = null, path = null, onResult = null, text = null } = {}) {
    this.panel = panel;
    this.original = original;
    this.build = build;
    this.onResult = onResult;
    this.path = path || panel.model?.path || `${panel.name}.glsl`;
    this.fileInput.accept = this.path.match(/\.[^./]*$/)?.[0] ?? ".glsl";
    this.title.textContent = `${this.path.split("/").pop()}: edits apply to the ${panel.name} panel as you type`;
    this.root.hidden = false;
    this.editor.setText(text ?? panel.model?.code ?? original);
    this.check();
  }

  close() {
    clearTimeout(this.timer);
    this.root.hidden = true;
    this.panel = null;
  }

  schedule() {
    // Kept at once (not after the check): a reload right after typing loses nothing.
    if (this.panel) this.actions.keepText(this.panel, this.editor.text);
    clearTimeout(this.timer);
    this.timer = setTimeout(() => this.check(), DEBOUNCE_MS);
  }

  /** Header and compile check of the text; installs it when both pass. */
  check() {
    clearTimeout(this.timer);
    const panel = this.panel;
    if (!panel) return [];
    const text = this.editor.text;
    this.actions.keepText(panel, text);
    const file = this.path.split("/").pop();
    let errors = [];
    try {
      const model = this.build ? this.build(text) : parseModel(text, this.path, panel.name);
      this.actions.tryCompile(panel, model);
      this.actions.install(panel, model);
    } catch (err) {
      if (err instanceof ModelError) errors = [{ line: err.line || 1, message: err.detail }];
      else if (err.errors) {
        // Compile errors in this file at their lines; any elsewhere (the lab's own files,
        // reached through this one) on the first line, naming where they are.
        // A wrapper model (exercise mode) follows the student's text in the same file.
        const own = text.split("\n").length;
        errors = err.errors.map((e) => (e.file === this.path && e.line <= own ? { line: e.line, message: e.message }
          : { line: 1, message: `${e.file === this.path ? "the library model after your file" : e.file}:${e.line}: ${e.message}` }));
        if (!errors.length) errors = [{ line: 1, message: err.message }];
      } else throw err;
    }
    this.editor.showErrors(errors);
    const lines = [...new Set(errors.map((e) => e.line))].join(", ");
    this.status.textContent = errors.length
      ? `${errors.length} error${errors.length > 1 ? "s" : ""} in ${file} (line ${lines}): the panel shows the last version that compiled`
      : `${file} compiles: the panel shows this version`;
    this.status.classList.toggle("bad", errors.length > 0);
    this.onResult?.(errors);
    this.checks++;
    return errors;
  }

  save() {
    const blob = new Blob([this.editor.text], { type: "text/plain" });
    const a = el("a", { href: URL.createObjectURL(blob), download: this.path.split("/").pop() });
    document.body.append(a);
    a.click();
    a.remove();
    setTimeout(() => URL.revokeObjectURL(a.href), 1000);
  }

  reset() {
    this.editor.setText(this.original);
    this.check();
  }
}

// The web lab's shader editor: CodeMirror 6 with GLSL highlighting (the legacy "shader"
// mode), a dark theme, and compile errors shown at their lines. Bundled by esbuild into
// lab/web/static/editor.js (npm run build); the page loads no code from anywhere else.
import { EditorView, basicSetup } from "codemirror";
import { EditorState } from "@codemirror/state";
import { HighlightStyle, StreamLanguage, syntaxHighlighting } from "@codemirror/language";
import { tags } from "@lezer/highlight";
import { shader } from "@codemirror/legacy-modes/mode/clike";
import { forEachDiagnostic, lintGutter, setDiagnostics } from "@codemirror/lint";
import { oneDark } from "@codemirror/theme-one-dark";

// One Dark's grey (comments, line numbers) is 3.9:1 and its coral (names) 4.4:1 on its
// background: lighter shades of both reach 4.5:1 (WCAG 1.4.3) at 6.1:1 and 6.2:1.
const READABLE_GREY = "#a3acbd";
const READABLE_CORAL = "#f0939b";
const readable = [
  syntaxHighlighting(HighlightStyle.define([
    { tag: [tags.comment, tags.lineComment, tags.blockComment, tags.meta, tags.link], color: READABLE_GREY },
    { tag: [tags.name, tags.deleted, tags.character, tags.propertyName, tags.macroName], color: READABLE_CORAL },
  ])),
  EditorView.theme({ ".cm-gutters": { color: READABLE_GREY } }, { dark: true }),
];

/** An editor in `parent` holding `doc`; `onChange(text)` after every edit. */
export function createEditor(parent, { doc = "", onChange = () => {} } = {}) {
  const view = new EditorView({
    parent,
    state: EditorState.create({
      doc,
      extensions: [
        basicSetup,
        StreamLanguage.define(shader),
        readable, // before One Dark: the first highlighter and theme to style a token win
        oneDark,
        lintGutter(),
        EditorView.lineWrapping,
        EditorView.updateListener.of((update) => {
          if (update.docChanged) onChange(update.state.doc.toString());
        }),
        EditorView.contentAttributes.of({ "aria-label": "GLSL source; compile errors are listed below" }),
      ],
    }),
  });
  return {
    view,
    get text() {
      return view.state.doc.toString();
    },
    /** Replaces the whole text (as an edit: onChange runs). */
    setText(text) {
      view.dispatch({ changes: { from: 0, to: view.state.doc.length, insert: text } });
    },
    /** Marks errors [{line, message}] (1-based lines of this text); [] clears them. */
    showErrors(errors) {
      const doc = view.state.doc;
      const diagnostics = errors
        .filter((e) => e.line >= 1 && e.line <= doc.lines)
        .map((e) => {
          const line = doc.line(e.line);
          return { from: line.from, to: line.to, severity: "error", message: e.message };
        });
      view.dispatch(setDiagnostics(view.state, diagnostics));
      return diagnostics.length;
    },
    /** The errors marked now: [{line, message}]. */
    errors() {
      const out = [];
      forEachDiagnostic(view.state, (d, from) => {
        out.push({ line: view.state.doc.lineAt(from).number, message: d.message });
      });
      return out;
    },
  };
}

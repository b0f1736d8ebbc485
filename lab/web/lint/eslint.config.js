// ESLint for the web lab's own JavaScript, run from lab/web by tests/test_web_js.py
// (`eslint --config lint/eslint.config.js`: the patterns below are relative to lab/web).
// The bundled editor (static/editor.js, built by esbuild from npm packages) is not ours.
import js from "@eslint/js";
import globals from "globals";

export default [
  { ignores: ["static/editor.js", "editor/**", "lint/**", "**/node_modules/**"] },
  js.configs.recommended,
  {
    files: ["static/**/*.js"],
    languageOptions: { ecmaVersion: 2023, sourceType: "module", globals: { ...globals.browser } },
  },
  {
    files: ["*.mjs", "static/deck.js"],
    languageOptions: { ecmaVersion: 2023, sourceType: "module", globals: { ...globals.browser, ...globals.node } },
  },
  {
    rules: {
      // Leaving out keys by destructuring them into _ names is how a copy drops them.
      "no-unused-vars": ["error", { args: "none", caughtErrors: "none", ignoreRestSiblings: true }],
      "no-var": "error",
      "prefer-const": ["error", { destructuring: "all" }],
      eqeqeq: ["error", "always"],
      "no-shadow": "off",
      "no-implicit-globals": "error",
      "no-use-before-define": ["error", { functions: false, classes: false, variables: false }],
    },
  },
];

// The deck for the keyboard and for zoom (WCAG 2.1.4, 1.4.4, 2.4.7). Loaded before
// Reveal.initialize by build.mjs.
//  - reveal's one-letter shortcuts can be switched off (?letters=off, kept for the session)
//    or remapped (?keys=n:next,p:prev: letter -> a Reveal method);
//  - keys pressed while focus is inside a control on a slide stay with that control;
//  - browser zoom enlarges the text: the slide's logical size shrinks by the zoom factor,
//    so reveal's fit-to-window no longer undoes the zoom; a slide taller than the window scrolls.
window.deckA11y = (() => {
  const params = new URLSearchParams(location.search);
  const store = (key, value) => {
    try {
      if (value !== null) sessionStorage.setItem(key, value);
      return sessionStorage.getItem(key);
    } catch {
      return value;
    }
  };
  const letters = store("deck-letters", params.get("letters")) !== "off";
  const remap = store("deck-keys", params.get("keys")) || "";
  const WIDTH = 1280;
  const HEIGHT = 800;

  /** Reveal's `keyboard` option: the remapped letters (an empty object maps none). */
  function keyboard() {
    const map = {};
    for (const pair of remap.split(",").filter(Boolean)) {
      const [key, action] = pair.split(":");
      if (key && key.length === 1 && action) map[key.toUpperCase().charCodeAt(0)] = action;
    }
    return map;
  }

  const isLetter = (e) => e.key.length === 1 && /[a-z.,/?]/i.test(e.key);
  const owned = (e) => {
    const t = document.activeElement;
    if (!t || t === document.body) return false;
    if (t.closest(".reveal .slides") && t.matches("input, select, textarea, button, summary, [tabindex], [contenteditable]")) {
      return e.key === " " || e.key === "Enter" || e.key.startsWith("Arrow") || isLetter(e);
    }
    return false;
  };

  /** reveal's keyboardCondition: false leaves the key alone. */
  function condition(e) {
    if (owned(e)) return false;
    if (isLetter(e) && !e.ctrlKey && !e.metaKey && !e.altKey) {
      const code = e.key.toUpperCase().charCodeAt(0);
      if (!letters && !(code in keyboard())) return false;
    }
    return true;
  }

  // The zoom the page was opened at: the baseline (kept while reloading in the session).
  const base = Number(store("deck-dpr", null)) || Number(store("deck-dpr", String(devicePixelRatio)));
  const zoom = () => Math.max(1, devicePixelRatio / base);

  function fit(Reveal) {
    const z = zoom();
    const { width } = Reveal.getConfig();
    if (Math.abs(width - WIDTH / z) < 1) return;
    Reveal.configure({ width: Math.round(WIDTH / z), height: Math.round(HEIGHT / z) });
    document.documentElement.classList.toggle("zoomed", z > 1);
  }

  function attach(Reveal) {
    Reveal.configure({ keyboardCondition: condition });
    Reveal.on("ready", () => fit(Reveal));
    addEventListener("resize", () => fit(Reveal));
  }

  return { keyboard, condition, attach, zoom };
})();

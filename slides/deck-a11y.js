// The deck for the keyboard and for zoom (WCAG 2.1.4, 1.4.4, 2.4.7). Loaded before
// Reveal.initialize by build.mjs.
//  - reveal's one-letter shortcuts can be switched off (?letters=off, kept for the session)
//    or remapped (?keys=n:next,p:prev: letter -> a Reveal method);
//  - keys pressed while focus is inside a control on a slide stay with that control;
//  - browser zoom enlarges the text: the slide's logical size shrinks by the zoom factor,
//    so reveal's fit-to-window no longer undoes the zoom; what no longer fits on a slide
//    reflows onto continuation pages below it (vertical slides, "(continued)"; the arrows
//    step through them), so a zoomed slide does not scroll inside. A single block taller
//    than a page (a live demo, a large figure) is fitted to the page's height.
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

  // -- reflow onto continuation pages ----------------------------------------------------------
  let pages = []; // [{ wrapper, first, moved: [[node, parent, before]...], sizes: [[el, height]] }]

  const SLACK = 6; // slide px kept free at the bottom of a page (rounding, descenders)

  /** Where `el`'s bottom is, in slide px below the top of `page`. */
  const bottom = (el, page, scale) => (el.getBoundingClientRect().bottom - page.getBoundingClientRect().top) / scale;

  /** Splits `list` where its items pass `limit` (slide px in `page`): returns the list of the
   * items that go on (null when none fit). An item whose own sub-list starts within the limit
   * splits inside it, and goes on as an item without its bullet. */
  function splitList(list, page, limit, scale, record) {
    const items = [...list.children];
    const k = items.findIndex((li) => bottom(li, page, scale) > limit);
    if (k < 0) return null;
    const tail = list.cloneNode(false);
    if (list.tagName === "OL") tail.start = (list.start || 1) + k;
    const inner = items[k].querySelector(":scope > ul, :scope > ol");
    let from = k;
    if (inner && inner.firstElementChild && bottom(inner.firstElementChild, page, scale) <= limit) {
      const rest = splitList(inner, page, limit, scale, record);
      if (rest) {
        const item = document.createElement("li");
        item.className = "continued";
        item.append(rest);
        record.made.push(item);
        tail.append(item);
        from = k + 1;
      }
    } else if (k === 0) return null;
    for (const li of items.slice(from)) {
      move(li, tail, record);
    }
    record.made.push(tail);
    return tail;
  }

  /** Moves `node` to the end of `to`, remembering where it was (unsplit puts it back). */
  function move(node, to, record) {
    record.moved.push([node, node.parentNode, node.nextSibling]);
    to.append(node);
  }

  /** Splits a paragraph taller than a page between sentences (or after a colon or a
   * semicolon): the sentences that end
   * within `limit` stay; returns a paragraph of the rest (null when the first does not fit). */
  function splitParagraph(p, page, limit, scale, record) {
    const starts = [];
    for (const node of [...p.childNodes]) {
      let text = node;
      let end;
      while (text.nodeType === 3 && (end = /[.;:!?]\s+(?=\S)/.exec(text.data))) {
        text = text.splitText(end.index + end[0].length);
        starts.push(text);
      }
    }
    const before = (node) => {
      const range = document.createRange();
      range.setStart(p, 0);
      range.setEndBefore(node);
      return (range.getBoundingClientRect().bottom - page.getBoundingClientRect().top) / scale;
    };
    let cut = null;
    for (const start of starts) {
      if (before(start) > limit) break;
      cut = start;
    }
    if (!cut) return null;
    const tail = p.cloneNode(false);
    for (let node = cut, after; node; node = after) {
      after = node.nextSibling;
      move(node, tail, record);
    }
    record.made.push(tail);
    return tail;
  }

  const talls = (block) => (block.matches("iframe, img") ? [block] : [...block.querySelectorAll("iframe, img")]);
  const hasTall = (block) => talls(block).length > 0;

  /** Shrinks the demos and pictures in `block` until its bottom is within `limit`. */
  function fitInto(block, page, limit, scale, record) {
    const shrink = talls(block);
    for (const t of shrink) record.sizes.push([t, t.style.height, t.style.maxHeight]);
    for (let i = 0; i < 4; i++) {
      const over = bottom(block, page, scale) - limit;
      if (over <= 0.5) return true;
      for (const t of shrink) {
        t.style.maxHeight = `${Math.max(t.getBoundingClientRect().height / scale - over, 80)}px`;
        if (t.tagName === "IFRAME") t.style.height = t.style.maxHeight;
      }
    }
    return bottom(block, page, scale) <= limit + 0.5;
  }

  /** Gives the demos and pictures in `block` their own sizes back. */
  function unfit(block, record) {
    const mine = new Set(talls(block));
    record.sizes = record.sizes.filter(([t, height, maxHeight]) => {
      if (!mine.has(t)) return true;
      [t.style.height, t.style.maxHeight] = [height, maxHeight];
      return false;
    });
  }

  /** Moves what does not fit in `height` from `section` to new pages after it; returns them. */
  function split(section, height, heading, record, scale) {
    const made = [];
    let page = section;
    for (let guard = 0; guard < 20; guard++) {
      const kids = [...page.children].filter((c) => c.tagName !== "ASIDE");
      const k = kids.findIndex((c) => bottom(c, page, scale) > height - SLACK);
      if (k < 0) break;
      const block = kids[k];
      const above = k ? bottom(kids[k - 1], page, scale) : 0;
      const next = document.createElement("section");
      next.style.display = "block"; // measured next; reveal shows it as a slide after sync
      const title = heading.cloneNode(true);
      title.textContent = `${heading.textContent} (continued)`;
      record.made.push(title);
      next.append(title);
      let rest = kids.slice(k);
      // A list, or a box (<small>) holding one, splits between its items.
      const isList = (e) => e && /^(UL|OL)$/.test(e.tagName);
      const list = isList(block) ? block : block.children.length === 1 && isList(block.firstElementChild) ? block.firstElementChild : null;
      let tail = list ? splitList(list, page, height - SLACK, scale, record) : null;
      if (block.tagName === "P" && !hasTall(block)) tail = splitParagraph(block, page, height - SLACK, scale, record);
      if (tail && list !== block) {
        const box = block.cloneNode(false);
        box.append(tail);
        record.made.push(box);
        tail = box;
      }
      if (tail) {
        next.append(tail); // the items that fit stay
        rest = rest.slice(1);
      } else if (k <= 1 || (hasTall(block) && height - above > 0.4 * height)) {
        // Alone on its page (under its heading), or with room left, and still too tall: a
        // demo or a figure is fitted to the page (where it does not fit below text, it
        // goes on the next page); text taller than a page scrolls.
        if (fitInto(block, page, height - 3 * SLACK, scale, record) || k <= 1) {
          if (k + 1 >= kids.length) break;
          rest = rest.slice(1);
        } else unfit(block, record);
      }
      for (const node of rest) move(node, next, record);
      page.after(next);
      made.push(next);
      page = next;
    }
    return made;
  }

  /** Puts every moved node back where it was (zoom back to 100 %). */
  function unsplit() {
    for (const record of pages.reverse()) {
      for (const [node, parent, before] of record.moved.reverse()) parent.insertBefore(node, before);
      for (const [, parent] of record.moved) parent.normalize(); // a paragraph's sentences join again
      for (const node of record.made) node.remove();
      for (const [el, height, maxHeight] of record.sizes) [el.style.height, el.style.maxHeight] = [height, maxHeight];
      record.wrapper.replaceWith(record.first);
    }
    pages = [];
  }

  /** Each slide taller than a page goes on as vertical pages below it. */
  function reflow(Reveal) {
    const { height } = Reveal.getConfig();
    const slides = [...document.querySelectorAll(".reveal .slides > section")];
    // Every slide laid out while it is measured (reveal hides those far from the present one).
    const shown = slides.map((s) => [s, s.style.display, s.hidden]);
    for (const section of slides) [section.style.display, section.hidden] = ["block", false];
    const box = document.querySelector(".reveal .slides");
    const scale = box.getBoundingClientRect().width / box.offsetWidth || 1; // reveal's fit
    for (const section of slides) {
      if (section.querySelector(":scope > section")) continue; // already vertical
      const heading = section.querySelector(":scope > h1, :scope > h2");
      if (!heading) continue;
      const record = { moved: [], sizes: [], made: [], first: section };
      const made = split(section, height, heading, record, scale);
      if (!made.length && !record.sizes.length) continue;
      const wrapper = document.createElement("section");
      section.replaceWith(wrapper);
      wrapper.append(section, ...made);
      record.wrapper = wrapper;
      record.made = [...record.made, ...made];
      pages.push(record);
    }
    // A page still taller than the slide (text longer than a page) scrolls; the others do not,
    // whatever an equation draws a few px below its line.
    const leaves = document.querySelectorAll(".reveal .slides > section:not(.stack), .reveal .slides > section > section");
    for (const leaf of leaves) {
      leaf.classList.remove("tall");
      const last = [...leaf.children].filter((c) => c.tagName !== "ASIDE").pop();
      if (last && bottom(last, leaf, scale) > height + 1) leaf.classList.add("tall");
    }
    for (const [section, display, hidden] of shown) [section.style.display, section.hidden] = [display, hidden];
    for (const record of pages) for (const page of record.wrapper.children) if (page !== record.first) page.style.display = "";
  }

  /** Fits the slide size to the zoom; `again`: measure the pages again (fonts arrived). */
  function fit(Reveal, again = false) {
    const z = zoom();
    const { width } = Reveal.getConfig();
    if (Math.abs(width - WIDTH / z) < 1 && !(again && z > 1)) return;
    const at = Reveal.getIndices();
    const page = pages.find((r) => r.wrapper.contains(Reveal.getCurrentSlide())) ? 0 : at.v;
    unsplit();
    Reveal.configure({ width: Math.round(WIDTH / z), height: Math.round(HEIGHT / z),
      navigationMode: z > 1 ? "linear" : "default" });
    document.documentElement.classList.toggle("zoomed", z > 1);
    if (z > 1) reflow(Reveal);
    Reveal.sync();
    Reveal.slide(at.h, page);
  }

  function attach(Reveal) {
    Reveal.configure({ keyboardCondition: condition });
    Reveal.on("ready", () => fit(Reveal));
    addEventListener("resize", () => fit(Reveal));
    // A font that arrives later (the equations' sizes) changes what fits: measure again.
    let timer = 0;
    const again = () => {
      clearTimeout(timer);
      timer = setTimeout(() => fit(Reveal, true), 100);
    };
    document.fonts?.addEventListener("loadingdone", again);
    document.fonts?.ready.then(again);
  }

  return { keyboard, condition, attach, zoom };
})();

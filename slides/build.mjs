// Builds the lecture deck: lecture.md -> index.html (reveal.js), equations typeset by KaTeX
// at build time, `::demo` lines -> iframes of the web lab, `::figures [HEIGHT] A.png "caption" | ...`
// lines -> figure rows.
// Usage: node slides/build.mjs OUTDIR   (brdf-lab slides build runs it after npm ci and
// after rendering the figures into OUTDIR/figures and exporting the lab into OUTDIR/lab).
import { cpSync, existsSync, mkdirSync, readFileSync, writeFileSync } from "node:fs";
import { dirname, join } from "node:path";
import { fileURLToPath } from "node:url";

import katex from "katex";
import { marked } from "marked";

const HERE = dirname(fileURLToPath(import.meta.url));
const SOURCE = join(HERE, "lecture.md");
const LABEL = "slides/lecture.md";

function fail(line, message) {
  console.error(`${LABEL}:${line}: ${message}`);
  process.exit(1);
}

const escapeHtml = (text) =>
  text.replace(/&/g, "&amp;").replace(/</g, "&lt;").replace(/>/g, "&gt;").replace(/"/g, "&quot;");

/** Slides separated by lines that are exactly `---`, each with its first line number. */
function splitSlides(text) {
  const slides = [];
  let current = { line: 1, lines: [] };
  text.split("\n").forEach((line, index) => {
    if (line.trim() === "---") {
      slides.push(current);
      current = { line: index + 2, lines: [] };
    } else current.lines.push(line);
  });
  slides.push(current);
  return slides.filter((s) => s.lines.some((l) => l.trim()));
}

function typeset(tex, display, line) {
  try {
    // MathML beside the HTML: screen readers read the MathML, eyes see the HTML.
    return katex.renderToString(tex, { displayMode: display, throwOnError: true, output: "htmlAndMathml" });
  } catch (err) {
    fail(line, `the equation ${JSON.stringify(tex.slice(0, 40))} does not typeset: ${err.message}`);
  }
}

function renderSlide(slide, outdir, used) {
  const math = [];
  const keep = (html) => `MATHPLACEHOLDER${math.push(html) - 1}X`;
  const body = [];
  let notes = [];
  slide.lines.forEach((raw, offset) => {
    const line = slide.line + offset;
    const demo = /^::demo\s+(\S+)(?:\s+(\d+))?\s*$/.exec(raw);
    const ibl = /^::ibl\s+(\S+)(?:\s+(\d+))?\s*$/.exec(raw);
    const figures = /^::figures\s+(?:(\d+)\s+)?(.*)$/.exec(raw); // optional: max height (px)
    if (ibl) {
      // The reflection equation by Monte Carlo: the lab's IBL view, live (lab/ibl_demo.html).
      used.ibl.push({ slide: used.count, hash: ibl[1] });
      body.push(keep(`<iframe class="ibl-demo" data-src="lab/ibl_demo.html#${escapeHtml(ibl[1])}&amp;embed=1"` +
        ` style="width:100%;border:0;height:${ibl[2] || "420"}px" title="live Monte Carlo demo"></iframe>`));
    } else if (demo) {
      const height = demo[2] || "560";
      used.demos.push({ slide: used.count, hash: demo[1] });
      body.push(keep(`<iframe class="demo" data-src="lab/index.html#${escapeHtml(demo[1])}&amp;embed=1"` +
        ` style="height:${height}px" title="live demo"></iframe>`));
    } else if (figures) {
      const style = figures[1] ? ` style="max-height:${figures[1]}px"` : "";
      const cells = figures[2].split("|").map((cell) => {
        const m = /^\s*(\S+\.png)\s*(?:"([^"]*)")?\s*$/.exec(cell);
        if (!m) fail(line, `write '::figures NAME.png "caption" | ...', not ${JSON.stringify(cell)}`);
        if (!existsSync(join(outdir, "figures", m[1]))) {
          fail(line, `figure ${m[1]} was not rendered (lab.figures.lecture_figures makes it)`);
        }
        used.figures.push(m[1]);
        // A plot's values in words (lab/describe.py, via lab.figures) follow its caption.
        const words = descriptions[m[1]] ? `. ${descriptions[m[1]]}` : "";
        return `<figure><img src="figures/${m[1]}" alt="${escapeHtml((m[2] || m[1]) + words)}"${style}>` +
          `<figcaption>${escapeHtml(m[2] || "")}</figcaption></figure>`;
      });
      body.push(keep(`<div class="figures">${cells.join("")}</div>`));
    } else if (/^Note:/.test(raw) || notes.length) {
      notes.push(raw.replace(/^Note:\s*/, ""));
    } else body.push(raw);
  });
  let text = body.join("\n");
  // Equations first, so markdown never sees their underscores and backslashes.
  text = text.replace(/\$\$([\s\S]+?)\$\$/g, (_, tex) => keep(typeset(tex.trim(), true, slide.line)));
  text = text.replace(/(^|[^\\$])\$([^$\n]+?)\$/g, (_, before, tex) => before + keep(typeset(tex, false, slide.line)));
  let html = marked.parse(text);
  html = html.replace(/<p>(MATHPLACEHOLDER\d+X)<\/p>/g, "$1");
  html = html.replace(/MATHPLACEHOLDER(\d+)X/g, (_, i) => math[Number(i)]);
  const aside = notes.length ? `<aside class="notes">${marked.parse(notes.join("\n"))}</aside>` : "";
  used.count++;
  return `<section data-source-line="${slide.line}">\n${html}${aside}</section>`;
}

const outdir = process.argv[2];
if (!outdir) fail(1, "give the output folder: node slides/build.mjs OUTDIR");
mkdirSync(outdir, { recursive: true });
const described = join(outdir, "figures", "descriptions.json");
const descriptions = existsSync(described) ? JSON.parse(readFileSync(described, "utf8")) : {};
const used = { count: 0, demos: [], ibl: [], figures: [] };
const sections = splitSlides(readFileSync(SOURCE, "utf8")).map((s) => renderSlide(s, outdir, used));
const lib = (from, to) => cpSync(join(HERE, "node_modules", from), join(outdir, "lib", to), { recursive: true });
lib("reveal.js/dist", "reveal");
lib("katex/dist/katex.min.css", "katex/katex.min.css");
lib("katex/dist/fonts", "katex/fonts");
cpSync(join(HERE, "deck.css"), join(outdir, "deck.css"));
cpSync(join(HERE, "deck-a11y.js"), join(outdir, "deck-a11y.js"));

writeFileSync(join(outdir, "index.html"), `<!doctype html>
<html lang="en">
<head>
<meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<title>BRDFs: how surfaces reflect light</title>
<link rel="icon" href="data:,">
<link rel="stylesheet" href="lib/reveal/reset.css">
<link rel="stylesheet" href="lib/reveal/reveal.css">
<link rel="stylesheet" href="lib/reveal/theme/white.css">
<link rel="stylesheet" href="lib/katex/katex.min.css">
<link rel="stylesheet" href="deck.css">
</head>
<body>
<div class="reveal"><div class="slides">
${sections.join("\n")}
</div></div>
<script src="lib/reveal/reveal.js"></script>
<script src="deck-a11y.js"></script>
<script>
  Reveal.initialize({ hash: true, width: 1280, height: 800, margin: 0.03, center: false,
    transition: "none", viewDistance: 2, pdfMaxPagesPerSlide: 1, keyboard: deckA11y.keyboard() });
  deckA11y.attach(Reveal);
  // A live demo keeps the keyboard focus after a click; it passes the slide keys up here.
  addEventListener("message", (e) => {
    const demo = [...document.querySelectorAll("iframe.demo, iframe.ibl-demo")].some((f) => f.contentWindow === e.source);
    if (!demo || !e.data || e.data.brdfLab !== "slide") return;
    // The frame leaves with its slide: give the keyboard back to the deck first.
    document.activeElement?.blur();
    window.focus();
    if (e.data.step === "next") Reveal.next();
    else if (e.data.step === "prev") Reveal.prev();
  });
</script>
</body>
</html>
`);
writeFileSync(join(outdir, "deck.json"), JSON.stringify(used, null, 1) + "\n");
console.log(`${used.count} slides, ${used.demos.length + used.ibl.length} live demos, ${used.figures.length} figures`);

"""The lecture deck builds (npm ci, figures, KaTeX), every slide renders without console
errors in headless Chromium, every live demo shows a rendered sphere, and it prints to PDF."""

from __future__ import annotations

import re
import shutil

import pytest

from lab.web.browser import chromium_path, sibling

pytestmark = pytest.mark.skipif(
    shutil.which("node") is None or shutil.which("npm") is None or chromium_path() is None,
    reason="needs node, npm and Chromium (apt-get install nodejs npm chromium)",
)

# Slides (by their heading) saved as screenshots besides every live demo.
SCREENSHOT_SLIDES = {
    "BRDFs": "title",
    "The BRDF: definition": "definition",
    "Lambert's sun and moon": "sun_moon",
    "The Phong exponent": "phong_figures",
    "Cook-Torrance: the terms": "cook_torrance_terms",
}

# In a demo's frame: where every visible control and canvas is, and how far the page scrolls.
LAYOUT = """() => {
  const boxes = [...document.querySelectorAll("input, select, button, canvas")]
    .filter((e) => e.getClientRects().length && getComputedStyle(e).visibility !== "hidden")
    .map((e) => { const r = e.getBoundingClientRect();
      const what = e.tagName + (e.type ? ":" + e.type : "") + "." + e.className;
      return { what,
               left: r.left, top: r.top, right: r.right, bottom: r.bottom }; });
  const root = document.documentElement;
  return { boxes, width: innerWidth, height: innerHeight,
           scroll: [root.scrollWidth - innerWidth, root.scrollHeight - innerHeight],
           sliders: document.querySelectorAll("input[type=range]").length };
}"""

# Drawn pixels (alpha > 0) of a panel's polar plot, a 2D canvas.
POLAR_PIXELS = """i => { const c = brdfLab.panel(i).polar;
  const d = c.getContext("2d").getImageData(0, 0, c.width, c.height).data; let n = 0;
  for (let k = 3; k < d.length; k += 4) if (d[k] > 0) n++; return n / (c.width * c.height); }"""


@pytest.fixture(scope="module")
def deck(output_dir):
    from lab.cli import main

    outdir = output_dir / "deck"
    if outdir.exists():
        shutil.rmtree(outdir)
    for old in output_dir.glob("slide_*.png"):  # slide numbers move when slides are added
        old.unlink()
    assert main(["slides", "build", str(outdir)]) == 0
    return outdir


@pytest.fixture(scope="module")
def deck_page(deck):
    from lab.web.browser import chromium
    from lab.web.site import serving

    with serving(deck) as url, chromium() as browser:
        page = browser.new_page(viewport={"width": 1280, "height": 800})
        errors: list[str] = []
        page.on("console", lambda m: m.type == "error" and errors.append(m.text))
        page.on("pageerror", lambda e: errors.append(str(e)))
        page.goto(f"{url}index.html")
        page.wait_for_function("window.Reveal && Reveal.isReady()")
        page.errors = errors
        page.lab_browser = browser
        yield page


def test_deck_builds(deck):
    from lab.web.slides import deck_info

    info = deck_info(deck)
    assert info["count"] >= 30
    assert len(info["demos"]) >= 5
    assert sorted(set(info["figures"])) == sorted(p.name for p in (deck / "figures").glob("*.png"))
    html = (deck / "index.html").read_text(encoding="utf-8")
    assert html.count('class="katex') >= 30  # equations typeset at build time
    text = re.sub(r"<[^>]+>", " ", html)
    assert "$$" not in text and "\\frac" not in re.sub(r"<annotation.*?</annotation>", "", html)
    for needed in (
        "lib/reveal/reveal.js",
        "lib/katex/katex.min.css",
        "lab/index.html",
        "lab/manifest.json",
        "lab/shaders/brdfs/phong.glsl",
    ):
        assert (deck / needed).is_file(), needed
    assert not (deck / "node_modules").exists()


def test_every_slide_renders(deck, deck_page, output_dir):
    from lab.web.slides import deck_info

    info = deck_info(deck)
    demo_slides = {d["slide"]: d["hash"] for d in info["demos"]}
    assert deck_page.evaluate("Reveal.getTotalSlides()") == info["count"]
    headings = deck_page.evaluate(
        "[...document.querySelectorAll('.reveal .slides > section')]"
        ".map(s => (s.querySelector('h1, h2') || {}).textContent || '')"
    )
    shots = {headings.index(h): name for h, name in SCREENSHOT_SLIDES.items()}
    for index in range(info["count"]):
        deck_page.evaluate(f"Reveal.slide({index})")
        deck_page.wait_for_timeout(50)
        if index in demo_slides:
            frames = deck_page.query_selector_all("section.present iframe.demo")
            assert len(frames) == 1, f"slide {index}: no demo iframe"
            frame = frames[0].content_frame()
            frame.wait_for_function(
                "window.brdfLab && brdfLab.state.firstRenderMs !== null", timeout=30_000
            )
            assert frame.evaluate("brdfLab.notes()") == [], f"bad preset {demo_slides[index]}"
            panels = frame.evaluate("brdfLab.state.panels.length")
            for i in range(panels):
                assert frame.evaluate(f"brdfLab.errors({i})") == ""
                # A non-empty canvas: many lit pixels on the sphere (read back as floats).
                lit = frame.evaluate(
                    f"(() => {{ const s = brdfLab.panel({i}).readSphere(); let n = 0;"
                    " for (let k = 0; k < s.data.length; k += 4)"
                    " if (s.data[k + 3] > 0 && s.data[k] + s.data[k + 1] + s.data[k + 2] > 1e-3)"
                    " n++;"
                    " return n / (s.width * s.height); })()"
                )
                assert lit > 0.01, f"slide {index} panel {i}: the sphere is (nearly) empty"
                drawn = frame.evaluate(POLAR_PIXELS, i)
                assert drawn > 0.01, f"slide {index} panel {i}: the polar plot is empty"
            check_demo_fits(deck_page, frames[0], frame, index)
            deck_page.screenshot(path=output_dir / f"slide_{index:02d}_demo.png")
        elif index in shots:
            name = f"slide_{index:02d}_{shots[index]}.png"
            deck_page.screenshot(path=output_dir / name)
        assert deck_page.errors == [], f"slide {index}: {deck_page.errors}"


def check_demo_fits(deck_page, iframe, frame, index: int, sliders: int = 3) -> None:
    """The demo's frame lies on the slide, and every control and canvas of the lab lies
    inside the frame: nothing needs scrolling during the lecture."""
    slide = deck_page.evaluate(
        "(() => { const r = document.querySelector('.reveal .slides').getBoundingClientRect();"
        " return { left: r.left, top: r.top, right: r.right, bottom: r.bottom }; })()"
    )
    box = iframe.bounding_box()
    assert box["y"] + box["height"] <= slide["bottom"] + 1, f"slide {index}: the demo runs off"
    assert box["x"] >= slide["left"] - 1 and box["x"] + box["width"] <= slide["right"] + 1
    layout = frame.evaluate(LAYOUT)
    assert layout["scroll"][0] <= 0 and layout["scroll"][1] <= 0, (
        f"slide {index}: the demo scrolls by {layout['scroll']} px"
    )
    assert layout["sliders"] >= sliders  # the light's two and one parameter or exposure
    for b in layout["boxes"]:
        inside = (
            b["left"] >= -0.5
            and b["top"] >= -0.5
            and b["right"] <= layout["width"] + 0.5
            and b["bottom"] <= layout["height"] + 0.5
        )
        assert inside, f"slide {index}: {b['what']} is outside the demo's frame: {b}"


def test_pdf(deck, deck_page, tmp_path):
    from lab.web.slides import deck_info, pdf

    with sibling(deck_page.lab_browser) as browser:  # not the other tests' WebGL contexts
        out = pdf(deck, tmp_path / "handout.pdf", browser=browser)
    data = out.read_bytes()
    assert data.startswith(b"%PDF")
    pages = len(re.findall(rb"/Type\s*/Page[^s]", data))
    assert pages == deck_info(deck)["count"]


def test_pdf_waits_for_the_monte_carlo_demo_or_says_snapshot(deck, deck_page):
    """The handout shows the Monte Carlo demo at its sample target; where printing cannot
    wait that long, a note beneath the demo says the page is a snapshot, with its count."""
    from lab.web.site import serving
    from lab.web.slides import IBL_PROGRESS, _wait_for_convergence

    with serving(deck) as url:
        page = deck_page.lab_browser.new_page(viewport={"width": 1280, "height": 800})
        page.goto(f"{url}index.html?print-pdf")
        page.wait_for_function("window.Reveal && Reveal.isReady()")
        page.evaluate(
            "document.querySelectorAll('iframe.ibl-demo').forEach(f => f.src = f.dataset.src)"
        )
        frames = "[...document.querySelectorAll('iframe.ibl-demo')].map(f => f.contentWindow)"
        ready = f"{frames}.every(w => w && w.iblDemo && w.iblDemo.panels.length)"
        page.wait_for_function(ready, timeout=120_000)  # they compile at once: slow under load
        _wait_for_convergence(page, 0.2)  # far too short for 2048 samples
        (samples, target), *_ = page.evaluate(IBL_PROGRESS)
        notes = page.eval_on_selector_all("p.snapshot", "ps => ps.map(p => p.textContent)")
        assert samples < target and len(notes) == 1
        assert f"of {target} samples per pixel" in notes[0]
        # A target it can reach: printing waits for it, and says nothing more.
        page.evaluate("document.querySelectorAll('p.snapshot').forEach(p => p.remove())")
        frame = page.query_selector("iframe.ibl-demo").content_frame()
        frame.evaluate("iblDemo.state.target = Math.max(24, ...iblDemo.panels.map(p => p.samples))")
        _wait_for_convergence(page, 120)
        (samples, target), *_ = page.evaluate(IBL_PROGRESS)
        assert samples >= target and page.query_selector("p.snapshot") is None
        page.close()


def test_slide_keys_work_after_using_a_demo(deck, deck_page):
    """A click on a demo's slider gives the frame the focus; a clicker's PageDown and PageUp
    still move between slides (the frame passes them to the deck)."""
    from lab.web.slides import deck_info

    first = deck_info(deck)["demos"][0]["slide"]
    deck_page.evaluate(f"Reveal.slide({first})")
    frame_element = deck_page.wait_for_selector("section.present iframe.demo")
    frame = frame_element.content_frame()
    frame.wait_for_function("window.brdfLab && brdfLab.state.firstRenderMs !== null")
    frame.locator("input[type=range]").first.click()
    assert frame.evaluate("document.hasFocus()")
    deck_page.keyboard.press("PageDown")
    deck_page.wait_for_function(f"Reveal.getIndices().h === {first + 1}", timeout=5_000)
    deck_page.keyboard.press("PageUp")  # the focus stays in the (now hidden) frame
    deck_page.wait_for_function(f"Reveal.getIndices().h === {first}", timeout=5_000)
    assert deck_page.errors == []


# Records what every 2D canvas draws as text (its font and the canvas), so a test can size it.
CANVAS_TEXT_HOOK = """(() => {
  const P = CanvasRenderingContext2D.prototype;
  const fill = P.fillText, clear = P.clearRect;
  P.clearRect = function (x, y, w, h) {
    const all = x <= 0 && y <= 0 && w >= this.canvas.width && h >= this.canvas.height;
    if (all) this.canvas.drawnText = [];
    return clear.apply(this, arguments);
  };
  P.fillText = function (text) {
    (this.canvas.drawnText ||= []).push({ text: String(text), px: parseFloat(this.font) });
    return fill.apply(this, arguments);
  };
})();"""

# In a demo's frame: every visible piece of text with its size in CSS px of the frame.
FRAME_TEXT = """() => {
  const out = [];
  const visible = (e) => e.getClientRects().length && getComputedStyle(e).visibility !== "hidden";
  const walker = document.createTreeWalker(document.body, NodeFilter.SHOW_TEXT);
  for (let n = walker.nextNode(); n; n = walker.nextNode()) {
    const e = n.parentElement;
    if (!n.textContent.trim() || !e || !visible(e) || e.closest("option, script")) continue;
    const px = parseFloat(getComputedStyle(e).fontSize);
    out.push({ text: n.textContent.trim().slice(0, 40), px });
  }
  for (const e of document.querySelectorAll("input[type=text], select")) {
    if (visible(e)) out.push({ text: e.value, px: parseFloat(getComputedStyle(e).fontSize) });
  }
  for (const c of document.querySelectorAll("canvas")) {
    if (!visible(c) || !c.drawnText) continue;
    const k = c.clientWidth / c.width;
    for (const t of c.drawnText) out.push({ text: t.text, px: t.px * k, canvas: true });
  }
  return out;
}"""

MIN_TEXT_PX = 24  # on a 1280x720 screen: readable from the back of a hall


@pytest.fixture(scope="module")
def deck_720(deck, deck_page):
    from lab.web.site import serving

    with serving(deck) as url:
        page = deck_page.lab_browser.new_page(viewport={"width": 1280, "height": 720})
        page.add_init_script(CANVAS_TEXT_HOOK)
        page.goto(f"{url}index.html")
        page.wait_for_function("window.Reveal && Reveal.isReady()")
        yield page
        page.close()


def show_demo(page, slide: int):
    page.evaluate(f"Reveal.slide({slide})")
    iframe = page.wait_for_selector("section.present iframe.demo")
    frame = iframe.content_frame()
    frame.wait_for_function(
        "window.brdfLab && brdfLab.state.firstRenderMs !== null", timeout=30_000
    )
    frame.evaluate("brdfLab.renderNow()")
    # The deck scales the slide (and the frame in it) to the window.
    scale = page.evaluate(
        "(() => { const f = document.querySelector('section.present iframe.demo');"
        " return f.getBoundingClientRect().width / f.offsetWidth; })()"
    )
    return frame, scale


def test_demo_text_readable_at_720p(deck, deck_720, output_dir):
    """Every word a live demo shows, HTML and canvas alike, is at least 24 px high on a
    1280x720 screen (the deck scaled to it, as a projector shows it)."""
    from lab.web.slides import deck_info

    small = []
    for demo in deck_info(deck)["demos"]:
        frame, scale = show_demo(deck_720, demo["slide"])
        texts = frame.evaluate(FRAME_TEXT)
        assert any(t["text"] for t in texts) and scale > 0.5
        assert sum(1 for t in texts if t.get("canvas")) >= 3  # the plots' text is counted
        for t in texts:
            if t["px"] * scale < MIN_TEXT_PX - 0.05:
                small.append(f"slide {demo['slide']}: {t['text']!r} {t['px'] * scale:.1f} px")
        deck_720.screenshot(path=output_dir / f"slide_{demo['slide']:02d}_demo_720p.png")
    assert not small, "text under 24 px at 720p:\n" + "\n".join(small)


def test_off_specular_demo_shows_the_peak(deck, deck_720, renderer):
    """The off-specular demo marks the peaks the renderer computes (past the mirror direction
    with Schlick's F, at it with F = 1) on lobes wide enough to see."""
    from test_claims import peak_angle

    from lab.web.slides import deck_info

    demo = next(d for d in deck_info(deck)["demos"] if "plot=theta" in d["hash"])
    frame, scale = show_demo(deck_720, demo["slide"])
    # Both plots on one θo axis: their mirror and peak marks line up.
    ranges = [frame.evaluate(f"brdfLab.panel({i}).polarGeometry.range") for i in (0, 1)]
    assert ranges[0] == ranges[1], ranges
    for i, fresnel in enumerate(("schlick", "none")):
        values = {"kd": (0.0, 0.0, 0.0), "m": 0.35, "fresnel": fresnel}
        assert frame.evaluate(f"brdfLab.panel({i}).values.fresnel") == fresnel
        expected = peak_angle(renderer, "cook_torrance", values, 60.0)
        shown = frame.evaluate(f"brdfLab.panel({i}).polarGeometry")
        assert shown["peakDeg"] == pytest.approx(expected, abs=1), fresnel
        assert shown["mirrorDeg"] == 60
        assert expected >= 70 if fresnel == "schlick" else expected == 60
        # Not a sliver: the part of the lobe above half its peak spans at least 40 px on screen.
        lo, hi = shown["range"]
        above = frame.evaluate(
            f"(() => {{ const p = brdfLab.panel({i}); const l = p.lobe; const f = [];"
            " for (let k = 0; k < 181; k++)"
            " f.push(l[4*k] * 0.2126 + l[4*k+1] * 0.7152 + l[4*k+2] * 0.0722);"
            " const c = f.map((v, k) => v * Math.cos((k - 90) * Math.PI / 180));"
            " const top = Math.max(...c.filter((_, k) => Math.abs(k - 90) <= 87));"
            " return c.filter((v, k) => Math.abs(k - 90) <= 87 && v >= top / 2).length; })()"
        )
        width = frame.evaluate(f"brdfLab.panel({i}).polar.clientWidth")
        assert above * width / (hi - lo) * scale >= 40


# On the present slide: each figure's image (its scale on screen against its PNG's pixels)
# and caption, and the small print, with font sizes in screen px.
FIGURES = """() => {
  const deck = Reveal.getScale();
  const px = (e) => parseFloat(getComputedStyle(e).fontSize) * deck;
  const figures = [...document.querySelectorAll('section.present .figures figure')].map((f) => {
    const img = f.querySelector('img'), cap = f.querySelector('figcaption');
    return { src: img.getAttribute('src'), ready: img.complete && img.naturalWidth > 0,
             scale: img.getBoundingClientRect().width / img.naturalWidth,
             caption: cap && cap.textContent.trim() ? px(cap) : null };
  });
  const small = [...document.querySelectorAll('section.present small, section.present .source')]
    .filter((e) => e.textContent.trim()).map((e) => ({ text: e.textContent.trim().slice(0, 40),
                                                       px: px(e) }));
  return { figures, small };
}"""


def test_figure_text_readable_at_720p(deck, deck_720, output_dir):
    """Every text inside every figure (its font size in the PNG, which lab.figures records
    beside it, times the image's scale on screen), every caption and the small print is at
    least 24 px on a 1280x720 screen."""
    import json

    from lab.web.slides import deck_info

    small, seen = [], set()
    for index in range(deck_info(deck)["count"]):
        deck_720.evaluate(f"Reveal.slide({index})")
        deck_720.wait_for_function(
            "[...document.querySelectorAll('section.present .figures img')]"
            ".every((i) => i.complete && i.naturalWidth > 0)"
        )
        shown = deck_720.evaluate(FIGURES)
        for figure in shown["figures"]:
            name = figure["src"].removeprefix("figures/")
            seen.add(name)
            sidecar = deck / "figures" / name.replace(".png", ".text.json")
            assert sidecar.is_file(), f"{name}: no record of its text ({sidecar.name})"
            for text in json.loads(sidecar.read_text(encoding="utf-8")):
                if text["px"] * figure["scale"] < MIN_TEXT_PX - 0.05:
                    size = text["px"] * figure["scale"]
                    small.append(f"slide {index}: {name} {text['text']!r} {size:.1f} px")
            if figure["caption"] is not None and figure["caption"] < MIN_TEXT_PX - 0.05:
                small.append(f"slide {index}: caption of {name} {figure['caption']:.1f} px")
        for text in shown["small"]:
            if text["px"] < MIN_TEXT_PX - 0.05:
                small.append(f"slide {index}: {text['text']!r} {text['px']:.1f} px")
        if any(
            f["src"].endswith(("off_specular_peak.png", "vgroove.png")) for f in shown["figures"]
        ):
            deck_720.screenshot(path=output_dir / f"slide_{index:02d}_figure_720p.png")
    assert seen == set(deck_info(deck)["figures"])  # every figure was looked at
    assert not small, "text under 24 px at 720p:\n" + "\n".join(small)


# A panel's polar plot on screen: its half disc's radius, and whether the L (light) mark's
# box, drawn at radius + 0.8 font along the light's direction, meets a ring value's box.
POLAR_MARKS = """([i, thetaI]) => { const p = brdfLab.panel(i), g = p.polarGeometry, c = p.polar;
  const k = c.clientWidth / c.width;
  const font = Math.round(parseFloat(getComputedStyle(document.body).fontSize) / k);
  const r = g.radius + 0.8 * font, a = -thetaI * Math.PI / 180;
  const x = g.centre[0] - r * Math.sin(a), y = g.centre[1] - r * Math.cos(a);
  const box = [x - 0.35 * font, y - 0.5 * font, x + 0.35 * font, y + 0.5 * font];
  const meets = g.ringLabels.filter(([, l, t, rt, b]) =>
    l < box[2] && rt > box[0] && t < box[3] && b > box[1]).map(([text]) => text);
  return { radius: g.radius * k, meets }; }"""


def test_two_model_demos_give_the_plot_room(deck, deck_720):
    """Side by side, each model's polar plot gets a taller canvas: on the grazing-light slide
    (light at 80°) the half disc's radius is at least 80 px on screen (68 before) and the L
    mark stays clear of the rim's value (it used to sit on the '0.53')."""
    from lab.web.slides import deck_info

    demo = next(d for d in deck_info(deck)["demos"] if "light=80,0" in d["hash"])
    frame, scale = show_demo(deck_720, demo["slide"])
    for i in (0, 1):
        marks = frame.evaluate(POLAR_MARKS, [i, 80])
        assert marks["meets"] == [], marks
        assert marks["radius"] * scale >= 80, marks


# How far (screen px) the present slide's content reaches past the slide's box; KaTeX's
# own stretchy SVG paths and its MathML for screen readers are left out (clipped by design).
OVERFLOW = """() => { const box = document.querySelector('.reveal .slides').getBoundingClientRect();
  let worst = 0, what = '';
  for (const e of document.querySelectorAll('section.present *')) {
    if (e.closest('.katex svg, .katex-mathml, aside.notes')) continue;
    const r = e.getBoundingClientRect();
    if (!r.width || !r.height) continue;
    const over = Math.max(r.bottom - box.bottom, r.right - box.right, box.left - r.left);
    if (over > worst) { worst = over; what = e.tagName + ' ' + (e.textContent || '').slice(0, 50); }
  }
  return [worst, what]; }"""


def test_every_slide_fits_720p(deck, deck_720):
    """At 1280x720 no text, figure or demo runs off its slide (nothing clipped)."""
    from lab.web.slides import deck_info

    over = []
    for index in range(deck_info(deck)["count"]):
        deck_720.evaluate(f"Reveal.slide({index})")
        deck_720.wait_for_timeout(30)
        worst, what = deck_720.evaluate(OVERFLOW)
        if worst > 1:
            over.append(f"slide {index}: {what!r} by {worst:.0f} px")
    assert not over, "\n".join(over)


def test_reflection_equation_demo_converges_to_the_labs_render(deck, deck_page, output_dir):
    """The live Monte Carlo slide: both panels accumulate samples in WebGL2 float targets,
    the MIS panel's mean radiance on the sphere agrees with lab.ibl's own render of the
    same model, map and strategy (within 2%), and a moved slider starts both again."""
    import numpy as np

    from lab.constants import LUMA
    from lab.ibl.integrator import Environment, render
    from lab.web.slides import deck_info

    (demo,) = deck_info(deck)["ibl"]
    deck_page.evaluate(f"Reveal.slide({demo['slide']})")
    frame_element = deck_page.wait_for_selector("section.present iframe.ibl-demo")
    frame = frame_element.content_frame()
    frame.wait_for_function(
        "window.iblDemo && (iblDemo.state.error || (iblDemo.state.samples.length === 2"
        " && Math.min(...iblDemo.state.samples) >= 64))",
        timeout=120_000,
    )
    assert frame.evaluate("iblDemo.state.error") == ""
    uniform, mis = frame.evaluate("[iblDemo.read(0), iblDemo.read(1)]")
    assert uniform["covered"] > 0.7 and mis["samples"] >= 64
    deck_page.screenshot(path=output_dir / f"slide_{demo['slide']:02d}_ibl_demo.png")
    size = frame.evaluate("iblDemo.state.size")
    image = render("ggx", {"alpha": 0.1}, Environment.load("sky"), "mis_power", 256, size)
    sphere = image[..., 3] > 0
    expected = float((image[..., :3] @ np.array(LUMA))[sphere].mean())
    assert mis["mean"] == pytest.approx(expected, rel=0.02)
    assert uniform["mean"] == pytest.approx(expected, rel=0.15)  # unbiased, but noisy
    frame.evaluate(
        "(() => { const r = document.getElementById('rough'); r.value = 0.8;"
        " r.dispatchEvent(new Event('input')); })()"
    )
    assert max(frame.evaluate("iblDemo.panels.map(p => p.samples)")) <= 8
    check_demo_fits(deck_page, frame_element, frame, demo["slide"], sliders=3)
    # 28 px text in the frame: at least 24 px on a 1280x720 screen, like the lab's demos.
    small = [t for t in frame.evaluate(FRAME_TEXT) if t["px"] * 720 / 800 < MIN_TEXT_PX]
    assert not small, small
    assert deck_page.errors == []

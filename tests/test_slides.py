"""The lecture deck builds (npm ci, figures, KaTeX), every slide renders without console
errors in headless Chromium, every live demo shows a rendered sphere, and it prints to PDF."""

from __future__ import annotations

import re
import shutil

import pytest

from lab.web.browser import chromium_path

pytestmark = pytest.mark.skipif(
    shutil.which("node") is None or shutil.which("npm") is None or chromium_path() is None,
    reason="needs node, npm and Chromium (apt-get install nodejs npm chromium)",
)

SCREENSHOT_SLIDES = {0: "title", 4: "definition", 15: "sun_moon", 21: "phong_figures",
                     29: "cook_torrance_terms"}


@pytest.fixture(scope="module")
def deck(output_dir):
    from lab.cli import main

    outdir = output_dir / "deck"
    if outdir.exists():
        shutil.rmtree(outdir)
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
    for needed in ("lib/reveal/reveal.js", "lib/katex/katex.min.css", "lab/index.html",
                   "lab/manifest.json", "lab/shaders/brdfs/phong.glsl"):
        assert (deck / needed).is_file(), needed
    assert not (deck / "node_modules").exists()


def test_every_slide_renders(deck, deck_page, output_dir):
    from lab.web.slides import deck_info

    info = deck_info(deck)
    demo_slides = {d["slide"]: d["hash"] for d in info["demos"]}
    assert deck_page.evaluate("Reveal.getTotalSlides()") == info["count"]
    for index in range(info["count"]):
        deck_page.evaluate(f"Reveal.slide({index})")
        deck_page.wait_for_timeout(50)
        if index in demo_slides:
            frames = deck_page.query_selector_all("section.present iframe.demo")
            assert len(frames) == 1, f"slide {index}: no demo iframe"
            frame = frames[0].content_frame()
            frame.wait_for_function("window.brdfLab && brdfLab.state.firstRenderMs !== null",
                                    timeout=30_000)
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
            deck_page.screenshot(path=output_dir / f"slide_{index:02d}_demo.png")
        elif index in SCREENSHOT_SLIDES:
            name = f"slide_{index:02d}_{SCREENSHOT_SLIDES[index]}.png"
            deck_page.screenshot(path=output_dir / name)
        assert deck_page.errors == [], f"slide {index}: {deck_page.errors}"


def test_pdf(deck, deck_page, tmp_path):
    from lab.web.slides import deck_info, pdf

    out = pdf(deck, tmp_path / "handout.pdf", browser=deck_page.lab_browser)
    data = out.read_bytes()
    assert data.startswith(b"%PDF")
    pages = len(re.findall(rb"/Type\s*/Page[^s]", data))
    assert pages == deck_info(deck)["count"]

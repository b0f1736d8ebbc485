"""The lecture deck for every student: axe-core finds no violation on any slide or in any
live demo; equations carry MathML; browser zoom enlarges the text; one-letter shortcuts can
be switched off; Space on a demo's check box ticks it and leaves the slide where it is."""

from __future__ import annotations

import shutil

import pytest

from lab.web.browser import chromium_path
from tests.axe import deck_states, violations

pytestmark = pytest.mark.skipif(
    shutil.which("node") is None or shutil.which("npm") is None or chromium_path() is None,
    reason="needs node, npm and Chromium (apt-get install nodejs npm chromium)",
)


@pytest.fixture(scope="module")
def deck(tmp_path_factory):
    from lab.web.slides import build

    return build(tmp_path_factory.mktemp("deck")).parent


@pytest.fixture(scope="module")
def browser(deck):
    from lab.web.browser import chromium
    from lab.web.site import serving

    with serving(deck) as url, chromium() as browser:
        browser.base_url = url
        yield browser


def test_equations_carry_mathml(deck):
    html = (deck / "index.html").read_text(encoding="utf-8")
    katex = html.count('class="katex"')
    assert katex >= 100 and html.count('class="katex-mathml"><math') == katex


def test_axe_finds_no_violation_on_any_slide_or_demo(browser):
    found = {}
    frames = 0
    for name, page, frame in deck_states(browser, browser.base_url):
        bad = violations(page)
        if frame is not None:
            frames += 1
            bad += violations(page, frame)
        if bad:
            found[name] = [(v["id"], v["nodes"][:2]) for v in bad]
    assert frames >= 8  # every live demo was audited too
    assert found == {}, found


def slide_text_px(page) -> float:
    """The on-screen height, in device pixels, of the title slide's heading."""
    return page.evaluate(
        "() => document.querySelector('.reveal .slides section h1, .reveal .slides section h2')"
        ".getBoundingClientRect().height * devicePixelRatio"
    )


def open_deck(browser, query: str = "", zoom: float = 1.0, base: float = 1.0):
    """The deck in a window of 1280x800 device pixels at browser zoom `zoom` (opened at `base`)."""
    context = browser.new_context(
        viewport={"width": round(1280 / zoom), "height": round(800 / zoom)},
        device_scale_factor=zoom,
    )
    context.add_init_script(f"sessionStorage.setItem('deck-dpr', '{base}')")
    page = context.new_page()
    page.goto(f"{browser.base_url}index.html{query}")
    page.wait_for_function("window.Reveal && Reveal.isReady()")
    page.wait_for_timeout(100)
    return context, page


def test_browser_zoom_enlarges_the_text(browser):
    context, page = open_deck(browser)
    plain = slide_text_px(page)
    context.close()
    context, page = open_deck(browser, zoom=2.0)
    assert page.evaluate("Reveal.getConfig().width") == 640
    zoomed = slide_text_px(page)
    context.close()
    assert zoomed >= 1.8 * plain, (plain, zoomed)


def test_one_letter_shortcuts_can_be_switched_off(browser):
    context, page = open_deck(browser)
    page.keyboard.press("b")  # reveal: black out the screen
    assert page.evaluate("Reveal.isPaused()")
    context.close()
    context, page = open_deck(browser, "?letters=off")
    page.keyboard.press("b")
    assert not page.evaluate("Reveal.isPaused()")
    page.keyboard.press("ArrowRight")  # the arrows still turn the slides
    assert page.evaluate("Reveal.getIndices().h") == 1
    context.close()
    context, page = open_deck(browser, "?keys=n:next")
    page.keyboard.press("n")
    assert page.evaluate("Reveal.getIndices().h") == 1
    context.close()


def test_space_on_a_demo_checkbox_ticks_it_and_stays_on_the_slide(browser, deck):
    from lab.web.slides import deck_info

    demo = next(d for d in deck_info(deck)["demos"] if "cos" in d["hash"].split("show=")[1])
    context, page = open_deck(browser)
    page.evaluate("i => Reveal.slide(i)", demo["slide"])
    page.wait_for_function(
        "() => { const f = document.querySelector('.present iframe.demo');"
        " return f && f.contentWindow && f.contentWindow.brdfLab &&"
        " f.contentWindow.brdfLab.state.firstRenderMs !== null; }",
        timeout=60_000,
    )
    frame = page.query_selector(".present iframe.demo").content_frame()
    frame.wait_for_function("window.brdfLabA11y && window.brdfLabA11y.plots")
    # The demo's sphere says what it shows, as on the lab page (describe_views.js).
    frame.wait_for_function(
        "() => /on a sphere, light at θi 30°.*brightest/.test("
        "document.querySelector('canvas.sphere').dataset.description || '')"
    )
    frame.focus("#cos-weighted")
    page.keyboard.press("Space")
    page.wait_for_timeout(200)
    assert frame.evaluate("document.querySelector('#cos-weighted').checked")
    assert page.evaluate("Reveal.getIndices().h") == demo["slide"]
    page.keyboard.press("PageDown")  # the slide keys still pass up to the deck
    page.wait_for_timeout(200)
    assert page.evaluate("Reveal.getIndices().h") == demo["slide"] + 1
    context.close()


def test_plot_figures_are_described_in_words(deck):
    """The off-specular figure's alt text carries lab.describe's words: Cook-Torrance with
    Schlick's F peaks past the mirror direction at θi = 75°."""
    import html
    import re

    page = (deck / "index.html").read_text(encoding="utf-8")
    alt = html.unescape(
        re.search(r'<img src="figures/off_specular_peak.png" alt="([^"]*)"', page)[1]
    )
    assert "cook_torrance, θi 75°: peak of f_r cos θo at θo " in alt
    peak = int(re.search(r"cook_torrance, θi 75°: peak of f_r cos θo at θo (\d+)°", alt)[1])
    assert peak > 75  # the off-specular peak, in words


# Every page of the deck as it is now: [bottom of its content, the slide's height, its text
# (the speaker notes left out: they stay with the slide's first page), whether it scrolls].
PAGES = """() => Reveal.getSlides().map((s) => {
  const at = Reveal.getIndices(s); Reveal.slide(at.h, at.v);
  const box = document.querySelector(".reveal .slides");
  const scale = box.getBoundingClientRect().width / box.offsetWidth;
  const shown = [...s.children].filter((n) => n.nodeName !== "ASIDE");
  const top = s.getBoundingClientRect().top;
  const bottom = (shown.pop().getBoundingClientRect().bottom - top) / scale;
  const text = [...s.childNodes].filter((n) => n.nodeName !== "ASIDE").map((n) => n.textContent);
  const scrolls = getComputedStyle(s).overflowY === "auto" && s.scrollHeight > s.clientHeight;
  return [bottom, Reveal.getConfig().height, text.join(" "), scrolls]; })"""


def words(pages) -> str:
    """The deck's text in order without white space, the headings that pages repeat left out
    (a list split over pages loses the white space between its items)."""
    import re

    text = " ".join(re.sub(r"^\s*[^\n]*\(continued\)", " ", p[2]) for p in pages)
    return "".join(text.split())


def test_at_200_percent_no_slide_scrolls_inside_and_nothing_is_lost(browser):
    """At 200 % zoom in a 1280x720 window the text is twice as large; what no longer fits on
    a slide goes on pages below it: no page scrolls inside, the words are the same, in the
    same order; back at 100 % the deck is as it was."""
    context, page = open_deck(browser)
    page.set_viewport_size({"width": 1280, "height": 720})
    page.wait_for_timeout(200)
    plain = page.evaluate(PAGES)
    context.close()
    context = browser.new_context(viewport={"width": 640, "height": 360}, device_scale_factor=2)
    context.add_init_script("sessionStorage.setItem('deck-dpr', '1')")
    page = context.new_page()
    page.goto(f"{browser.base_url}index.html")
    page.wait_for_function("window.Reveal && Reveal.isReady()")
    page.wait_for_timeout(300)
    zoomed = page.evaluate(PAGES)
    scrolling = [p[2].strip()[:50] for p in zoomed if p[0] > p[1] + 1 or p[3]]
    assert scrolling == [], scrolling
    assert len(zoomed) > len(plain)  # pages were added
    assert words(zoomed) == words(plain)
    # The arrow that turns the slides goes through a slide's pages first.
    page.evaluate("Reveal.slide(1, 0)")
    page.keyboard.press("ArrowRight")
    assert page.evaluate("[Reveal.getIndices().h, Reveal.getIndices().v]") == [1, 1]
    # Back to 100 %: the pages fold back into their slides.
    cdp = context.new_cdp_session(page)
    cdp.send(
        "Emulation.setDeviceMetricsOverride",
        {"width": 1280, "height": 720, "deviceScaleFactor": 1, "mobile": False},
    )
    page.wait_for_function("Reveal.getConfig().width === 1280")
    page.wait_for_timeout(200)
    again = page.evaluate(PAGES)
    assert [p[2] for p in again] == [p[2] for p in plain]
    context.close()

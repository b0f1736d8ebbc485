"""The web lab's first screen (issue 26): on a 390x844 phone a sphere shows before any
toolbar; at 1400x900 with every view on, each model's controls sit within one screen of
its sphere (beside it), not below all its plots."""

from __future__ import annotations

import pytest
from webpage import LabTab

from lab.web.browser import chromium_path

pytestmark = pytest.mark.skipif(
    chromium_path() is None, reason="Chromium is not installed (apt-get install chromium)"
)

EVERY_VIEW = "lobe3d,sh,terms,slice,albedo,object,ibl"
BOXES = """() => [...document.querySelectorAll('#panels > .panel')].map((p) => {
  const box = (e) => { const r = e.getBoundingClientRect();
    return { top: r.top + scrollY, bottom: r.bottom + scrollY, left: r.left, height: r.height }; };
  return { sphere: box(p.querySelector('canvas.sphere')),
           controls: box(p.querySelector('.controls')),
           slider: box(p.querySelector('.controls input')) };
})"""


@pytest.fixture(scope="module")
def browser(tmp_path_factory):
    from lab.web.browser import chromium
    from lab.web.site import export, serving

    site = export(tmp_path_factory.mktemp("site")).parent
    with serving(site) as url, chromium() as browser:
        browser.base_url = url
        yield browser


def test_phone_shows_a_picture_first(browser, output_dir):
    tab = LabTab(browser, "model=phong&model=ward", 390, 844, has_touch=True)
    try:
        first = tab.js(BOXES)[0]["sphere"]
        assert first["height"] > 300  # as wide as the phone
        assert first["top"] >= 0 and first["top"] + first["height"] / 2 <= 844, first
        # The page's controls follow the pictures: the light's sliders below the first panel.
        lights = tab.js("document.getElementById('lights').getBoundingClientRect().top + scrollY")
        assert lights > first["bottom"]
        tab.page.screenshot(path=output_dir / "web_phone_first_screen.png")
        assert tab.errors == []
    finally:
        tab.close()


@pytest.mark.parametrize("width,height", [(1400, 900), (1024, 768)])
def test_wide_screen_keeps_controls_beside_the_sphere(browser, output_dir, width, height):
    tab = LabTab(browser, f"model=phong&model=ward&views={EVERY_VIEW}", width, height)
    try:
        for index, panel in enumerate(tab.js(BOXES)):
            sphere, slider = panel["sphere"], panel["slider"]
            # The first slider and the sphere's top fit one screen together.
            span = max(slider["bottom"], sphere["top"]) - min(slider["top"], sphere["top"])
            assert span <= height, f"panel {index}: {span:.0f} px from sphere to its slider"
            assert panel["controls"]["left"] > sphere["left"] + sphere["height"] / 2  # beside
        tab.page.screenshot(path=output_dir / f"web_{width}x{height}_every_view.png")
        assert tab.errors == []
    finally:
        tab.close()


def test_narrow_desktop_keeps_its_layout(browser):
    """Without extra views a panel keeps the sphere, the plot and the controls below."""
    tab = LabTab(browser, "model=phong", 1400, 900)
    try:
        (panel,) = tab.js(BOXES)
        assert panel["controls"]["top"] >= panel["sphere"]["bottom"] - 1
    finally:
        tab.close()


def test_phone_shows_one_view_at_a_time(browser, output_dir):
    """With extra views on a phone, a menu above each panel's pictures picks the one view
    shown (the sphere and polar plot first); the same page on a desktop shows them all."""
    address = "model=phong&views=lobe3d,albedo"
    shown = """() => [...document.querySelectorAll('#panels > .panel .views')]
      .flatMap((box) => box.classList.contains('switched-off') ? [] : [box])
      .flatMap((box) => box.matches('.views + .views')
        ? [...box.children].filter((v) => v.getClientRects().length).map((v) => v.dataset.view)
        : ['core'])"""
    tab = LabTab(browser, address, 390, 844, has_touch=True)
    try:
        menu = tab.page.locator("#panels > .panel label.view-switch select")
        assert menu.count() == 1
        options = menu.evaluate("s => [...s.options].map((o) => o.value)")
        assert options[0] == "sphere and polar plot" and len(options) == 3
        assert tab.js(shown) == ["core"]
        menu.select_option(options[2])  # the albedo: only it shows, the sphere is hidden
        assert tab.js(shown) == [options[2]]
        assert tab.js("document.querySelector('canvas.sphere').getClientRects().length") == 0
        tab.page.screenshot(path=output_dir / "web_phone_view_switch.png")
        menu.select_option(options[0])
        assert tab.js(shown) == ["core"]
        assert tab.errors == []
    finally:
        tab.close()
    wide = LabTab(browser, address, 1400, 900)
    try:
        assert wide.page.locator("label.view-switch:visible").count() == 0
        assert len(wide.js(shown)) == 3  # the core pictures and both views
    finally:
        wide.close()

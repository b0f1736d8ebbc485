"""The web lab on any screen: no horizontal scrolling from phone to desktop, touch moves the
light, help on tap, live address changes, reset, PNG export, presets, model titles."""

from __future__ import annotations

import io
from pathlib import Path

import numpy as np
import pytest
from webpage import LabTab

from lab.models import load_model
from lab.web.browser import chromium_path

pytestmark = pytest.mark.skipif(
    chromium_path() is None, reason="Chromium is not installed (apt-get install chromium)"
)

SIZES = ((1400, 900), (768, 1024), (390, 844))
SIZE = 96


@pytest.fixture(scope="module")
def browser(tmp_path_factory):
    from lab.web.browser import chromium
    from lab.web.site import export, serving

    site = export(tmp_path_factory.mktemp("site")).parent
    with serving(site) as url, chromium() as browser:
        browser.base_url = url
        yield browser


class Page(LabTab):
    def __init__(self, browser, hash_: str, width=1300, height=900, touch=False):
        super().__init__(browser, hash_, width, height, has_touch=touch, accept_downloads=True)

    def overflow(self) -> dict:
        """How far the page and each control reach past the right edge of the screen."""
        return self.js(
            """() => {
              const w = document.documentElement.clientWidth;
              const out = {page: document.documentElement.scrollWidth - w};
              for (const e of document.querySelectorAll('input, select, button, canvas, label')) {
                const r = e.getBoundingClientRect();
                if (r.width && r.right > w + 0.5) out[e.outerHTML.slice(0, 60)] = r.right - w;
              }
              return out;
            }"""
        )


@pytest.mark.parametrize("width,height", SIZES)
def test_no_horizontal_overflow(browser, output_dir, width, height):
    """Two models, two lights: nothing sticks out past the screen's right edge; on a phone
    the controls stack (every slider starts near the left edge, one per line)."""
    page = Page(
        browser,
        "model=phong&model=ward&light=30,0&light=60,120,0.5,0.5,1",
        width,
        height,
        touch=width < 800,
    )
    try:
        over = page.overflow()
        assert over == {"page": 0}, over
        spheres = page.js(
            "[...document.querySelectorAll('canvas.sphere')]"
            ".map(c => c.getBoundingClientRect().width)"
        )
        assert all(w >= min(384, width - 60) for w in spheres), spheres  # as wide as fits
        if width < 500:
            boxes = page.js("brdfLab.sliderBoxes()")
            tops = sorted(round(b["top"]) for b in boxes)
            assert len(set(tops)) == len(tops), "two sliders share a line on a phone"
        page.page.screenshot(path=output_dir / f"web_{width}x{height}.png", full_page=True)
        assert page.errors == []
    finally:
        page.close()


def test_touch_drag_moves_the_light(browser):
    page = Page(browser, f"model=lambert&size={SIZE}&light=0,0", 390, 844, touch=True)
    try:
        box = page.page.locator("canvas.sphere").first.bounding_box()
        # Half way up from the centre: N = (0, 0.5, 0.866) -> theta 30, phi 90.
        page.page.touchscreen.tap(box["x"] + box["width"] * 0.5, box["y"] + box["height"] * 0.25)
        light = page.js("brdfLab.state.light")
        assert light["theta"] == pytest.approx(30, abs=1.5)
        assert light["phi"] == pytest.approx(90, abs=1.5)
        page.js("brdfLab.renderNow()")
        image = page.sphere()
        y, x = np.unravel_index(np.argmax(image[..., 0]), image.shape[:2])
        assert y < SIZE / 2 and abs(x - SIZE / 2) <= 2  # Lambert's brightest point faces it
    finally:
        page.close()


def test_help_opens_on_tap(browser):
    page = Page(browser, "model=phong", 390, 844, touch=True)
    try:
        assert page.page.locator("#tip").is_hidden()
        page.page.locator("[data-param=ke] label").tap()
        tip = page.page.locator("#tip-text").inner_text()
        doc = next(p.doc for p in load_model("phong").params.values() if p.name == "ke")
        assert tip.startswith(f"ke: {doc}")
        assert page.page.locator("#tip").is_visible()
        page.page.locator("#tip button").tap()
        assert page.page.locator("#tip").is_hidden()
        page.page.locator(".light-row label .name").first.tap()
        assert "θi" in page.page.locator("#tip-text").inner_text()
    finally:
        page.close()


def test_hash_change_applies_live(browser, renderer):
    """Editing the address of an open page shows the new state, as the desktop renders it."""
    page = Page(browser, f"model=phong&size={SIZE}&light=45,0")
    try:
        page.js("location.hash = 'model=ward&alpha_x=0.3&model=lambert&light=20,60&exposure=1'")
        page.page.wait_for_function("brdfLab.state.panels.length === 2")
        assert page.js("brdfLab.state.panels.map(p => p.name)") == ["ward", "lambert"]
        assert page.js("brdfLab.values(0).alpha_x") == 0.3
        assert page.js("brdfLab.state.light") == {"theta": 20, "phi": 60}
        assert page.js("document.querySelector('#exposure').value") == "1"
        web = page.sphere(0)
        desktop = renderer.sphere(load_model("ward"), {"alpha_x": 0.3}, light=(20, 60), size=SIZE)
        on = desktop[..., 3] > 0
        np.testing.assert_allclose(web[on], desktop[on], rtol=1e-3, atol=1e-5)
        # A bad value in the new address is reported, the rest still applies.
        page.js("location.hash = 'model=phong&ke=-3'")
        page.page.wait_for_function("brdfLab.state.panels.length === 1")
        assert any("ke must be a number" in n for n in page.js("brdfLab.notes()"))
        assert page.page.locator("#notes").is_visible()
        assert page.errors == []
    finally:
        page.close()


def test_reset_restores_the_defaults(browser):
    page = Page(browser, f"model=phong&size={SIZE}")
    try:
        before = page.sphere()
        page.js("brdfLab.moveSlider(0, 'ke', 900)")
        page.js("brdfLab.addLight()")
        page.page.locator("#exposure").fill("2")
        assert not np.array_equal(page.sphere(), before)
        page.page.click("#reset")
        assert page.js("brdfLab.state.lights.length") == 1
        assert page.js("brdfLab.values(0).ke") == 50
        assert page.js("brdfLab.state.settings.exposure") == 0
        np.testing.assert_array_equal(page.sphere(), before)
        assert "ke=" not in page.js("location.hash")
    finally:
        page.close()


def test_png_export_of_each_view(browser):
    """Each view's PNG button downloads what the canvas shows."""
    from PIL import Image

    page = Page(browser, "model=phong&size=128&light=0,0")
    try:
        for view, size in (("sphere", (128, 128)), ("polar plot", None)):
            with page.page.expect_download() as info:
                page.page.locator(f".view[data-view='{view}'] button.png").first.click()
            download = info.value
            assert download.suggested_filename == f"phong_{view.split()[0]}.png"
            image = Image.open(io.BytesIO(Path(download.path()).read_bytes()))
            canvas = page.js(
                "v => { const c = document.querySelector(`.view[data-view='${v}'] canvas`);"
                " return [c.width, c.height]; }",
                view,
            )
            assert list(image.size) == canvas
            if size:
                rgba = np.asarray(image.convert("RGBA"), dtype=float)
                # Lit from the eye: the centre is the brightest part, the corner is empty.
                assert rgba[64, 64, :3].mean() > 100 and rgba[0, 0, 3] == 0
    finally:
        page.close()


def test_picker_shows_model_titles(browser):
    page = Page(browser, "model=lommel_seeliger")
    try:
        options = page.js(
            "[...document.querySelectorAll('.model-picker option')].map(o => [o.value, o.text])"
        )
        names = dict(options)
        assert names["lommel_seeliger"] == "Lommel-Seeliger"
        assert names["cook_torrance"] == load_model("cook_torrance").title.split(":")[0]
    finally:
        page.close()


def test_mirror_sky_sun_follows_the_light(browser, renderer):
    """The mirror reflects a sun where light 1 is: the glint sits where N halves L and V."""
    page = Page(browser, f"model=mirror&size={SIZE}&light=40,20")
    try:
        glints = []
        for theta, phi in ((40, 20), (60, -120)):
            page.js(f"brdfLab.setLight({theta}, {phi})")
            web = page.sphere()
            desktop = renderer.sphere(load_model("mirror"), {}, light=(theta, phi), size=SIZE)
            on = desktop[..., 3] > 0
            np.testing.assert_allclose(web[on], desktop[on], rtol=1e-3, atol=1e-4)
            y, x = np.unravel_index(np.argmax(web[..., 0]), web.shape[:2])
            t, p = np.radians(theta), np.radians(phi)
            h = np.array([np.sin(t) * np.cos(p), np.sin(t) * np.sin(p), np.cos(t) + 1])
            h /= np.linalg.norm(h)
            expect = ((h[0] + 1) / 2 * SIZE, (1 - h[1]) / 2 * SIZE)
            assert abs(x + 0.5 - expect[0]) <= 2 and abs(y + 0.5 - expect[1]) <= 2
            glints.append((x, y))
        assert glints[0] != glints[1]
    finally:
        page.close()


def test_desktop_presets_can_be_picked(browser):
    from lab.presets import read_preset, shipped_presets
    from lab.web.site import manifest

    shipped = manifest()["presets"]
    assert [p["file"] for p in shipped] == [p.name for p in shipped_presets()]
    assert shipped[0]["model"] == read_preset(shipped_presets()[0])["model"]
    page = Page(browser, "model=lambert")
    try:
        titles = page.js("[...document.querySelectorAll('#preset option')].map(o => o.text)")
        assert titles[1:] == [p["title"] for p in shipped]
        page.page.select_option("#preset", index=1)  # Phong exponents: ke = 4, 50, 120
        page.page.wait_for_function("brdfLab.state.panels.length === 3")
        first = read_preset(shipped_presets()[0])
        for i, entry in enumerate(first["model"]):
            values = page.js("i => brdfLab.values(i)", i)
            for key, value in entry["values"].items():
                assert values[key] == pytest.approx(value)
        assert page.js("brdfLab.state.light")["theta"] == first["settings"]["theta_i"]
        assert first["title"] in page.page.locator("#preset-notes").inner_text()
        # A preset model the page cannot open is named, the rest still shows.
        out = page.js(
            "p => brdfLab.presetHash(p)",
            {"model": [{"model": "measured", "table": "gold.binary"}, {"model": "phong"}]},
        )
        assert out["hash"].startswith("model=phong&")
        assert out["skipped"] == ["measured: measured opens in the desktop lab only"]
        assert page.errors == []
    finally:
        page.close()


PLOTS = ("polar", "sh", "terms", "slice", "albedo")  # canvases of axes and labels


@pytest.mark.parametrize("width,height", SIZES[::2])
def test_plot_labels_stay_inside_their_canvas(browser, width, height):
    """No plot draws into its outermost columns: a tick label centred on an axis end (the
    90° of the slice and of the albedo) would be cut off there."""
    views = ",".join(v for v in PLOTS if v != "polar")
    page = Page(browser, f"model=cook_torrance&views={views}", width, height)
    try:
        inked = page.js(
            """plots => Object.fromEntries(plots.map(name => {
              const c = document.querySelector('canvas.' + name);
              const data = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
              const alpha = (x) => { let n = 0;
                for (let y = 0; y < c.height; y++) n += data[4 * (y * c.width + x) + 3] > 0;
                return n; };
              return [name, [alpha(0), alpha(c.width - 1)]];
            }))""",
            list(PLOTS),
        )
        assert inked == {name: [0, 0] for name in PLOTS}, inked
        assert page.errors == []
    finally:
        page.close()


@pytest.mark.parametrize(
    "width,height,embed", [(w, h, False) for w, h in SIZES] + [(1280, 720, True)]
)
def test_ring_values_keep_off_the_lobe(browser, width, height, embed):
    """The polar plot's ring values sit below its baseline or beside its rim, never over the
    lobe (a Lambert lobe at normal incidence fills the half disc); the rim's is always
    shown, and no two run into each other. Embedded (a slide's large text) too."""
    address = "model=lambert&light=0,0" + ("&embed=1" if embed else "")
    page = Page(browser, address, width, height)
    try:
        g = page.js("brdfLab.panel(0).polarGeometry")
        (cx, cy), radius = g["centre"], g["radius"]
        labels = g["ringLabels"]
        assert labels, g
        for text, left, top, _right, _bottom in labels:
            assert top >= cy or left >= cx + radius, (text, g)
        rim = float(labels[0][0])  # drawn from the rim inward
        assert rim == pytest.approx(g["scale"], rel=0.05)
        spans = sorted((left, right) for _, left, _, right, _ in labels)
        assert all(a[1] <= b[0] for a, b in zip(spans, spans[1:], strict=False)), spans
        assert page.errors == []
    finally:
        page.close()


@pytest.mark.parametrize("theta", [10, 30, 70])
def test_spike_value_keeps_clear_of_the_spike_and_the_light(browser, theta):
    """The mirror's 'δ spike, ρ = ...' sits on the spike's outer side: left of the normal,
    and left of the spike at every height of the text (it leans outward going up), so it
    crosses neither the spike nor the light's ray."""
    page = Page(browser, f"model=mirror&light={theta},0", 1024, 768)
    try:
        g = page.js("brdfLab.panel(0).polarGeometry")
        (cx, cy), (left, top, right, bottom) = g["centre"], g["spikeLabel"]
        slope = np.tan(np.radians(theta))
        assert left >= 0 and right <= cx
        for y in np.linspace(top, bottom, 5):
            if y < cy and cy - y <= g["spikeLength"] * np.cos(np.radians(theta)):
                assert right <= cx - (cy - y) * slope + 1, (theta, g)
        assert page.errors == []
    finally:
        page.close()

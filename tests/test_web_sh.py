"""The page's spherical-harmonics view: the lobe from the model's GLSL on the quadrature
grid, its coefficients and the error of every order agree with the desktop's
(lab/app/views/sh.py's sh_data on the EGL render)."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest
from webpage import open_page

from lab.models import load_model
from lab.web.browser import chromium_path

pytestmark = pytest.mark.skipif(
    chromium_path() is None, reason="Chromium is not installed (apt-get install chromium)"
)

LIGHT = (40.0, 20.0)


@pytest.fixture(scope="module")
def page(tmp_path_factory):
    with open_page(tmp_path_factory, f"model=phong&light={LIGHT[0]:g},{LIGHT[1]:g}") as tab:
        yield tab


@pytest.mark.parametrize(
    ("name", "values"),
    [("lambert", {}), ("phong", {"ke": 40.0}), ("cook_torrance", {"m": 0.3}), ("ward", {})],
)
def test_sh_matches_desktop(page, renderer, name, values, output_dir):
    from lab.app.views.sh import sh_data

    page.evaluate("([n, v]) => brdfLab.setModel(0, n, v)", [name, values])
    page.evaluate("brdfLab.state.settings.sh_order = 6")
    page.evaluate("brdfLab.setViews(['sh'])")
    assert page.evaluate("brdfLab.errors(0)") == ""
    web = page.evaluate("brdfLab.readView(0, 'sh')")
    state = SimpleNamespace(model=load_model(name), values=values)
    desktop = sh_data(renderer, state, *LIGHT)
    coefficients = np.array(web["coefficients"])
    top = np.abs(desktop.coefficients).max()
    np.testing.assert_allclose(coefficients, desktop.coefficients, atol=1e-3 * top)
    np.testing.assert_allclose(web["errors"], desktop.errors, rtol=1e-3, atol=1e-5)
    np.testing.assert_allclose(web["plane"], desktop.plane, rtol=1e-3, atol=1e-6 * top)
    np.testing.assert_allclose(web["series"], desktop.reconstruction(6), atol=1e-3 * top)
    if name == "lambert":  # a constant times cos: exactly Y_1^0, nothing beyond order 1
        assert web["errors"][0] > 0.1 and max(web["errors"][1:]) < 1e-4
    else:  # a sharper lobe needs more terms: the error falls with the order
        assert web["errors"][16] < web["errors"][2] < web["errors"][0]
    note = page.locator(".view[data-view='spherical harmonics'] .view-note").inner_text()
    assert note.startswith("L = 6: 49 coefficients")
    view = page.locator(".view[data-view='spherical harmonics']")
    view.screenshot(path=output_dir / f"web_sh_{name}.png")
    assert page.errors == []


def test_mirror_has_no_series(page):
    page.evaluate("brdfLab.setModel(0, 'mirror')")
    page.evaluate("brdfLab.setViews(['sh'])")
    assert page.evaluate("brdfLab.readView(0, 'sh')")["coefficients"] == []


def test_while_a_slider_moves_the_series_waits_as_on_the_desktop(page):
    """With the hand on a slider (lab.fast) the view follows with the lobe alone and says
    the series comes when the slider stops (the probe and projection were most of its
    frame); once it stops, the series is the new lobe's, not the one before."""
    page.evaluate("([n, v]) => brdfLab.setModel(0, n, v)", ["phong", {"ke": 40.0}])
    page.evaluate("brdfLab.setViews(['sh'])")
    before = np.array(page.evaluate("brdfLab.readView(0, 'sh')")["coefficients"])
    note = page.locator(".view[data-view='spherical harmonics'] .view-note")
    page.evaluate(
        "(() => { const p = brdfLab.panel(0); p.values.ke = 200; brdfLab.state.fast = true; "
        "p.render(); })()"
    )
    assert note.inner_text() == "series and error follow when the slider stops"
    after = page.evaluate("brdfLab.readView(0, 'sh')")  # the hand stops: full quality
    assert note.inner_text().startswith("L = ")
    assert not np.allclose(np.array(after["coefficients"]), before, atol=1e-6)
    assert after["errors"][8] > 0 and page.errors == []

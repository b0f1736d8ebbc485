"""The page's microfacet terms view agrees with the desktop's (lab/views/terms.py on EGL)."""

from __future__ import annotations

import numpy as np
import pytest
from webpage import open_page

from lab.models import load_model
from lab.views.terms import microfacet_terms
from lab.web.browser import chromium_path

pytestmark = pytest.mark.skipif(
    chromium_path() is None, reason="Chromium is not installed (apt-get install chromium)"
)

LIGHT = (35.0, 20.0)


@pytest.fixture(scope="module")
def page(tmp_path_factory):
    with open_page(
        tmp_path_factory, f"model=ggx&light={LIGHT[0]:g},{LIGHT[1]:g}&views=terms"
    ) as tab:
        yield tab


@pytest.mark.parametrize(
    ("name", "values"),
    [
        ("ggx", {"alpha": 0.2, "f0": [0.95, 0.64, 0.54]}),
        ("cook_torrance", {"m": 0.3, "distribution": "blinn", "fresnel": "dielectric"}),
    ],
)
def test_terms_match_desktop(page, renderer, name, values, output_dir):
    page.evaluate("([n, v]) => brdfLab.setModel(0, n, v)", [name, values])
    assert page.evaluate("brdfLab.errors(0)") == ""
    web = page.evaluate("brdfLab.readView(0, 'terms')")
    desktop = microfacet_terms(renderer, load_model(name), values, *LIGHT)
    D = np.array(web["D"], dtype=float)
    finite = np.isfinite(desktop.D)
    assert (np.isfinite(D) == finite).all()
    np.testing.assert_allclose(
        D[finite], desktop.D[finite], rtol=1e-3, atol=1e-6 * desktop.D[finite].max()
    )
    np.testing.assert_allclose(web["G"], desktop.G, rtol=1e-3, atol=1e-6)
    np.testing.assert_allclose(web["F"], desktop.F, rtol=1e-3, atol=1e-6)
    page.locator(".view[data-view='microfacet terms']").screenshot(
        path=output_dir / f"web_terms_{name}.png"
    )
    assert page.errors == []


def test_other_models_say_why(page):
    page.evaluate("brdfLab.setModel(0, 'phong')")
    assert page.evaluate("brdfLab.readView(0, 'terms')")["D"] == []
    note = page.locator(".view[data-view='microfacet terms'] .view-note").inner_text()
    assert "does not define MICROFACET_TERMS" in note


def test_a_measured_table_is_told_to_fit_a_model(page, renderer, tmp_path):
    from lab.measured.merl import write_merl
    from lab.measured.tabulate import tabulate

    table = write_merl(tabulate("ggx", dims=(30, 30, 60), renderer=renderer), tmp_path / "t.binary")
    before = page.evaluate("brdfLab.state.panels.length")
    page.set_input_files("#open-file", str(table))
    page.wait_for_function(f"brdfLab.state.panels.length > {before}", timeout=60_000)
    page.evaluate("brdfLab.renderNow()")
    assert page.evaluate(f"brdfLab.readView({before}, 'terms')")["D"] == []
    notes = page.locator(".view[data-view='microfacet terms'] .view-note").all_inner_texts()
    note = notes[before]
    assert "measured table" in note and "fit a microfacet model" in note, note
    assert "MICROFACET_TERMS" not in note
    assert page.errors == []

"""The microfacet terms view: D, G and F from the model's own GLSL (MICROFACET_TERMS) are
the lecture's formulas (lab/reference.py); models without them are named."""

from __future__ import annotations

import math
import os

import numpy as np
import pytest
from PIL import Image

from lab import reference
from lab.cli import main
from lab.models import ModelError, load_model
from lab.views.terms import has_terms, microfacet_terms, term_pairs

LIGHT = (35.0, 20.0)


def test_library_microfacet_models_define_their_terms():
    assert has_terms(load_model("cook_torrance")) and has_terms(load_model("ggx"))
    assert not has_terms(load_model("phong"))


@pytest.mark.parametrize(
    "values",
    [
        {"m": 0.3},
        {"m": 0.1, "distribution": "blinn", "fresnel": "dielectric", "ior": 1.8},
        {"m": 0.2, "distribution": "gaussian", "fresnel": "none", "f0": [0.9, 0.6, 0.2]},
    ],
)
def test_cook_torrance_terms_are_the_formulas(renderer, values):
    t = microfacet_terms(renderer, load_model("cook_torrance"), values, *LIGHT)
    p = reference.resolve("cook_torrance", values)
    alpha = np.radians(t.theta[:-1])  # the horizon itself is left out (cos = 0)
    beta = math.atan(p["m"])
    expected_d = {
        "beckmann": lambda: reference.d_beckmann(alpha, p["m"]),
        "blinn": lambda: reference.d_blinn(alpha, beta),
        "gaussian": lambda: reference.d_gaussian(alpha, beta),
    }[p["distribution"]]()
    np.testing.assert_allclose(t.D[:-1], expected_d, rtol=2e-3, atol=1e-6 * expected_d.max())
    # G in the plane of incidence: the V-groove formula for the light's pairs.
    L, V = term_pairs(*LIGHT)
    k = len(t.theta)
    L, V = L[k : k + 181], V[k : k + 181]
    H = (L + V) / np.linalg.norm(L + V, axis=1, keepdims=True)
    above = V[:, 2] > 1e-6
    expected_g = reference.g_vgroove(H[:, 2], L[:, 2], V[:, 2], np.sum(V * H, axis=1))
    np.testing.assert_allclose(t.G[above], expected_g[above], rtol=1e-4, atol=1e-5)
    cos_d = np.cos(np.radians(t.theta))
    expected_f = {
        "schlick": lambda: reference.fresnel_schlick(np.asarray(p["f0"], float), cos_d),
        "dielectric": lambda: np.repeat(
            reference.fresnel_dielectric(cos_d, p["ior"])[:, None], 3, 1
        ),
        "none": lambda: np.ones((len(cos_d), 3)),
    }[p["fresnel"]]()
    np.testing.assert_allclose(t.F, expected_f, rtol=1e-4, atol=1e-5)


def test_ggx_terms_are_the_formulas(renderer):
    values = {"alpha": 0.25, "f0": [0.95, 0.64, 0.54]}
    t = microfacet_terms(renderer, load_model("ggx"), values, *LIGHT)
    expected_d = reference.d_ggx(np.radians(t.theta), 0.25)
    np.testing.assert_allclose(t.D, expected_d, rtol=2e-3, atol=1e-6 * expected_d.max())
    theta_i = np.radians(LIGHT[0])
    theta_o = np.radians(np.abs(t.theta_o[1:-1]))  # not the horizon
    g2 = 1.0 / (1.0 + reference.lambda_ggx(theta_i, 0.25) + reference.lambda_ggx(theta_o, 0.25))
    np.testing.assert_allclose(t.G[1:-1], g2, rtol=1e-3)
    cos_d = np.cos(np.radians(t.theta))
    np.testing.assert_allclose(
        t.F, reference.fresnel_schlick(np.array(values["f0"]), cos_d), rtol=1e-4, atol=1e-5
    )


def test_a_model_without_terms_is_named(renderer, tmp_path, capsys):
    with pytest.raises(ModelError, match="phong is not written as a microfacet model"):
        microfacet_terms(renderer, load_model("phong"), {}, *LIGHT)
    assert main(["render", "phong", "--view", "terms", "-o", str(tmp_path / "p.png")]) != 0
    assert "MICROFACET_TERMS" in capsys.readouterr().err
    out = tmp_path / "ct.png"
    assert main(["render", "cook_torrance", "--view", "terms", "-o", str(out)]) == 0
    with Image.open(out) as image:
        assert image.size[0] >= 600 and np.asarray(image).std() > 10


@pytest.mark.skipif(not os.environ.get("DISPLAY"), reason="needs a display (xvfb-run)")
def test_app_view_overlays_the_microfacet_models(qtbot, window, output_dir):
    from qtapp import floating_view, settle

    window.lab.add(load_model("cook_torrance"))
    window.lab.add(load_model("ggx"))
    window.lab.add(load_model("phong"))
    view = floating_view(qtbot, window, "terms")
    settle(qtbot, window)
    assert [label for label, _ in view.shown] == ["cook_torrance", "ggx"]
    s = window.lab.settings
    for (_, terms), name in zip(view.shown, ("cook_torrance", "ggx"), strict=True):
        truth = microfacet_terms(window.renderer, load_model(name), {}, s["theta_i"], s["phi_i"])
        np.testing.assert_allclose(terms.G, truth.G)
    assert "phong" in view.info.text() and "MICROFACET_TERMS" in view.info.text()
    view.export_png(output_dir / "app_view_terms_open.png")

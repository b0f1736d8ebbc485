"""The page's IBL view (progressive Monte Carlo of the reflection equation in WebGL): the
furnace render equals the albedo view, and the converged image agrees with the desktop's
EGL render of the same template within the Monte Carlo noise."""

from __future__ import annotations

import base64

import numpy as np
import pytest
from webpage import open_page

from lab.constants import LUMA
from lab.ibl.environments import DEFAULT_SIZE, procedural
from lab.ibl.furnace import against_albedo
from lab.ibl.integrator import Environment, IBLRenderer, render, sphere_normals
from lab.web.browser import chromium_path

pytestmark = pytest.mark.skipif(
    chromium_path() is None, reason="Chromium is not installed (apt-get install chromium)"
)

SIZE = 64  # the page's sphere size: the IBL view renders at this size too


@pytest.fixture(scope="module")
def page(tmp_path_factory):
    with open_page(tmp_path_factory, f"model=ggx&size={SIZE}&views=ibl") as tab:
        yield tab


@pytest.fixture(scope="module")
def ibl(ctx):
    return IBLRenderer(ctx)


def web_ibl(
    page,
    model: str,
    values: dict,
    environment: str,
    strategy: str,
    samples: int,
    sequence: str = "random",
):
    """The page's IBL mean after `samples` per pixel: (SIZE, SIZE, 4), row 0 at the top."""
    page.evaluate(
        """async ([model, values, environment, strategy, sequence]) => {
            const specs = brdfLab.state.specs;
            brdfLab.setSettings({ ibl_env: specs.ibl_env.choices.indexOf(environment),
              ibl_strategy: specs.ibl_strategy.choices.indexOf(strategy), ibl_rotation: 0,
              ibl_sequence: sequence === "sobol" ? 1 : 0 });
            brdfLab.setModel(0, model, values);
            brdfLab.panel(0).extra.ibl.restart();
        }""",
        [model, values, environment, strategy, sequence],
    )
    got = page.evaluate(f"brdfLab.panel(0).extra.ibl.converge({samples})")
    assert got == samples
    out = page.evaluate("brdfLab.readView(0, 'ibl')")
    assert out["samples"] == samples
    data = np.frombuffer(base64.b64decode(out["data"]), dtype=np.float32)
    return data.reshape(out["height"], out["width"], 4)


def test_the_page_starts_with_auto_on_sobol_points(page):
    """A fresh page's IBL view runs the desktop's defaults: 'auto' (MIS under the sky, BRDF
    sampling in the furnace, as lab.ibl.integrator.chosen_strategy resolves it) on each
    pixel's Sobol' sequence, and says so."""
    view = "brdfLab.panel(0).extra.ibl"
    assert page.evaluate(f"{view}.strategyBox.value") == "auto"
    assert page.evaluate(f"{view}.sequenceBox.value") == "Sobol'"
    page.wait_for_function(f"{view}.samples > 0")
    status = page.evaluate(f"{view}.status.textContent")
    assert "auto" in status and ", here MIS, power heuristic" in status and "Sobol'" in status
    page.evaluate(
        """() => { const box = brdfLab.panel(0).extra.ibl.envBox; box.value = 'furnace';
          box.dispatchEvent(new Event('change')); }"""
    )
    page.wait_for_function(f"{view}.status.textContent.includes(', here BRDF importance')")
    assert page.errors == []


# Physically based models with an analytic sampler (their furnace render converges fast).
FURNACE = [
    ("ggx", {"alpha": 0.3}),
    ("cook_torrance", {"m": 0.3}),
    ("lambert", {}),
    ("oren_nayar", {}),
]


@pytest.mark.parametrize("name,values", FURNACE)
def test_furnace_render_equals_the_albedo(page, ibl, name, values):
    """Under the white furnace the reflected radiance at each view angle is the directional
    albedo (the desktop's albedo view, EGL), within 1%."""
    image = web_ibl(page, name, values, "furnace", "brdf", 1024)
    result = against_albedo(image, name, values, ibl)
    assert result.max_relative_error < 0.01, (name, result.rendered, result.albedo)
    assert not result.energy_gain
    assert page.errors == []


def test_unnormalised_phong_gains_energy_in_the_furnace(page, output_dir):
    """Plain Phong with ks = 1, ke = 1 reflects more than arrives: the view says so."""
    values = {"kd": [0.5] * 3, "ks": [1.0] * 3, "ke": 1.0}
    image = web_ibl(page, "phong", values, "furnace", "brdf", 128)
    status = page.evaluate("brdfLab.panel(0).extra.ibl.status.textContent")
    assert "ENERGY GAIN (red)" in status, status
    assert image[..., :3].max() > 1.0
    # Marked in colour too, as on the desktop: the gaining rings are red on the canvas (the
    # white furnace would otherwise hide a white sphere in a white background).
    red = page.evaluate(
        """() => { const c = brdfLab.panel(0).extra.ibl.canvas;
          const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data; let n = 0;
          for (let k = 0; k < d.length; k += 4) if (d[k] > 240 && d[k + 1] < 170) n++;
          return n / (c.width * c.height); }"""
    )
    assert red > 0.1, red
    page.locator("#panels > .panel").first.screenshot(path=output_dir / "web_ibl_furnace_gain.png")


@pytest.mark.parametrize(
    "strategy,sequence,environment",
    [
        ("cosine", "random", "sky"),
        ("environment", "random", "sky"),
        ("brdf", "random", "sky"),
        ("mis_power", "random", "sky"),
        ("auto", "sobol", "sky"),
        ("auto", "sobol", "studio"),
        ("brdf", "sobol", "sky"),
    ],
)
def test_converged_image_agrees_with_the_desktop(page, ibl, strategy, sequence, environment):
    """GGX: the page's render and the EGL render (same template, strategy, sequence, seeds
    and sample count) differ no more than two EGL renders with different seeds do (the
    rasterizers' sin/cos differ, so their sample streams part ways: the Monte Carlo noise)."""
    values = {"alpha": 0.3}
    samples = 64
    web = web_ibl(page, "ggx", values, environment, strategy, samples, sequence)
    env = Environment(procedural(environment, DEFAULT_SIZE), environment)
    desktop = render("ggx", values, env, strategy, samples, SIZE, renderer=ibl, sequence=sequence)
    other = render(
        "ggx", values, env, strategy, samples, SIZE, seed=1, renderer=ibl, sequence=sequence
    )
    _, mask = sphere_normals(SIZE)
    lum = lambda im: im[..., :3][mask] @ np.array(LUMA)  # noqa: E731
    noise = np.sqrt(np.mean((lum(other) - lum(desktop)) ** 2))
    error = np.sqrt(np.mean((lum(web) - lum(desktop)) ** 2))
    assert noise > 0
    assert error < 1.25 * noise, (strategy, error, noise)
    # The means over the sphere agree within four standard errors of such a difference.
    spread = np.std(lum(other) - lum(desktop)) / np.sqrt(mask.sum())
    assert abs(lum(web).mean() - lum(desktop).mean()) < 4 * spread, (strategy, spread)
    # The view's alpha: 1 on the sphere, 0 behind it, as Progressive.image().
    assert np.allclose(web[..., 3][mask], 1.0) and np.allclose(web[..., 3][~mask], 0.0)


def test_view_shows_the_count_and_restarts_when_a_slider_moves(page, output_dir):
    web_ibl(page, "ggx", {"alpha": 0.3}, "sky", "mis_power", 32)
    assert page.evaluate("brdfLab.panel(0).extra.ibl.status.textContent").startswith(
        "32 samples per pixel"
    )
    restarted = page.evaluate(
        "(() => { brdfLab.moveSlider(0, 'alpha', 300);"
        " return brdfLab.panel(0).extra.ibl.samples; })()"
    )
    assert restarted == 0
    # It goes on by itself, pass after pass.
    page.wait_for_function("brdfLab.panel(0).extra.ibl.samples >= 16")
    page.locator("[data-view=ibl]").first.screenshot(path=output_dir / "web_ibl.png")
    # A model without a sampler says what it uses instead.
    page.evaluate("brdfLab.setModel(0, 'ward', {})")
    page.evaluate("brdfLab.setModel(0, 'lommel_seeliger', {})")
    status = page.evaluate("brdfLab.panel(0).extra.ibl.status.textContent")
    assert "has no BRDF sampler: MIS of cosine-weighted and environment sampling" in status
    assert page.errors == []


def test_address_holds_the_ibl_settings(page):
    """The IBL settings go in the address under their registry names (ibl_env, ...; a
    choice by name or number); an older address's ibl=ENVIRONMENT,STRATEGY,ROTATION still
    reads; changes are written."""
    page.evaluate("location.hash = 'model=ward&views=ibl&ibl_env=studio&ibl_strategy=3'")
    page.wait_for_function("brdfLab.panel(0)?.name === 'ward'")
    assert page.evaluate("brdfLab.panel(0).extra.ibl.envBox.value") == "studio"
    assert page.evaluate("brdfLab.panel(0).extra.ibl.strategyBox.value") == "brdf"
    page.evaluate("location.hash = 'model=ward&views=ibl&ibl=studio,brdf,90'")
    page.wait_for_function("brdfLab.state.settings.ibl_rotation === 90")
    assert page.evaluate("brdfLab.panel(0).extra.ibl.envBox.value") == "studio"
    page.evaluate(
        """() => { const box = brdfLab.panel(0).extra.ibl.envBox; box.value = 'grey_room';
          box.dispatchEvent(new Event('change')); }"""
    )
    # ENVIRONMENTS and STRATEGIES of lab/views/ibl.py: grey_room is 3, brdf 3.
    page.wait_for_function(
        "['ibl_env=3', 'ibl_strategy=3', 'ibl_rotation=90'].every(k => location.hash.includes(k))"
    )
    page.evaluate("location.hash = 'model=ward&views=ibl&ibl=moon'")
    page.wait_for_function("brdfLab.notes().some(n => n.startsWith('ibl=moon'))")
    assert page.evaluate("brdfLab.panel(0).extra.ibl.envBox.value") == "sky"

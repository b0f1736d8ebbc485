"""The page's other views (slice, albedo, lit object, shared polar scale, out-of-plane φo)
read back from WebGL agree with the desktop's EGL render of the same template."""

from __future__ import annotations

import base64
import math

import numpy as np
import pytest
from webpage import open_page

from lab.constants import LUMA, PLOT_DECADES
from lab.models import load_model
from lab.render import Light, direction
from lab.views import albedo as albedo_spec
from lab.web.browser import chromium_path

pytestmark = pytest.mark.skipif(
    chromium_path() is None, reason="Chromium is not installed (apt-get install chromium)"
)

SIZE = 96
# Two independent rasterizers (SwiftShader, llvmpipe): per value within ABS + REL * |desktop|.
ABS_TOL = 1e-5
REL_TOL = 1e-3


@pytest.fixture(scope="module")
def page(tmp_path_factory):
    with open_page(tmp_path_factory, f"model=phong&size={SIZE}&light=40,20") as tab:
        yield tab


def image(page, name: str, panel: int = 0) -> np.ndarray:
    out = page.evaluate("([i, n]) => brdfLab.readView(i, n)", [panel, name])
    data = np.frombuffer(base64.b64decode(out["data"]), dtype=np.float32)
    return data.reshape(out["height"], out["width"], 4)


def assert_close(web: np.ndarray, desktop: np.ndarray, what: str) -> None:
    finite = np.isfinite(desktop)
    assert (np.isfinite(web) == finite).all(), f"{what}: infinities differ"
    diff = np.abs(web[finite] - desktop[finite])
    bound = ABS_TOL + REL_TOL * np.abs(desktop[finite])
    worst = float((diff / (np.abs(desktop[finite]) + ABS_TOL)).max())
    assert (diff <= bound).all(), f"{what}: {(diff > bound).sum()} values differ; worst {worst:.2e}"


@pytest.mark.parametrize(
    "name,values",
    [("phong", {}), ("ward", {"alpha_x": 0.3}), ("cook_torrance", {}), ("oren_nayar", {})],
)
def test_slice_matches_desktop(page, renderer, name, values):
    page.evaluate("([n, v]) => brdfLab.setModel(0, n, v)", [name, values])
    page.evaluate("brdfLab.setSettings({phi_d: 60})")
    page.evaluate("brdfLab.setViews(['slice'])")
    assert page.evaluate("brdfLab.errors(0)") == ""
    web = image(page, "slice")[..., :3]
    desktop = renderer.slice(load_model(name), values, phi_d=60.0, size=SIZE)
    assert web.shape == desktop.shape
    assert web.max() > 0.01
    assert_close(web, desktop, f"{name} slice")
    assert page.errors == []


@pytest.mark.parametrize(
    "name,values",
    [("phong", {}), ("cook_torrance", {"m": 0.2}), ("phong", {"kd": [1, 1, 1], "ks": [1, 1, 1]})],
)
def test_albedo_matches_desktop_and_flags_gain(page, renderer, name, values):
    page.evaluate("([n, v]) => brdfLab.setModel(0, n, v)", [name, values])
    page.evaluate("brdfLab.setViews(['albedo'])")
    out = page.evaluate("brdfLab.readView(0, 'albedo')")
    thetas = np.array(out["thetas"])
    full = albedo_spec.FULL  # the app's full quality, the page's from the view's page data
    np.testing.assert_allclose(thetas, albedo_spec.thetas(full))
    assert thetas[0] == 0 and thetas[-1] == 87.5  # 2.5° steps short of grazing
    desktop = renderer.albedo(
        load_model(name), values, thetas, phi_i=20.0, samples=full["samples"], wedges=full["wedges"]
    )
    assert_close(np.array(out["rgb"]), desktop, f"{name} albedo")
    gain = bool((desktop.max(axis=1) > 1 + 1e-3).any())
    assert out["gain"] == gain
    note = page.locator(".view[data-view=albedo] .view-note").inner_text()
    assert ("energy gain" in note) == gain
    assert page.errors == []


def test_some_albedo_gains_energy(page):
    """The flag is not always off: Phong with kd = ks = 1 reflects more than it receives."""
    page.evaluate("brdfLab.setModel(0, 'phong', {kd: [1, 1, 1], ks: [1, 1, 1]})")
    page.evaluate("brdfLab.setViews(['albedo'])")
    assert page.evaluate("brdfLab.readView(0, 'albedo')")["gain"] is True


@pytest.mark.parametrize("mode", [0, 1, 2, 3])
def test_lit_object_matches_desktop(page, app_renderer, mode, output_dir):
    """Two coloured lights and ambient, each step of the spatially varying lecture."""
    lights = [
        {"theta": 40, "phi": 20, "rgb": [1, 0.9, 0.8]},
        {"theta": 70, "phi": 200, "rgb": [0.3, 0.4, 1]},
    ]
    ambient = [0.03, 0.03, 0.03]
    values = {"m": 0.3}
    page.evaluate("v => brdfLab.setModel(0, 'cook_torrance', v)", values)
    page.evaluate("brdfLab.setViews(['object'])")
    page.evaluate(f"brdfLab.setSettings({{shape: {mode % 4}, mode: {mode}, yaw: 0.8, pitch: 0.4}})")
    page.evaluate("([l, a]) => brdfLab.setLights(l, a)", [lights, ambient])
    assert page.evaluate("brdfLab.errors(0)") == ""
    web = image(page, "object")
    desktop = app_renderer.object(
        load_model("cook_torrance"),
        values,
        [Light(d["theta"], d["phi"], tuple(d["rgb"])) for d in lights],
        ambient=tuple(ambient),
        shape=mode % 4,
        mode=mode,
        yaw=0.8,
        pitch=0.4,
        size=SIZE,
    )
    on = desktop[..., 3] > 0
    # The ray march may stop one step apart on the silhouette: the pixels both hit agree.
    both = on & (web[..., 3] > 0)
    assert both.sum() >= 0.995 * on.sum()
    web, desktop = web[both][:, :3], desktop[both][:, :3]
    assert np.isfinite(web).all() and web.max() > 0.01
    # Normals are finite differences of the distance field: where N.L is near 0 (the
    # terminator) their float rounding is amplified, so a few pixels there may differ more.
    rel = np.abs(web - desktop) / (np.abs(desktop) + ABS_TOL)
    bad = (rel > REL_TOL).any(axis=1)
    assert bad.mean() <= 0.005, f"object mode {mode}: {bad.sum()} of {len(bad)} pixels differ"
    assert float(np.median(rel)) < 1e-4 and float(rel.max()) < 0.05
    if mode == 3:
        page.screenshot(path=output_dir / "web_object.png")
    page.evaluate("brdfLab.setLights([{theta: 40, phi: 20}])")
    assert page.errors == []


def test_polar_out_of_plane_matches_probe(page, renderer):
    """φo turns the plotted plane about the normal: the values are the BRDF at those pairs."""
    page.evaluate("brdfLab.setViews([])")
    page.evaluate("brdfLab.setModel(0, 'ward', {alpha_x: 0.4, alpha_y: 0.1})")
    for phi_o in (0, 35, 90):
        page.evaluate(f"brdfLab.setSettings({{phi_o: {phi_o}}})")
        lobe = np.array(page.evaluate("brdfLab.readLobe(0)")).reshape(181, 4)[:, :3]
        theta_o = np.arange(-90, 91)
        azimuth = np.where(theta_o >= 0, 20 + 180, 20) + phi_o
        V = direction(np.abs(theta_o), azimuth)
        L = np.repeat(direction(40, 20)[None], 181, axis=0)
        desktop = renderer.probe(load_model("ward"), {"alpha_x": 0.4, "alpha_y": 0.1}, L, V)
        assert_close(lobe, desktop, f"polar at phi_o {phi_o}")
    page.evaluate("brdfLab.setSettings({phi_o: 0})")


def test_models_share_one_polar_scale_with_a_log_option(page):
    page.evaluate("brdfLab.setModel(0, 'mirror', {rho_s: [0.9, 0.9, 0.9]})")
    page.evaluate(
        "() => { brdfLab.state.panels.length < 2 && document.querySelector('#add-model').click(); }"
    )
    page.evaluate("brdfLab.setModel(1, 'phong', {ks: [1, 1, 1], ke: 200})")
    peak = page.evaluate("brdfLab.state.panels.map(p => p.polarGeometry.scale)")
    lobe = np.array(page.evaluate("brdfLab.readLobe(1)")).reshape(181, 4)[:, :3] @ LUMA
    assert peak[0] == peak[1] == pytest.approx(max(lobe.max(), 1.0), rel=1e-4)
    assert page.evaluate("brdfLab.overlay().scale") == peak[0]
    assert page.locator("#overlay").is_visible()
    spike = page.evaluate("brdfLab.spike(0)")["length"]
    assert spike == pytest.approx(0.9 / peak[0], rel=1e-4)  # the mirror shrinks beside Phong
    page.evaluate("brdfLab.setSettings({polar_log: true})")
    expected = math.log10(0.9 / (peak[0] * 10.0**-PLOT_DECADES)) / PLOT_DECADES
    assert page.evaluate("brdfLab.spike(0)")["length"] == pytest.approx(expected, rel=1e-4)
    assert "polar_log=1" in page.evaluate("location.hash")
    page.evaluate("brdfLab.setSettings({polar_log: false})")
    page.evaluate("() => brdfLab.state.panels[1].root.querySelector('button.close').click()")

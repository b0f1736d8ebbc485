"""The page's 3D lobe (the model's BRDF in the vertex stage of shaders/views/lobe_mesh.glsl)
agrees with the desktop's EGL render of the same mesh, scale and camera."""

from __future__ import annotations

import base64

import numpy as np
import pytest
from webpage import open_page

from lab.models import load_model
from lab.views.lobe3d import LOBE_GRID, LobeCamera, _lobe_common
from lab.web.browser import chromium_path

pytestmark = pytest.mark.skipif(
    chromium_path() is None, reason="Chromium is not installed (apt-get install chromium)"
)

SIZE = 256
LIGHT = (40.0, 20.0)
REL_TOL = 1e-3
BACKGROUND = (40 / 255, 40 / 255, 44 / 255, 1.0)


@pytest.fixture(scope="module")
def page(tmp_path_factory):
    with open_page(
        tmp_path_factory, f"model=phong&size={SIZE}&light={LIGHT[0]:g},{LIGHT[1]:g}"
    ) as tab:
        yield tab


def read(page, panel: int = 0) -> tuple[np.ndarray, dict]:
    out = page.evaluate("i => brdfLab.readView(i, 'lobe3d')", panel)
    data = np.frombuffer(base64.b64decode(out["data"]), dtype=np.float32)
    return data.reshape(out["height"], out["width"], 4), out


def hex_rgb(text: str) -> tuple[float, float, float]:
    return tuple(int(text[i : i + 2], 16) / 255 for i in (1, 3, 5))


@pytest.mark.parametrize(
    ("name", "values", "settings"),
    [
        ("phong", {"ke": 30.0}, {}),
        ("cook_torrance", {"m": 0.25}, {"polar_log": True}),
        ("ward", {"alpha_x": 0.4, "alpha_y": 0.1}, {"polar_cos": True}),
    ],
)
def test_lobe_matches_desktop(page, renderer, name, values, settings, output_dir):
    page.evaluate("([n, v]) => brdfLab.setModel(0, n, v)", [name, values])
    settings = {"polar_log": False, "polar_cos": False, **settings}
    page.evaluate("s => brdfLab.setSettings(s)", settings)
    page.evaluate("brdfLab.setSettings({lobe_yaw: -0.9, lobe_pitch: 0.45, lobe_zoom: 2})")
    page.evaluate("brdfLab.setViews(['lobe3d'])")
    assert page.evaluate("brdfLab.errors(0)") == ""
    web, out = read(page)
    log, cos = settings["polar_log"], settings["polar_cos"]
    model = load_model(name)
    peak = renderer.lobe_peak(model, values, *LIGHT, cos, LOBE_GRID)
    assert out["peak"] == pytest.approx(list(peak), rel=REL_TOL, abs=1e-7)
    assert out["scale"] == pytest.approx(max(peak), rel=REL_TOL)
    color = hex_rgb(page.evaluate("brdfLab.panel(0).color"))
    desktop = renderer.lobe_mesh(
        [(model, values, color)],
        *LIGHT,
        size=(out["width"], out["height"]),
        camera=LobeCamera(-0.9, 0.45, 2.0),
        cos_weighted=cos,
        log=log,
        marks=False,
        peaks=[peak],
        background=BACKGROUND,
    )
    assert web.shape == desktop.shape
    # Every vertex of the mesh: the luminance the vertex stage places it by.
    uniforms = {"u_grid": LOBE_GRID, "u_light_angles": tuple(np.radians(LIGHT)), "u_cos": cos}
    rows, cols = LOBE_GRID
    fbo = renderer._run(model, "lobe_mesh_peak", values, (cols, rows), uniforms, _lobe_common())
    at_vertices = renderer._read(fbo)[..., 0].ravel()
    np.testing.assert_allclose(out["grid"], at_vertices, rtol=REL_TOL, atol=1e-6)
    # The picture: the same silhouette, and the same shading but where triangles are
    # smaller than a pixel (the tip, the grid lines), where two rasterizers pick different
    # facets for a pixel.
    on_web = np.abs(web[..., :3] - np.array(BACKGROUND[:3])).max(axis=-1) > 0.02
    on = np.abs(desktop[..., :3] - np.array(BACKGROUND[:3])).max(axis=-1) > 0.02
    assert on.mean() > 0.05, "the lobe covers little of the picture"
    assert (on & on_web).sum() / (on | on_web).sum() > 0.97
    diff = np.abs(web - desktop)[..., :3].max(axis=-1)
    assert np.median(diff[on]) < 0.01 and diff[on].mean() < 0.02
    page.screenshot(path=output_dir / f"web_lobe3d_{name}.png")
    assert page.errors == []


def test_drag_orbits_and_models_share_a_scale(page, renderer):
    page.evaluate("brdfLab.setModel(0, 'phong', {ke: 30})")
    page.evaluate("brdfLab.setSettings({polar_log: false, polar_cos: false})")
    page.evaluate("brdfLab.setSettings({lobe_yaw: -0.6, lobe_pitch: 0.35, lobe_zoom: 1})")
    page.evaluate("brdfLab.setViews(['lobe3d'])")
    box = page.locator("canvas.lobe3d").first.bounding_box()
    x, y = box["x"] + box["width"] / 2, box["y"] + box["height"] / 2
    page.mouse.move(x, y)
    page.mouse.down()
    page.mouse.move(x + box["width"] / 4, y, steps=4)
    page.mouse.up()
    page.evaluate("brdfLab.renderNow()")
    yaw = page.evaluate("brdfLab.state.settings.lobe_yaw")
    assert yaw == pytest.approx(-0.6 + np.pi / 4, abs=0.05)
    # A second, brighter model: both panels draw on its scale.
    page.evaluate("document.querySelector('#add-model').click()")
    page.evaluate("brdfLab.setModel(1, 'phong', {ks: [1, 1, 1], ke: 200})")
    scales = page.evaluate("[0, 1].map(i => brdfLab.readView(i, 'lobe3d').scale)")
    strong = renderer.lobe_peak(load_model("phong"), {"ks": [1, 1, 1], "ke": 200.0}, *LIGHT)
    assert scales[0] == scales[1] == pytest.approx(max(strong), rel=REL_TOL)
    page.evaluate("() => brdfLab.state.panels[1].root.querySelector('button.close').click()")
    assert page.errors == []


def test_camera_and_order_in_the_address_and_presets(page):
    page.evaluate("brdfLab.setViews(['lobe3d', 'sh'])")
    page.evaluate("brdfLab.setSettings({lobe_yaw: 0.25, lobe_zoom: 1.5, sh_order: 4})")
    address = page.evaluate("location.hash")
    assert "lobe_yaw=0.25" in address and "lobe_zoom=1.5" in address and "sh_order=4" in address
    hash_ = page.evaluate(
        "brdfLab.presetHash({model: [{model: 'ggx'}], views: ['lobe3d', 'sh'],"
        " settings: {lobe_yaw: 1.2, lobe_pitch: 0.8, lobe_zoom: 2.5, sh_order: 3}})"
    )
    assert hash_["skipped"] == []
    page.evaluate("h => { location.hash = h; }", hash_["hash"])
    page.wait_for_function("(s => s.sh_order === 3 && s.lobe_zoom === 2.5)(brdfLab.state.settings)")
    state = page.evaluate("(s => [s.lobe_yaw, s.lobe_pitch])(brdfLab.state.settings)")
    assert state + [page.evaluate("brdfLab.state.views")] == [1.2, 0.8, ["lobe3d", "sh"]]
    page.evaluate("brdfLab.setSettings({lobe_yaw: -0.6, lobe_pitch: 0.35, lobe_zoom: 1})")
    page.evaluate("brdfLab.setSettings({sh_order: 8})")
    assert page.errors == []


def test_mirror_spike_and_coarse_frame(page, renderer):
    """A delta model's spike (the scale's floor) is the desktop's; while the hand moves the
    lobe draws at half resolution, and full size again once it stops."""
    page.evaluate("brdfLab.setModel(0, 'mirror')")
    page.evaluate("brdfLab.setSettings({polar_log: false, polar_cos: false})")
    page.evaluate("brdfLab.setViews(['lobe3d'])")
    _, out = read(page)
    peak, spike = renderer.lobe_peak(load_model("mirror"), {}, *LIGHT, False, LOBE_GRID)
    assert spike > 0.5
    assert out["peak"] == pytest.approx([peak, spike], rel=REL_TOL, abs=1e-7)
    size = [out["width"], out["height"]]
    coarse = page.evaluate(
        "() => { brdfLab.state.fast = true; brdfLab.panel(0).render();"
        " return brdfLab.panel(0).extra.lobe3d.size; }"
    )
    assert coarse == [(size[0] + 1) // 2, (size[1] + 1) // 2]
    # A reader (still moving) gets the full quality the page settles to.
    assert [read(page)[1][k] for k in ("width", "height")] == size
    assert page.evaluate("brdfLab.state.fast") is False
    page.evaluate("brdfLab.setModel(0, 'phong')")
    assert page.errors == []

"""The web lab in headless Chromium (SwiftShader): every model renders, agrees with the
desktop EGL render (llvmpipe), sliders follow the formula, errors name the model file."""

from __future__ import annotations

import json
import re
from pathlib import Path

import numpy as np
import pytest
from webpage import LabTab

from lab.models import load_model, model_names
from lab.web.browser import chromium_path

pytestmark = pytest.mark.skipif(
    chromium_path() is None, reason="Chromium is not installed (apt-get install chromium)"
)

SIZE = 128
LIGHT = (40.0, 20.0)
# SwiftShader and llvmpipe are two independent rasterizers with their own pow/exp/atan.
# Every sphere pixel must agree per channel within ABS_TOL + REL_TOL * |desktop|; the
# largest relative difference measured over the library's defaults was about 1.2e-4.
ABS_TOL = 1e-5
REL_TOL = 1e-3


@pytest.fixture(scope="module")
def site(tmp_path_factory):
    from lab.cli import main

    outdir = tmp_path_factory.mktemp("site")
    assert main(["web-export", str(outdir)]) == 0
    return outdir


@pytest.fixture(scope="module")
def browser(site):
    from lab.web.browser import chromium
    from lab.web.site import serving

    with serving(site) as url, chromium() as browser:
        browser.base_url = url
        yield browser


Page = LabTab  # a tab of the lab in its own context, its console errors collected


@pytest.fixture(scope="module")
def lab_page(browser):
    page = Page(browser, f"model=lambert&size={SIZE}&light={LIGHT[0]:g},{LIGHT[1]:g}")
    yield page
    page.close()


def test_site_export_is_self_contained(site):
    manifest = json.loads((site / "manifest.json").read_text())
    assert manifest["models"] == model_names()
    for relative in manifest["files"]:
        assert (site / "shaders" / relative).is_file(), relative
    assert {"index.html", "lab.js", "header.js", "assemble.js", "style.css"} <= {
        p.name for p in site.iterdir()
    }


@pytest.mark.parametrize("name", model_names())
def test_model_renders_like_desktop(lab_page, renderer, name, output_dir):
    """Same model file, same defaults: the page's float sphere matches Renderer.sphere."""
    assert lab_page.js("n => brdfLab.setModel(0, n)", name) >= 0
    assert lab_page.js("brdfLab.errors(0)") == ""
    assert lab_page.errors == []
    web = lab_page.sphere()
    desktop = renderer.sphere(load_model(name), {}, light=LIGHT, size=SIZE)
    assert web.shape == desktop.shape
    np.testing.assert_array_equal(web[..., 3], desktop[..., 3])  # same silhouette
    on = desktop[..., 3] > 0
    assert np.isfinite(web[on]).all()
    assert web[on][:, :3].max() > 0.01, "the sphere is black"
    close = np.abs(web[..., :3] - desktop[..., :3]) <= ABS_TOL + REL_TOL * np.abs(desktop[..., :3])
    worst = float((np.abs(web - desktop)[..., :3] / (np.abs(desktop[..., :3]) + ABS_TOL))[on].max())
    assert close[on].all(), f"{name}: {int((~close[on]).sum())} values differ; worst {worst:.2e}"
    if name in ("phong", "cook_torrance", "mirror"):
        lab_page.page.screenshot(path=output_dir / f"web_{name}.png")


def test_slider_follows_the_formula(browser, output_dir):
    """Phong lit from the eye: radiance = ks (2 c^2 - 1)^ke c with c = N.V (kd = 0)."""
    page = Page(browser, f"model=phong&kd=0&ks=0.8&size={SIZE}&light=0,0")
    try:
        y, x = (np.mgrid[0:SIZE, 0:SIZE] + 0.5) / SIZE * 2 - 1
        r2 = x**2 + y**2
        c = np.sqrt(np.clip(1 - r2, 0, None))
        renders = []
        for position, expected_ke in ((200, 1000**0.2), (700, 1000**0.7)):
            ke = page.js("p => brdfLab.moveSlider(0, 'ke', p)", position)
            assert ke == pytest.approx(expected_ke, rel=1e-3)  # a log slider
            assert page.js("brdfLab.values(0).ke") == ke
            image = page.sphere()
            expected = 0.8 * np.maximum(2 * c**2 - 1, 0) ** ke * c
            on = r2 < 0.98  # away from the rim, where c is steep in the pixel position
            np.testing.assert_allclose(image[..., 0][on], expected[on], rtol=2e-3, atol=2e-4)
            renders.append(image)
        # A larger exponent: a smaller, brighter-edged highlight (less light off-centre).
        assert renders[1][..., 0].sum() < 0.5 * renders[0][..., 0].sum()
        assert f"ke={ke:g}" in page.js("location.hash")
        page.page.screenshot(path=output_dir / "web_slider.png")
        assert page.errors == []
    finally:
        page.close()


def test_presets_and_side_by_side(browser, output_dir):
    page = Page(
        browser,
        "model=phong&ke=120&model=ward&alpha_x=0.3&model=cook_torrance"
        "&distribution=blinn&light=60,45&size=200",
    )
    try:
        assert page.js("brdfLab.state.panels.length") == 3
        assert page.js("brdfLab.values(0).ke") == 120
        assert page.js("brdfLab.values(1).alpha_x") == 0.3
        assert page.js("brdfLab.values(2).distribution") == "blinn"
        assert page.js("brdfLab.state.light") == {"theta": 60, "phi": 45}
        lobe = np.array(page.js("brdfLab.readLobe(0)")).reshape(181, 4)
        # Phong's lobe peaks at the mirror direction theta_o = theta_i = 60 deg.
        assert int(np.argmax(lobe[:, 0])) - 90 == 60
        page.page.screenshot(path=output_dir / "web_side_by_side.png", full_page=True)
        assert page.errors == []
    finally:
        page.close()


def test_bad_preset_is_reported_on_the_page(browser):
    page = Page(browser, "model=nosuch&model=phong&ke=5000&colour=1")
    try:
        notes = page.js("brdfLab.notes()")
        assert any("unknown model nosuch" in n for n in notes)
        assert any("ke must be a number in [1, 1000]" in n for n in notes)
        assert any("has no parameter colour" in n for n in notes)
        assert page.js("brdfLab.values(0).ke") == 50  # the default stays
        assert page.errors == []
    finally:
        page.close()


def test_drag_moves_the_light(lab_page):
    box = lab_page.page.locator("canvas.sphere").first.bounding_box()
    # Half way to the right rim: N = (0.5, 0, 0.866) -> theta 30, phi 0.
    lab_page.page.mouse.click(box["x"] + box["width"] * 0.75, box["y"] + box["height"] * 0.5)
    light = lab_page.js("brdfLab.state.light")
    assert light["theta"] == pytest.approx(30, abs=1.5) and light["phi"] == pytest.approx(0, abs=1)
    lab_page.js(f"brdfLab.setLight({LIGHT[0]}, {LIGHT[1]})")


def test_errors_name_the_model_file_and_line(lab_page):
    """A compile error points at the user's file and its own lines; so does a header error."""
    from lab.models import ModelError, parse_model

    fixtures = Path(__file__).parent / "fixtures" / "headers"
    code = (fixtures / "err_compile.glsl").read_text()
    count = lab_page.js("brdfLab.state.panels.length")
    error = lab_page.js("([l, c]) => brdfLab.loadModel(l, c)", ["my_model.glsl", code])
    assert "does not compile" in error
    lines = {int(m) for m in re.findall(r"my_model\.glsl:(\d+):", error)}
    assert lines and lines <= {5, 6}, error  # `float x = 1;` and `undefined_name`
    header = (fixtures / "err_float_default.glsl").read_text()
    error = lab_page.js("([l, c]) => brdfLab.loadModel(l, c)", ["bad.glsl", header])
    with pytest.raises(ModelError) as python_error:
        parse_model(header, "bad.glsl")
    assert error == str(python_error.value)  # the same words as the desktop lab
    assert lab_page.errors == []
    lab_page.js(
        f"() => {{ while (brdfLab.state.panels.length > {count}) "
        "brdfLab.state.panels.pop().root.remove(); }"
    )


def test_live_server_serves_page_manifest_and_shaders():
    """`brdf-lab serve` maps /shaders/ to the live shader folder and makes the manifest."""
    from urllib.request import urlopen

    from lab.models import SHADER_DIR
    from lab.web.site import serving

    with serving() as url:
        manifest = json.loads(urlopen(url + "manifest.json").read())
        assert manifest["models"] == model_names()
        phong = urlopen(url + "shaders/brdfs/phong.glsl").read().decode()
        assert phong == (SHADER_DIR / "brdfs" / "phong.glsl").read_text()
        assert b"lab.js" in urlopen(url + "index.html").read()


def test_export_into_a_file_is_a_one_line_error(tmp_path, capsys):
    from lab.cli import main

    target = tmp_path / "taken"
    target.write_text("x")
    assert main(["web-export", str(target)]) == 2
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0 and "is a file" in err


def test_two_lights_add_up(lab_page, renderer):
    """Light A alone + light B alone = both together; ambient adds on every sphere pixel;
    and the page agrees with the desktop render of the same lights."""
    from lab.render import Light

    a = {"theta": 30, "phi": 0, "rgb": [1, 0.8, 0.6]}
    b = {"theta": 60, "phi": 135, "rgb": [0.2, 0.5, 1]}
    ambient = [0.05, 0.02, 0.01]
    lab_page.js("n => brdfLab.setModel(0, n)", "phong")
    images = []
    for lights, amb in (([a], [0, 0, 0]), ([b], [0, 0, 0]), ([a, b], [0, 0, 0]), ([a, b], ambient)):
        lab_page.js("([l, amb]) => brdfLab.setLights(l, amb)", [lights, amb])
        assert lab_page.js("brdfLab.errors(0)") == ""
        images.append(lab_page.sphere())
    only_a, only_b, both, lit = images
    on = both[..., 3] > 0
    assert only_a[on][:, :3].max() > 0.05 and only_b[on][:, :3].max() > 0.05
    np.testing.assert_allclose(both[on], (only_a + only_b)[on] - [0, 0, 0, 1], rtol=1e-5, atol=1e-6)
    np.testing.assert_allclose(lit[on][:, :3], both[on][:, :3] + ambient, rtol=1e-5, atol=1e-6)
    assert (lit[~on] == 0).all()  # the background gets no ambient
    desktop = renderer.sphere(
        load_model("phong"),
        {},
        size=SIZE,
        ambient=tuple(ambient),
        lights=[Light(d["theta"], d["phi"], tuple(d["rgb"])) for d in (a, b)],
    )
    close = np.abs(lit - desktop)[..., :3] <= ABS_TOL + REL_TOL * np.abs(desktop[..., :3])
    assert close[on].all()
    # The page keeps the lights in its address, so a preset can hold them.
    hash_ = lab_page.js("location.hash")
    assert "light=30,0,1,0.8,0.6&light=60,135,0.2,0.5,1&ambient=0.05,0.02,0.01" in hash_
    assert lab_page.page.locator(".light-row").count() == 2
    assert lab_page.errors == []
    lab_page.js(f"brdfLab.setLights([{{theta: {LIGHT[0]}, phi: {LIGHT[1]}}}])")


def test_add_light_button(browser):
    page = Page(browser, f"model=lambert&size={SIZE}&light=0,0")
    try:
        before = page.sphere()
        page.page.click("#add-light")
        page.js("brdfLab.renderNow()")
        assert page.js("brdfLab.state.lights.length") == 2
        after = page.sphere()
        # A second white light can only add light (Lambert: nowhere negative).
        on = before[..., 3] > 0
        assert (after[on][:, :3] >= before[on][:, :3] - 1e-6).all()
        assert after[on][:, :3].sum() > 1.1 * before[on][:, :3].sum()
        page.page.click(".light-row[data-light='1'] button.close")
        assert page.js("brdfLab.state.lights.length") == 1
        assert page.errors == []
    finally:
        page.close()


def test_mirror_spike_has_the_reflectance_length(lab_page, renderer):
    """The δ spike's reflectance is read back from the model's DELTA_REFLECTANCE."""
    model = load_model("mirror")
    for rho in ((0.9, 0.9, 0.9), (0.6, 0.3, 0.1)):
        lab_page.js("rho => brdfLab.setModel(0, 'mirror', {rho_s: rho})", list(rho))
        spike = lab_page.js("brdfLab.spike(0)")
        desktop = renderer.delta_reflectance(model, {"rho_s": rho}, LIGHT[0], LIGHT[1])
        np.testing.assert_allclose(spike["rgb"], desktop, rtol=1e-6)
        np.testing.assert_allclose(spike["rgb"], rho, rtol=1e-6)
        luma = 0.2126 * rho[0] + 0.7152 * rho[1] + 0.0722 * rho[2]
        assert spike["length"] == pytest.approx(luma, rel=1e-5)  # of the plot's radius
    lab_page.js("brdfLab.setModel(0, 'phong')")
    assert lab_page.js("brdfLab.spike(0)")["rgb"] is None


def test_labels_and_tooltips(lab_page):
    """Parameter names carry the header's meaning; light angles show degrees."""
    lab_page.js("brdfLab.setModel(0, 'phong')")
    tip = lab_page.page.locator("[data-param=ke] label").get_attribute("title")
    assert tip.startswith("ke: specular exponent: larger means a smaller, sharper highlight")
    assert "1 to 1000, log slider" in tip
    row = lab_page.page.locator(".light-row").first
    assert row.locator(".theta-text").inner_text() == f"{LIGHT[0]:g}°"
    assert row.locator(".phi-text").inner_text() == f"{LIGHT[1]:g}°"
    assert "θi" in row.inner_text() and "φi" in row.inner_text()


def test_embed_in_a_small_frame(browser):
    """Embedded in a frame too small for it, the lab shrinks its pictures and still draws."""
    page = Page(browser, "model=mirror&model=phong&size=400&embed=1")
    try:
        page.page.set_viewport_size({"width": 700, "height": 260})
        page.js("() => { dispatchEvent(new Event('resize')); brdfLab.renderNow(); }")
        sizes = page.js("[...document.querySelectorAll('canvas.sphere')].map(c => c.clientWidth)")
        assert all(96 <= s < 400 for s in sizes), sizes
        assert page.js("brdfLab.errors(0) + brdfLab.errors(1)") == ""
        assert page.js("brdfLab.spike(0)")["length"] == pytest.approx(0.9, rel=1e-5)
        assert page.errors == []
    finally:
        page.close()


def test_too_many_models_are_reported(browser):
    """A link with more models than fit names the ones left out and turns "+ model" off."""
    page = Page(browser, "&".join(f"model={m}" for m in ["lambert"] * 6 + ["phong", "ward"]))
    try:
        assert page.js("brdfLab.state.panels.length") == 6
        assert "at most 6 models side by side; left out: phong, ward" in page.js("brdfLab.notes()")
        assert page.js("document.querySelector('#add-model').disabled")
        assert page.errors == []
    finally:
        page.close()

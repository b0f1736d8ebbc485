"""Model files opened in the page: a MERL .binary table (the `measured` model, trilinear by
8 texelFetches) and a BRDF Explorer .brdf file render as the desktop's EGL render does."""

from __future__ import annotations

import base64

import numpy as np
import pytest
from test_brdf_explorer import INT_DIVISION, INT_DIVISION_VALUE
from webpage import open_page

from lab.brdf_explorer import parse_brdf
from lab.measured import merl
from lab.measured.merl import MerlTable, read_merl, write_merl
from lab.measured.model import measured_model
from lab.measured.tabulate import tabulate
from lab.render import direction
from lab.web.browser import chromium_path

pytestmark = pytest.mark.skipif(
    chromium_path() is None, reason="Chromium is not installed (apt-get install chromium)"
)

SIZE = 96
LIGHT = (40.0, 20.0)
ABS_TOL = 1e-5
REL_TOL = 1e-3
GGX = {"kd": (0.2, 0.1, 0.05), "ks": (0.8, 0.8, 0.8), "alpha": 0.3}  # as test_measured_render
# BRDF Explorer's style: '#' comments, ints where floats are meant, a loop with an int counter.
BLINN = """\
# Normalised Blinn-Phong, as a BRDF Explorer file
analytic

::begin parameters
float n 1 1000 40
bool normalized 1
color tint 1 0.5 0.25
::end parameters

::begin shader
const float PI = 3.14159265358979323846;
float sqr(float x) { return x*x; }
vec3 BRDF( vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y )
{
    vec3 H = normalize(L+V);
    float val = pow(max(0, dot(N,H)), n);
    if (normalized)
        val *= (n + 2) / (2*PI);
    float taper = 0;
    for (int i = 0; i < 4; i++) taper += 0.25 * sqr(1);
    return tint * val * taper;
}
::end shader
"""


@pytest.fixture(scope="module")
def page(tmp_path_factory):
    with open_page(
        tmp_path_factory, f"model=lambert&size={SIZE}&light={LIGHT[0]:g},{LIGHT[1]:g}"
    ) as tab:
        yield tab


@pytest.fixture(scope="module")
def table_file(renderer, tmp_path_factory):
    """A full-size GGX table, as the Python tests make theirs."""
    path = tmp_path_factory.mktemp("merl") / "ggx.binary"
    write_merl(tabulate("ggx", GGX, renderer=renderer), path)
    return path


def open_file(page, path) -> int:
    """Opens `path` with the page's file picker; returns the index of its new panel."""
    before = page.evaluate("brdfLab.state.panels.length")
    page.set_input_files("#open-file", str(path))
    page.wait_for_function(f"brdfLab.state.panels.length > {before}", timeout=60_000)
    page.evaluate("brdfLab.renderNow()")
    return before


def sphere(page, panel: int) -> np.ndarray:
    out = page.evaluate("i => brdfLab.readSphere(i)", panel)
    data = np.frombuffer(base64.b64decode(out["data"]), dtype=np.float32)
    return data.reshape(out["height"], out["width"], 4)


def assert_close(web: np.ndarray, desktop: np.ndarray, what: str) -> None:
    diff = np.abs(web - desktop)
    bound = ABS_TOL + REL_TOL * np.abs(desktop)
    worst = float((diff / (np.abs(desktop) + ABS_TOL)).max())
    assert (diff <= bound).all(), f"{what}: {(diff > bound).sum()} values differ; worst {worst:.2e}"


def test_merl_table_renders_like_desktop(page, renderer, table_file):
    panel = open_file(page, table_file)
    assert page.evaluate(f"brdfLab.errors({panel})") == ""
    assert page.evaluate(f"brdfLab.state.panels[{panel}].name") == "ggx_measured"
    model = measured_model(read_merl(table_file))
    theta_o = np.arange(-90, 91)
    # Out of the plane of incidence (there phi_d is 90 deg, a bin edge, everywhere).
    page.evaluate("brdfLab.setSettings({phi_o: 35})")
    V = direction(np.abs(theta_o), np.where(theta_o >= 0, LIGHT[1] + 180, LIGHT[1]) + 35)
    L = np.repeat(direction(*LIGHT)[None], 181, axis=0)
    # Nearest jumps at bin edges, where two rasterizers may round either way: compared
    # away from them (as test_measured_render does).
    coords = np.stack(merl.continuous_index(*merl.half_diff(L, V)))
    inside = (np.abs(coords - np.round(coords)) > 0.01).all(axis=0)
    assert inside.sum() > 120
    for interpolation in ("linear", "nearest"):
        values = {"interpolation": interpolation, "gain": 1.5}
        page.evaluate("([i, v]) => brdfLab.setModel(i, 'ggx_measured', v)", [panel, values])
        if interpolation == "linear":
            web = sphere(page, panel)
            desktop = renderer.sphere(model, values, light=LIGHT, size=SIZE)
            np.testing.assert_array_equal(web[..., 3], desktop[..., 3])
            on = desktop[..., 3] > 0
            assert web[on][:, :3].max() > 0.01
            assert_close(web[on][:, :3], desktop[on][:, :3], "measured sphere")
        # The polar plot's probe values (theta_o = -90..90 in its plane).
        lobe = np.array(page.evaluate(f"brdfLab.readLobe({panel})")).reshape(181, 4)[:, :3]
        desktop = renderer.probe(model, values, L, V)
        assert lobe.max() > 0.1
        assert_close(lobe[inside], desktop[inside], f"measured polar, {interpolation}")
    page.evaluate("brdfLab.setSettings({phi_o: 0})")
    page.evaluate(f"() => brdfLab.state.panels[{panel}].root.querySelector('button.close').click()")
    assert page.errors == []


def test_linear_lookup_wraps_phi_d_and_clamps_theta(page, renderer, tmp_path):
    """A small table whose values change along every axis: the 8-texel lookup agrees with
    the desktop's and numpy's at the edges (phi_d wraps, theta clamps)."""
    h, d, p = np.meshgrid(np.arange(6.0), np.arange(5.0), np.arange(8.0), indexing="ij")
    rgb = np.stack([1 + h, 1 + 0.5 * d, 1 + np.cos(p * np.pi / 4)], axis=-1) * 0.1
    path = write_merl(MerlTable.from_rgb(rgb), tmp_path / "edges.binary")
    panel = open_file(page, path)
    model = measured_model(read_merl(path))
    web = sphere(page, panel)
    desktop = renderer.sphere(model, {}, light=LIGHT, size=SIZE)
    on = desktop[..., 3] > 0
    assert_close(web[on][:, :3], desktop[on][:, :3], "small table")
    page.evaluate(f"() => brdfLab.state.panels[{panel}].root.querySelector('button.close').click()")


@pytest.mark.parametrize(
    ("data", "words"),
    [
        (b"\x01\x00", "too short for the 12-byte header"),
        (np.array([90, 90, 180], "<i4").tobytes() + b"\0" * 64, "file truncated"),
        (np.array([-5, 90, 180], "<i4").tobytes(), "not a MERL .binary file"),
    ],
)
def test_damaged_table_is_reported(page, tmp_path, data, words):
    path = tmp_path / "broken.binary"
    path.write_bytes(data)
    panel = open_file(page, path)
    error = page.evaluate(f"brdfLab.errors({panel})")
    assert error.startswith("broken.binary: ") and words in error
    page.evaluate(f"() => brdfLab.state.panels[{panel}].root.querySelector('button.close').click()")


def test_brdf_explorer_file_renders_like_desktop(page, app_renderer, tmp_path):
    path = tmp_path / "blinn.brdf"
    path.write_text(BLINN)
    panel = open_file(page, path)
    assert page.evaluate(f"brdfLab.errors({panel})") == ""
    names = page.evaluate(f"brdfLab.state.panels[{panel}].model.params.map(p => p.name)")
    assert names == ["n", "normalized", "tint"]
    model = parse_brdf(BLINN, path)
    for values in ({}, {"n": 200.0, "normalized": False}):
        page.evaluate("([i, v]) => brdfLab.setModel(i, 'blinn', v)", [panel, values])
        web = sphere(page, panel)
        desktop = app_renderer.sphere(model, values, light=LIGHT, size=SIZE)
        on = desktop[..., 3] > 0
        assert web[on][:, :3].max() > 0.01
        assert_close(web[on][:, :3], desktop[on][:, :3], f"blinn.brdf {values}")
    # A mistake names the .brdf file's own line.
    bad = tmp_path / "broken_blinn.brdf"
    bad.write_text(BLINN.replace("return tint * val * taper;", "return tint * val * taper"))
    panel = open_file(page, bad)
    error = page.evaluate(f"brdfLab.errors({panel})")
    assert "does not compile" in error
    assert "broken_blinn.brdf:21" in error or "broken_blinn.brdf:22" in error, error
    page.evaluate(f"() => brdfLab.state.panels[{panel}].root.querySelector('button.close').click()")
    assert page.errors == []


def test_brdf_int_division_is_what_brdf_explorer_computes(page, app_renderer, tmp_path):
    """GLSL ES converts no ints: the page writes the file's literals as floats, yet 1/4
    stays 0 there as in BRDF Explorer's desktop GLSL (and in the desktop lab)."""
    path = tmp_path / "ints.brdf"
    path.write_text(INT_DIVISION)
    panel = open_file(page, path)
    assert page.evaluate(f"brdfLab.errors({panel})") == ""
    lobe = np.array(page.evaluate(f"brdfLab.readLobe({panel})")).reshape(181, 4)[:, :3]
    front = lobe[100:170]  # theta_o 10..79 deg: both directions above the surface
    np.testing.assert_allclose(front, np.tile(INT_DIVISION_VALUE, (70, 1)), rtol=1e-6)
    web = sphere(page, panel)
    desktop = app_renderer.sphere(parse_brdf(INT_DIVISION, path), {}, light=LIGHT, size=SIZE)
    on = desktop[..., 3] > 0
    assert_close(web[on][:, :3], desktop[on][:, :3], "ints.brdf")
    page.evaluate(f"() => brdfLab.state.panels[{panel}].root.querySelector('button.close').click()")
    assert page.errors == []

"""Descriptions of the views other than the polar plot (lab/describe_views.py and its mirror
lab/web/static/describe_views.js): the words say what the view's numbers are (the brightest
point of a Lambert sphere faces the light, Phong's faces the halfway vector, GGX's D at the
normal is 1/(π α²)...), and the page says the same words on the same numbers."""

from __future__ import annotations

import json
import math
import re
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

from lab import describe_views as dv
from lab.constants import GRAZING_DEG, LUMA
from lab.describe import fmt

ROOT = Path(__file__).resolve().parent.parent


@pytest.fixture(scope="module")
def renderer():
    from lab.render import Renderer

    return Renderer()


def angles_of(text: str) -> tuple[int, int]:
    """(from the halfway vector, from the light) in a sphere's description."""
    m = re.search(r"normal is (\d+)° from the halfway vector and (\d+)° from the light", text)
    assert m, text
    return int(m[1]), int(m[2])


@pytest.mark.parametrize("theta_i,phi_i", [(40.0, 0.0), (60.0, 120.0)])
def test_sphere_brightest_point_faces_the_light_or_the_halfway_vector(renderer, theta_i, phi_i):
    lambert = renderer.sphere("lambert", {}, (theta_i, phi_i), size=128)
    text = dv.sphere("lambert", lambert, theta_i, phi_i)
    half, light = angles_of(text)
    assert light <= 2 and abs(half - theta_i / 2) <= 2  # N = L: θi/2 from H
    lum = lambert[..., :3] @ np.array(LUMA)
    assert f"brightest {fmt(float(lum.max()))} " in text
    phong = renderer.sphere("phong", {"ke": 60.0}, (theta_i, phi_i), size=128)
    half, light = angles_of(dv.sphere("phong", phong, theta_i, phi_i))
    assert half <= 2 and abs(light - theta_i / 2) <= 2  # the highlight: N = H
    # Lambert lights the disc where N·L > 0: for θi = 40° that is (1 + cos θi) / 2 of its area.
    if theta_i == 40.0:
        share = int(re.search(r"(\d+) % of the disc lit", text)[1])
        assert abs(share - 100 * (1 + math.cos(math.radians(theta_i))) / 2) <= 3


def test_albedo_words_and_energy_gain():
    thetas = np.arange(0.0, 90.0, 2.5)
    flat = np.full(len(thetas), 0.5)
    assert dv.albedo("lambert", thetas, flat) == (
        "lambert: directional albedo 0.5 at θi 0° to 0.5 at θi 88°; largest 0.5 at θi 0°; "
        "above 1 nowhere."
    )
    gain = 0.9 + 0.4 * (thetas / 90) ** 2
    text = dv.albedo("bad", thetas, gain)
    over = thetas[gain > 1 + dv.GAIN]
    assert f"at {len(over)} of {len(thetas)} angles, θi {round(over[0])}° to 88°." in text
    assert f"largest {fmt(gain.max())} at θi 88°" in text


def test_slice_range_peak_and_half_width(renderer):
    image = renderer.slice("blinn_phong", {"ke": 50.0, "kd": [0, 0, 0]}, 90.0, 90)
    lum = image[..., :3] @ np.array(LUMA)
    text = dv.image_slice("blinn_phong", image, 90.0)
    assert f"from {fmt(lum.min())} to {fmt(lum.max())} sr⁻¹" in text
    # Blinn-Phong's specular is cos^ke θh: it halves at cos θh = 2^(-1/ke), along any θd.
    half = math.degrees(math.acos(2 ** (-1 / 50.0)))
    said = int(re.search(r"half its θh 0° value by θh (\d+)°", text)[1])
    assert abs(said - half) <= 1.5, (said, half)
    flat = renderer.slice("lambert", {}, 90.0, 32)
    assert "over the whole slice, no peak" in dv.image_slice("lambert", flat, 90.0)


def grid_angles(rows: int = 46, cols: int = 72) -> np.ndarray:
    """(θo, φo) pairs in radians on a plain grid whose row 0 is the normal."""
    theta = np.radians(np.linspace(0.0, 89.5, rows))
    phi = np.radians(np.linspace(0.0, 360.0, cols, endpoint=False))
    t, p = np.meshgrid(theta, phi, indexing="ij")
    return np.stack([t.ravel(), p.ravel()], axis=1).ravel()


def lobe_values(model: str, params: dict, angles: np.ndarray, theta_i: float, phi_i: float):
    from lab import reference
    from lab.geometry import direction

    pairs = angles.reshape(-1, 2)
    V = direction(np.degrees(pairs[:, 0]), np.degrees(pairs[:, 1]))
    L = np.repeat(direction(theta_i, phi_i)[None], len(V), axis=0)
    return reference.brdf(model, params, L, V) @ np.array(LUMA)


def test_3d_lobe_peak_in_the_mirror_direction():
    angles = grid_angles()
    values = lobe_values("phong", {"ke": 40.0}, angles, 40.0, 0.0)
    text = dv.lobe3d("phong", values, angles, 40.0, 0.0)
    assert "toward θo 40°, φo 180°, the mirror direction" in text
    assert f"peak of f_r {fmt(values.max())} sr⁻¹" in text
    assert text.endswith(f"at the normal {fmt(values[0])}.")
    lambert = lobe_values("lambert", {}, angles, 40.0, 0.0)
    assert f"peak of f_r {fmt(lambert.max())}" in dv.lobe3d("lambert", lambert, angles, 40, 0)


def test_terms_say_ggx_d_at_the_normal_in_closed_form(renderer):
    from lab.views.terms import microfacet_terms

    alpha = 0.3
    t = microfacet_terms(renderer, "ggx", {"alpha": alpha}, 45.0)
    text = dv.terms("ggx", t.theta, t.D, t.theta_o, t.G, t.F)
    assert text.startswith(f"ggx: D {fmt(1 / (math.pi * alpha**2))} sr⁻¹ at θh 0°")
    f0 = float(np.asarray(t.F)[0] @ np.array(LUMA))
    assert f"F {fmt(f0)} at θd 0°" in text


def test_sh_counts_orders_to_five_per_cent():
    errors = [1.0, 0.4, 0.2, 0.08, 0.04, 0.01]
    assert dv.sh("m", errors, 3) == (
        "m: spherical harmonics to order 3, relative error 8 %; order 0: 100 %; "
        "below 5 % from order 4."
    )
    assert "above 5 % up to order 2" in dv.sh("m", errors[:3], 9)


def image_json(image: np.ndarray) -> dict:
    rgba = np.asarray(image, dtype=np.float64)
    if rgba.shape[-1] == 3:
        rgba = np.concatenate([rgba, np.ones(rgba.shape[:2] + (1,))], axis=-1)
    flat = [v if math.isfinite(v) else str(v) for v in rgba.ravel().tolist()]
    return {"width": rgba.shape[1], "height": rgba.shape[0], "data": flat}


@pytest.mark.skipif(shutil.which("node") is None, reason="needs node")
def test_page_says_the_same_words(tmp_path, renderer):
    """describe_views.js on the same numbers: the same text, to the character."""
    from lab.views.terms import microfacet_terms

    sphere = renderer.sphere("phong", {}, (35.0, 20.0), size=64)
    sick = sphere.copy()
    sick[30:32, 30:40, 0] = np.nan  # non-finite pixels are counted
    obj = renderer.sphere("ggx", {"alpha": 0.2}, (60.0, 200.0), size=48)
    two = sphere + renderer.sphere("phong", {}, (60.0, 200.0), size=64) * 2  # light 2 wins
    thetas = np.arange(0.0, 90.0, 2.5)
    angles = grid_angles(24, 36)
    t = microfacet_terms(renderer, "ggx", {"alpha": 0.25}, 30.0)
    cases = {
        "sphere": [
            (["phong", image_json(sphere), 35.0, 20.0], dv.sphere("phong", sphere, 35.0, 20.0)),
            (["sick", image_json(sick), 35.0, 20.0], dv.sphere("sick", sick, 35.0, 20.0)),
            (
                ["two", image_json(two), 35.0, 20.0, [[60.0, 200.0]]],
                dv.sphere("two", two, 35.0, 20.0, [(60.0, 200.0)]),
            ),
        ],
        "picture": [(["ggx", "lit object", image_json(obj)], dv.picture("ggx", "lit object", obj))],
        "albedo": [
            (
                ["a", thetas.tolist(), (0.9 + 0.4 * (thetas / 90) ** 2).tolist()],
                dv.albedo("a", thetas, 0.9 + 0.4 * (thetas / 90) ** 2),
            ),
        ],
        "slice": [],
        "lobe3d": [],
        "terms": [
            (
                [
                    "ggx",
                    {
                        "theta": t.theta.tolist(),
                        "D": t.D.tolist(),
                        "theta_o": t.theta_o.tolist(),
                        "G": t.G.tolist(),
                        "F": np.asarray(t.F).tolist(),
                    },
                ],
                dv.terms("ggx", t.theta, t.D, t.theta_o, t.G, t.F),
            ),
        ],
        "sh": [(["m", [1.0, 0.3, 0.12, 0.049], 2], dv.sh("m", [1.0, 0.3, 0.12, 0.049], 2))],
    }
    for model, params in [("ggx", {"alpha": 0.2}), ("lambert", {}), ("blinn_phong", {})]:
        image = renderer.slice(model, params, 75.0, 40)
        cases["slice"].append(
            ([model, image_json(image), 75.0], dv.image_slice(model, image, 75.0))
        )
    for model, theta_i, phi_i in [
        ("phong", 40.0, 30.0),
        ("lambert", 20.0, 0.0),
        ("ward", 0.0, 0.0),
    ]:
        values = lobe_values(model, {}, angles, theta_i, phi_i)
        args = [model, values.tolist(), angles.tolist(), theta_i, phi_i, "f_r"]
        cases["lobe3d"].append((args, dv.lobe3d(*args)))
    data = tmp_path / "cases.json"
    data.write_text(json.dumps(cases))
    script = tmp_path / "check.mjs"
    module = (ROOT / "lab/web/static/describe_views.js").as_uri()
    script.write_text(
        f"""import * as d from "{module}";
import {{ readFileSync }} from "node:fs";
const L = {list(LUMA)};
const G = {GRAZING_DEG};
const cases = JSON.parse(readFileSync(process.argv[2], "utf8"));
const image = (j) => ({{ ...j, data: Float64Array.from(j.data, Number) }});
const run = {{
  sphere: ([n, im, t, p, more]) => d.sphere(n, image(im), t, p, L, more),
  picture: ([n, w, im]) => d.picture(n, w, image(im), L),
  albedo: ([n, t, a]) => d.albedo(n, t, a),
  slice: ([n, im, p]) => d.imageSlice(n, image(im), p, L, G),
  lobe3d: ([n, v, a, t, p, w]) => d.lobe3d(n, v, a, t, p, w, G),
  terms: ([n, t]) => d.terms(n, t, L, G),
  sh: ([n, e, o]) => d.sh(n, e, o),
}};
const out = {{}};
for (const [kind, list] of Object.entries(cases)) out[kind] = list.map(([args]) => run[kind](args));
console.log(JSON.stringify(out));
"""
    )
    result = subprocess.run(
        ["node", str(script), str(data)], capture_output=True, text=True, check=True
    )
    js = json.loads(result.stdout)
    for kind, listed in cases.items():
        assert js[kind] == [python for _, python in listed], kind


def from_page(read: dict) -> np.ndarray:
    import base64

    data = np.frombuffer(base64.b64decode(read["data"]), dtype=np.float32)
    return data.reshape(read["height"], read["width"], 4)


@pytest.fixture(scope="module")
def browser(tmp_path_factory):
    from lab.web.browser import chromium, chromium_path
    from lab.web.site import export, serving

    if chromium_path() is None:
        pytest.skip("needs Chromium")
    site = export(tmp_path_factory.mktemp("site")).parent
    with serving(site) as url, chromium() as browser:
        browser.base_url = url
        yield browser


def test_page_views_are_described_by_their_own_numbers(browser):
    """Each view canvas's description (tied by aria-describedby) is describe_views.py's on
    the numbers the page computed; it follows a change once it settles."""
    from tests.axe import VIEWS, open_lab

    page = open_lab(browser, browser.base_url, f"model=ggx&views={VIEWS}", 1300, 900)
    page.wait_for_function("window.brdfLabA11y && window.brdfLabA11y.views")
    names = ("slice", "albedo", "sh", "lobe3d", "terms", "object", "ibl")
    reads = {n: page.evaluate(f"brdfLab.readView(0, '{n}')") for n in names}  # each drawn
    sphere = from_page(page.evaluate("brdfLab.readSphere(0)"))
    page.evaluate("brdfLabA11y.refresh()")
    page.wait_for_function(  # the IBL estimate has its first samples
        "() => [...document.querySelectorAll('.panel canvas[role=img]')]"
        ".every((c) => c.dataset.description)",
        timeout=15000,
    )
    said = page.evaluate(
        """() => Object.fromEntries([...document.querySelectorAll('.panel canvas[role=img]')]
          .map((c) => [c.classList[0], document.getElementById(
            (c.getAttribute('aria-describedby') || '').split(' ').pop())?.textContent || '']))"""
    )
    light = page.evaluate("[brdfLab.state.lights[0].theta, brdfLab.state.lights[0].phi]")
    assert said["sphere"] == dv.sphere("ggx", sphere, *light)
    assert said["slice"] == dv.image_slice("ggx", from_page(reads["slice"]), 90.0)
    albedo = np.max(reads["albedo"]["rgb"], axis=1)
    assert said["albedo"] == dv.albedo("ggx", reads["albedo"]["thetas"], albedo)
    assert said["sh"].startswith("ggx: spherical harmonics to order 8, relative error")
    for name in ("lobe3d", "terms", "object", "ibl"):
        assert said[name].startswith(("ggx", "lit object of ggx", "image-based lighting of ggx")), (
            name,
            said,
        )
    assert "the mirror direction" in said["lobe3d"]
    # A change: the light moves; once it settles the words follow.
    page.locator("#light-theta").focus()
    for _ in range(10):
        page.keyboard.press("ArrowRight")
    now = page.evaluate("brdfLab.state.lights[0].theta")
    assert now != light[0]
    page.wait_for_function(
        "t => document.querySelector('canvas.lobe3d').dataset.description.includes(`θi ${t}°`)",
        arg=round(now),
        timeout=10000,
    )
    page.close()


def test_with_several_lights_the_nearest_halfway_vector_is_named(renderer):
    from lab.render import Light

    lights = [Light(30.0, 0.0), Light(50.0, 180.0)]
    image = renderer.sphere("phong", {"ke": 60.0}, (30.0, 0.0), size=128, lights=lights)
    text = dv.sphere("phong", image, 30.0, 0.0, [(50.0, 180.0)])
    assert text.startswith("phong on a sphere, 2 lights, light 1 at θi 30°, φi 0°: brightest")
    m = re.search(r"normal is (\d+)° from the halfway vector of light (\d) and (\d+)°", text)
    assert m and int(m[1]) <= 2 and int(m[3]) == pytest.approx(25 if m[2] == "2" else 15, abs=2)

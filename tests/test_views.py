"""What each view shows: highlight positions, lobe peaks, slices, the mirror's environment."""

from __future__ import annotations

import numpy as np
import pytest

from lab.plots import luminance
from lab.render import Light, direction

SIZE = 256


def pixel_to_normal(row: float, col: float, size: int = SIZE) -> np.ndarray:
    x = (col + 0.5) / size * 2 - 1
    y = 1 - (row + 0.5) / size * 2
    return np.array([x, y, np.sqrt(max(0.0, 1 - x * x - y * y))])


@pytest.mark.parametrize(
    "name, values",
    [("phong", {"ke": 200.0}), ("blinn_phong", {"ke": 800.0}), ("ggx", {"alpha": 0.05})],
)
@pytest.mark.parametrize("light", [(40.0, 0.0), (60.0, 135.0), (20.0, 270.0)])
def test_highlight_sits_where_the_mirror_direction_says(renderer, name, values, light):
    """The brightest pixel's normal bisects the light and the view direction."""
    values = {**values, "kd": (0.0,) * 3}
    image = renderer.sphere(name, values, light, size=SIZE, multiply_cos=False)
    row, col = np.unravel_index(luminance(image[..., :3]).argmax(), (SIZE, SIZE))
    expected = direction(*light) + np.array([0.0, 0.0, 1.0])
    expected /= np.linalg.norm(expected)
    angle = np.degrees(np.arccos(np.clip(pixel_to_normal(row, col) @ expected, -1, 1)))
    assert angle < 1.5


def test_sphere_background_and_cosine(renderer):
    image = renderer.sphere("lambert", {"albedo": (0.6, 0.6, 0.6)}, (0.0, 0.0), size=SIZE)
    assert image[0, 0, 3] == 0 and image[SIZE // 2, SIZE // 2, 3] == 1
    # Lit from the eye, Lambert's radiance is albedo / pi * cos(theta): darker toward the rim.
    centre = image[SIZE // 2, SIZE // 2, 0]
    assert centre == pytest.approx(0.6 / np.pi, rel=1e-3)
    normal = pixel_to_normal(SIZE // 2, SIZE - 20)
    assert image[SIZE // 2, SIZE - 20, 0] == pytest.approx(0.6 / np.pi * normal[2], rel=1e-2)
    flat = renderer.sphere(
        "lambert", {"albedo": (0.6, 0.6, 0.6)}, (0.0, 0.0), size=SIZE, multiply_cos=False
    )
    assert flat[SIZE // 2, SIZE - 20, 0] == pytest.approx(0.6 / np.pi, rel=1e-3)


def test_several_lights_and_ambient_add_up(renderer):
    """The Phong illumination model: ka L_a + a sum over lights (the render is linear)."""
    a, b = Light(30.0, 0.0, (1.0, 0.5, 0.2)), Light(50.0, 200.0, (0.2, 0.4, 1.0))
    ambient = np.array([0.5, 0.6, 0.7])
    values = {"ke": 20.0, "ka": (0.2, 0.1, 0.4)}
    both = renderer.sphere("phong_illumination", values, lights=[a, b], ambient=ambient, size=SIZE)
    one = renderer.sphere("phong_illumination", values, lights=[a], size=SIZE)
    two = renderer.sphere("phong_illumination", values, lights=[b], size=SIZE)
    inside = both[..., 3] > 0
    expected = (one + two)[inside, :3] + ambient * values["ka"]
    np.testing.assert_allclose(both[inside, :3], expected, atol=1e-5)


def test_slide_form_of_the_phong_illumination_model(renderer):
    """Each pixel is ka L_a + sum_l L_l (kd (N.L_l) + ks (R_l.V)^ke), computed here by hand."""
    lights = [Light(35.0, 10.0, (1.0, 0.8, 0.6)), Light(60.0, 220.0, (0.3, 0.5, 1.0))]
    ka, kd, ks, ke = np.array([0.1, 0.2, 0.3]), np.array([0.4, 0.3, 0.2]), 0.6, 12.0
    La = np.array([0.3, 0.3, 0.3])
    values = {"ka": tuple(ka), "kd": tuple(kd), "ks": (ks,) * 3, "ke": ke}
    image = renderer.sphere("phong_illumination", values, lights=lights, ambient=La, size=SIZE)
    V = np.array([0.0, 0.0, 1.0])
    for row, col in ((SIZE // 2, SIZE // 2), (70, 150), (180, 60)):
        N = pixel_to_normal(row, col)
        expected = ka * La
        for light in lights:
            L = direction(light.theta, light.phi)
            if N @ L > 0:
                R = 2 * (N @ L) * N - L
                expected = expected + np.array(light.rgb) * (
                    kd * (N @ L) + ks * max(R @ V, 0.0) ** ke
                )
        np.testing.assert_allclose(image[row, col, :3], expected, rtol=1e-3)


def test_phong_illumination_specular_has_no_cosine(renderer):
    """The slide's specular term ks (R.V)^ke appears in the render without N.L."""
    values = {"kd": (0.0,) * 3, "ks": (1.0,) * 3, "ke": 1.0}
    image = renderer.sphere("phong_illumination", values, (60.0, 0.0), size=SIZE)
    L = direction(60.0, 0.0)
    for row, col in ((SIZE // 2, SIZE // 2), (90, 180), (200, 150)):
        N = pixel_to_normal(row, col)
        R = 2 * (N @ L) * N - L
        assert image[row, col, 0] == pytest.approx(max(R[2], 0.0), rel=1e-3)


def test_mirror_reflects_the_environment(renderer):
    image = renderer.sphere("mirror", {"rho_s": (1.0, 1.0, 1.0)}, size=SIZE)
    top, bottom = image[20, SIZE // 2, :3], image[SIZE - 20, SIZE // 2, :3]
    assert top[2] > top[0]  # upper half reflects the blue sky
    floor_row = image[SIZE - 30, SIZE // 4 : 3 * SIZE // 4, 0]  # the checkered floor
    assert floor_row.max() > 2 * floor_row.min()
    assert bottom.max() < 1.0
    half = renderer.sphere("mirror", {"rho_s": (0.5, 0.5, 0.5)}, size=SIZE)
    np.testing.assert_allclose(half[..., :3], 0.5 * image[..., :3], rtol=1e-5, atol=1e-7)


def test_phong_polar_lobe_peaks_at_the_mirror_angle(renderer):
    for theta_i in (20.0, 45.0, 70.0):
        lobe = renderer.polar("phong", {"kd": (0.0,) * 3, "ke": 50.0}, theta_i)
        assert lobe.theta_o[luminance(lobe.values).argmax()] == theta_i


def test_cook_torrance_has_an_off_specular_peak(renderer):
    """At grazing incidence f_r cos(theta_o) of Cook-Torrance peaks beyond the mirror angle."""
    theta_i = 70.0
    values = {"kd": (0.0,) * 3, "m": 0.35}
    lobe = renderer.polar("cook_torrance", values, theta_i, cos_weighted=True)
    peak = lobe.theta_o[luminance(lobe.values).argmax()]
    assert peak > theta_i + 5
    phong = renderer.polar("phong", {"kd": (0.0,) * 3, "ke": 20.0}, theta_i, cos_weighted=False)
    assert phong.theta_o[luminance(phong.values).argmax()] == theta_i


def test_polar_marks_the_delta_spike(renderer):
    lobe = renderer.polar("mirror", {"rho_s": (0.7, 0.7, 0.7)}, 30.0)
    assert (lobe.values == 0).all()
    np.testing.assert_allclose(lobe.spike, (0.7, 0.7, 0.7), rtol=1e-6)


def test_slice_of_blinn_phong_depends_on_theta_h_only(renderer):
    image = renderer.slice("blinn_phong", {"kd": (0.0,) * 3, "ke": 10.0}, phi_d=90.0, size=64)
    # Rows are theta_d (top = 90 deg); at phi_d = 90 deg both directions stay above the horizon.
    rows = image[8:56, :, 0]
    np.testing.assert_allclose(rows, np.broadcast_to(rows[-1], rows.shape), rtol=1e-4)
    theta_h = (np.arange(64) + 0.5) / 64 * 90.0
    np.testing.assert_allclose(rows[-1], 0.5 * np.cos(np.radians(theta_h)) ** 10, rtol=1e-3)


def test_lobe3d_matches_probe(renderer):
    theta_o, phi_o, f = renderer.lobe3d("ward", {"alpha_x": 0.1, "alpha_y": 0.3}, 30.0, 0.0)
    assert f.shape == (len(theta_o), len(phi_o), 3)
    i, j = 20, 40
    direct = renderer.eval_angles(
        "ward", {"alpha_x": 0.1, "alpha_y": 0.3}, [[30.0, 0.0, theta_o[i], phi_o[j]]]
    )
    np.testing.assert_allclose(f[i, j], direct[0], rtol=1e-5)


def test_softpipe_renders_like_llvmpipe(renderer, tmp_path):
    """A second, independent rasterizer gives the same sphere (to float rounding)."""
    import os
    import subprocess
    import sys

    script = (
        "import numpy as np, sys; from lab.render import Renderer; from lab.gl import describe;"
        "r = Renderer(); print(describe(r.ctx));"
        "np.save(sys.argv[1], r.sphere('cook_torrance', {'m': 0.2}, (40.0, 30.0), size=128))"
    )
    out = tmp_path / "softpipe.npy"
    env = {**os.environ, "GALLIUM_DRIVER": "softpipe"}
    result = subprocess.run(
        [sys.executable, "-c", script, str(out)],
        env=env,
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert result.returncode == 0, result.stderr
    assert "softpipe" in result.stdout
    theirs = np.load(out)
    ours = renderer.sphere("cook_torrance", {"m": 0.2}, (40.0, 30.0), size=128)
    np.testing.assert_allclose(theirs, ours, rtol=1e-3, atol=1e-5)

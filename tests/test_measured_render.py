"""The `measured` model on the GPU: tabulate -> file -> texture agrees with the analytic model."""

from __future__ import annotations

import math

import numpy as np
import pytest

from lab.measured import merl
from lab.measured.merl import read_merl, write_merl
from lab.measured.model import measured_model
from lab.measured.tabulate import tabulate

GGX = {"kd": (0.2, 0.1, 0.05), "ks": (0.8, 0.8, 0.8), "alpha": 0.3}


def random_pairs(n: int, seed: int = 0, max_theta: float = 80.0):
    rng = np.random.default_rng(seed)
    theta = np.radians(rng.uniform(0, max_theta, (n, 2)))
    phi = rng.uniform(0, 2 * math.pi, (n, 2))
    dirs = np.stack([np.sin(theta) * np.cos(phi), np.sin(theta) * np.sin(phi), np.cos(theta)], -1)
    return dirs[:, 0], dirs[:, 1]


@pytest.fixture(scope="module")
def full_table(renderer, tmp_path_factory):
    """A full-size (90 x 90 x 180) table of GGX, written and read back."""
    path = tmp_path_factory.mktemp("merl") / "ggx.binary"
    write_merl(tabulate("ggx", GGX, renderer=renderer), path)
    return read_merl(path)


def test_full_size_round_trip_nearest_and_linear(renderer, full_table, gl_clean):
    assert full_table.dims == merl.MERL_DIMS
    L, V = random_pairs(4000)
    model = measured_model(full_table)
    analytic = renderer.probe("ggx", GGX, L, V).astype(np.float64)
    # Nearest must return the analytic value at the centre of the bin that holds (L, V);
    # points within 1 % of a bin edge are left out (float32 may put them either side).
    coords = np.stack(merl.continuous_index(*merl.half_diff(L, V)))
    inside = (np.abs(coords - np.round(coords)) > 0.01).all(axis=0)
    h, d, p = merl.bin_index(*merl.half_diff(L, V))
    centres = merl.bin_centres()
    Lc, Vc = merl.directions(centres[0][h], centres[1][d], centres[2][p])
    at_centre = renderer.probe("ggx", GGX, Lc, Vc).astype(np.float64)
    nearest = renderer.probe(model, {"interpolation": "nearest"}, L, V).astype(np.float64)
    assert np.allclose(nearest[inside], at_centre[inside], rtol=1e-3, atol=1e-5)
    # Binning error: nearest is off by up to half a bin; linear is much closer.
    linear = renderer.probe(model, {"interpolation": "linear"}, L, V).astype(np.float64)
    err_nearest = np.abs(nearest - analytic) / analytic
    err_linear = np.abs(linear - analytic) / analytic
    assert np.median(err_nearest) < 0.01 and np.percentile(err_nearest, 99) < 0.06
    assert np.median(err_linear) < 0.001 and np.percentile(err_linear, 99) < 0.01
    assert np.mean(err_linear) < 0.2 * np.mean(err_nearest)
    # The shader's lookup is the numpy one; bins along an edge may differ in float32.
    peak = analytic.max()
    for kind, gpu in (("nearest", nearest), ("linear", linear)):
        cpu = merl.lookup(full_table, L, V, kind)
        close = np.abs(gpu - cpu) < 0.01 * np.maximum(cpu, 0.05 * peak)
        assert close.mean() > 0.995, kind
    # Linear weighs its 8 texel fetches in float (no texture filter's 1/256 steps).
    cpu = merl.lookup(full_table, L, V, "linear")
    rel = np.abs(linear - cpu) / np.maximum(cpu, 1e-3 * peak)
    assert np.median(rel) < 1e-5 and np.percentile(rel, 99) < 1e-3


def test_measured_sphere_matches_analytic_sphere(renderer, full_table, gl_clean):
    model = measured_model(full_table)
    measured = renderer.sphere(model, {}, (30.0, 20.0), size=128)
    analytic = renderer.sphere("ggx", GGX, (30.0, 20.0), size=128)
    lit = analytic[..., :3].sum(-1) > 1e-3
    rel = np.abs(measured[..., :3] - analytic[..., :3])[lit] / analytic[..., :3][lit]
    assert np.median(rel) < 0.01 and np.mean(measured[..., 3] == analytic[..., 3]) == 1.0
    # Other models still render as before once the table's texture unit is in use.
    again = renderer.sphere("ggx", GGX, (30.0, 20.0), size=128)
    assert np.array_equal(again, analytic)
    # gain scales the table.
    doubled = renderer.sphere(model, {"gain": 2.0}, (30.0, 20.0), size=128)
    assert np.allclose(doubled[..., :3], 2 * measured[..., :3], rtol=1e-5, atol=1e-7)


def test_measured_model_in_every_view(renderer, full_table, gl_clean):
    model = measured_model(full_table)
    polar = renderer.polar(model, {}, 45.0)
    reference = renderer.polar("ggx", GGX, 45.0)
    inner = np.abs(polar.theta_o) <= 80
    assert np.allclose(polar.values[inner], reference.values[inner], rtol=0.02, atol=1e-4)
    image = renderer.slice(model, {}, phi_d=90.0, size=64)
    truth = renderer.slice("ggx", GGX, phi_d=90.0, size=64)
    assert np.median(np.abs(image - truth)[truth > 1e-3] / truth[truth > 1e-3]) < 0.01
    albedo = renderer.albedo(model, {}, [0.0, 30.0, 60.0], samples=64, wedges=16)
    truth = renderer.albedo("ggx", GGX, [0.0, 30.0, 60.0], samples=64, wedges=16)
    assert np.allclose(albedo, truth, rtol=0.03)


def test_tabulate_noise_is_relative(renderer):
    clean = tabulate("lambert", {}, dims=(8, 8, 16), renderer=renderer)
    noisy = tabulate("lambert", {}, dims=(8, 8, 16), noise=0.05, seed=3, renderer=renderer)
    mask = clean.rgb > 0
    ratio = noisy.rgb[mask] / clean.rgb[mask]
    assert abs(ratio.std() - 0.05) < 0.01 and abs(ratio.mean() - 1) < 0.01


@pytest.mark.parametrize("seed", [0, 11])
def test_the_tabulate_view_makes_tabulates_table(renderer, seed):
    """shaders/views/tabulate.glsl (the web page's table, static/tables.js) draws what
    tabulate makes, layer by layer: the same noise to float32 rounding (the hash and its
    float steps are the numpy twin's) on the model's values at the bin centres."""
    from lab.models import load_model

    dims = (12, 10, 16)
    values = {"alpha": 0.3, "kd": (0.1, 0.2, 0.3)}
    want = tabulate("ggx", values, dims=dims, noise=0.05, seed=seed, renderer=renderer).rgb
    smooth = tabulate("ggx", values, dims=dims, renderer=renderer).rgb
    model = load_model("ggx")
    for layer in (0, 5, 11):
        uniforms = {"u_dims": dims, "u_layer": layer, "u_noise": 0.05, "u_seed": seed}
        fbo = renderer._run(model, "tabulate", values, (dims[2], dims[1]), uniforms)
        got = renderer._read(fbo)[..., :3]
        assert np.allclose(got, want[layer], rtol=2e-5, atol=1e-7), layer
        lit = smooth[layer] > 1e-3  # and the noise is there: 5 % of the smooth values
        assert 0.02 < np.std(got[lit] / smooth[layer][lit]) < 0.08


def test_lookup_near_the_specular_peak(renderer, gl_clean):
    """theta_h of a few 1e-4 rad must land in bins 0-1, as float64 numpy puts it."""
    table = merl.MerlTable.from_rgb(
        np.broadcast_to(np.arange(90.0)[:, None, None, None] + 1.0, (90, 90, 180, 3))
    )
    model = measured_model(table)
    theta_h = np.array([0.0, 2e-4, 6e-4, 1.5e-3, 4e-3])
    L, V = merl.directions(theta_h, np.full(5, 0.5), np.full(5, 1.0))
    got = renderer.probe(model, {"interpolation": "nearest"}, L, V)[:, 0]
    expected = merl.lookup(table, L, V, "nearest")[:, 0]
    assert np.allclose(got, expected) and list(expected) == [1.0, 2.0, 2.0, 3.0, 5.0]


def test_render_measured_offers_every_plot_view(renderer, tmp_path, capsys):
    """`render-measured --view` takes every view with a PNG (the registry's list, not one of
    its own); the D, G, F view, which a table has not, says what to do instead."""
    from PIL import Image

    from lab.cli import main
    from lab.views import plot_views

    table = write_merl(
        tabulate("ggx", GGX, dims=(30, 30, 60), renderer=renderer), tmp_path / "t.binary"
    )
    for view in plot_views():
        out = tmp_path / f"{view}.png"
        code = main(["render-measured", str(table), "--view", view, "--size", "64", "-o", str(out)])
        err = capsys.readouterr().err.strip()
        if view == "terms":
            assert code == 2 and err.count("\n") == 0, err
            assert "t.binary" in err and "brdf-lab fit" in err and "MICROFACET_TERMS" not in err
            continue
        assert code == 0, (view, err)
        pixels = np.asarray(Image.open(out).convert("L"), dtype=np.float64)
        assert pixels.std() > 5, view  # a picture, not a blank image

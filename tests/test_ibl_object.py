"""Environment lighting of the lab's object (shaders/views/ibl_object.glsl): the object
view's shapes under a map by Monte Carlo, like the sphere (lab/ibl)."""

from __future__ import annotations

import numpy as np
import pytest
from PIL import Image

from lab.constants import LUMA
from lab.ibl.integrator import SHAPES, Environment, IBLRenderer, render
from lab.models import load_model

OBJECTS = [s for s in SHAPES if s != "sphere"]


@pytest.fixture(scope="module")
def ibl(ctx):
    return IBLRenderer(ctx)


def luminance(image: np.ndarray) -> np.ndarray:
    return image[..., :3] @ np.array(LUMA)


@pytest.mark.parametrize("shape", OBJECTS)
def test_lambert_object_in_the_furnace_is_its_albedo_everywhere(ibl, shape):
    """White furnace, cosine-weighted samples of a Lambertian surface: f cos / p = albedo
    for every sample, so every pixel of the object equals the albedo, whatever its normal
    and however few the samples."""
    image = render(
        "lambert", {"albedo": (0.6, 0.4, 0.2)}, "furnace", "brdf", 4, 96, renderer=ibl, shape=shape
    )
    lit = image[..., 3] > 0.5
    assert lit.mean() > 0.1
    np.testing.assert_allclose(
        image[lit][:, :3], np.broadcast_to([0.6, 0.4, 0.2], (lit.sum(), 3)), rtol=1e-4
    )


def test_glossy_object_in_the_furnace_reflects_at_most_the_light(ibl):
    """GGX conserves energy: no part of a white metal torus reflects more than the furnace
    sends (single scattering loses a little at grazing angles, never gains)."""
    metal = {"alpha": 0.3, "kd": (0.0, 0.0, 0.0), "f0": (1.0, 1.0, 1.0)}
    image = render("ggx", metal, "furnace", "mis_power", 256, 64, renderer=ibl, shape="torus")
    lum = luminance(image)[image[..., 3] > 0.5]
    assert np.percentile(lum, 99) <= 1.01 and lum.mean() > 0.8


def test_strategies_agree_on_the_object(ibl):
    """Under the sky, uniform and MIS sampling converge to the same rounded box (mean within
    2%), and MIS with far less noise."""
    env = Environment.load("sky", (256, 128))
    values = {"alpha": 0.3}
    mis = render("ggx", values, env, "mis_power", 512, 48, renderer=ibl, shape="rounded box")
    uniform = render("ggx", values, env, "uniform", 4096, 48, renderer=ibl, shape="rounded box")
    lit = mis[..., 3] > 0.5
    assert luminance(uniform)[lit].mean() == pytest.approx(luminance(mis)[lit].mean(), rel=0.02)


@pytest.mark.parametrize("shape", OBJECTS)
def test_silhouette_matches_the_object_view(ctx, ibl, shape):
    """views/ibl_object.glsl mirrors views/object.glsl's geometry: the same pixels covered."""
    from lab.app.renderer import AppRenderer
    from lab.render import Light

    index = SHAPES.index(shape)
    model = load_model("lambert")
    theirs = AppRenderer(ctx).object(
        model, {}, [Light(45.0, 0.0)], shape=index, yaw=0.6, pitch=0.5, size=96
    )
    mine = render(model, {}, "grey_room", "cosine", 1, 96, renderer=ibl, shape=shape)
    covered_theirs, covered_mine = theirs[..., 3] > 0.5, mine[..., 3] > 0.5
    assert (covered_theirs != covered_mine).mean() < 0.002, shape


def test_render_command_lights_a_shape(tmp_path, capsys):
    from lab.cli import main

    out = tmp_path / "torus.png"
    args = ["render", "ggx", "--view", "ibl", "--shape", "torus", "--samples", "8"]
    assert main([*args, "--size", "64", "-o", str(out)]) == 0
    assert "the torus" in capsys.readouterr().out
    with Image.open(out) as image:
        assert image.size == (64, 64)
    assert main(["render", "ggx", "--view", "ibl", "--shape", "cube", "-o", str(out)]) == 2
    assert "--shape 'cube': use one of 'torus'" in capsys.readouterr().err

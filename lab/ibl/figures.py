"""The lecture's IBL figures: equal samples, two strategies; the white furnace."""

from __future__ import annotations

from pathlib import Path

import moderngl

from lab import plots
from lab.ibl.integrator import Environment, IBLRenderer, render

SIZE, SAMPLES = 192, 32
GLOSSY = ("ggx", {"alpha": 0.1})


def ibl_figures(outdir: Path, ctx: moderngl.Context) -> list[Path]:
    """Uniform vs MIS at equal samples under the sky, and unnormalised Phong in the furnace."""
    renderer = IBLRenderer(ctx)
    sky = Environment.load("sky")
    paths = []
    for strategy in ("uniform", "mis_power"):
        image = render(*GLOSSY, sky, strategy, SAMPLES, SIZE, renderer=renderer)
        paths.append(outdir / f"ibl_{strategy}.png")
        plots.save_image(image[..., :3], paths[-1])
    furnace = Environment.load("furnace")
    for name, values in (
        ("ggx", {"alpha": 0.3, "kd": (0.0,) * 3, "f0": (1.0,) * 3}),
        ("phong", {"kd": (0.5,) * 3, "ks": (1.0,) * 3, "ke": 1.0}),
    ):
        image = render(name, values, furnace, "brdf", SAMPLES, SIZE, renderer=renderer)
        paths.append(outdir / f"ibl_furnace_{name}.png")
        plots.save_image(image[..., :3], paths[-1], exposure=-1.0)  # 1 shows as mid-grey
    return paths

"""Retroreflection: f_r(ω, ω) against θ, light and eye together (a test-only view)."""

from __future__ import annotations

import numpy as np

from lab.constants import LUMA
from lab.views import PlotJob, Setting, ViewSpec

THETAS = np.arange(0.0, 90.0, 1.0)


def retro_values(renderer, model, values, phi: float) -> np.ndarray:
    """Luminance of f_r with V = L at each θ of THETAS."""
    angles = np.column_stack([THETAS, np.full_like(THETAS, phi), THETAS, np.full_like(THETAS, phi)])
    rgb = np.asarray(renderer.eval_angles(model, values, angles), dtype=np.float64)
    return rgb @ np.array(LUMA)


def plot(job: PlotJob) -> None:
    """One white column per degree, as tall as f_r relative to the view's own scale."""
    from PIL import Image

    lum = retro_values(job.renderer, job.model, job.values, job.phi_i)
    height = 100
    image = np.zeros((height, len(THETAS)), dtype=np.uint8)
    tops = np.round(height * lum / max(lum.max(), 1e-12)).astype(int)
    for column, top in enumerate(tops):
        image[height - top :, column] = 255
    Image.fromarray(image, "L").save(job.out)


VIEW = ViewSpec(
    name="retro",
    title="Retroreflection",
    settings={"retro_gain": Setting(1.0, 0.5, 4.0, "gain", 0.5)},
    dock=("bottom", 1),
    widget="extra_views.retro_widget:RetroView",
    plot=plot,
    order=90,
)

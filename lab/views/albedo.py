"""Directional albedo against θi, energy gain flagged (shaders/views/albedo.glsl)."""

from __future__ import annotations

import numpy as np

from lab import plots
from lab.views import PlotJob, ViewSpec


def plot(job: PlotJob) -> None:
    """The albedo's R, G and B against θi, with the albedo = 1 line and any gain above it."""
    fig, ax = plots.figure()
    thetas = np.arange(0.0, 90.0, 1.0)
    a = job.renderer.albedo(job.model, job.values, thetas, job.phi_i)
    for channel, color in enumerate(("tab:red", "tab:green", "tab:blue")):
        ax.plot(thetas, a[:, channel], color=color, label="RGB"[channel])
    ax.axhline(1.0, color="black", lw=1, ls="--", label="albedo = 1")
    gain = a.max(axis=1) > 1.0
    if gain.any():
        ax.fill_between(
            thetas,
            1.0,
            a.max(axis=1),
            where=gain,
            color="red",
            alpha=0.2,
            label="energy gain (not physical)",
        )
    ax.set_xlabel("θi (degrees)")
    ax.set_ylabel("directional albedo")
    ax.set_ylim(0, max(1.1, float(a.max()) * 1.05))
    ax.legend(fontsize=8)
    ax.set_title(f"{job.model.name}: directional albedo", fontsize=10)
    plots.save_figure(fig, job.out, job.size)


# The albedo's quality, the app's and the page's: θi from `theta0` in `count` steps of `step`
# degrees, `samples` along each of `wedges` wedges around the mirror direction
# (shaders/views/albedo.glsl); FAST while a slider or the light moves.
FULL = {"theta0": 0.0, "step": 2.5, "count": 36, "samples": 192, "wedges": 48}
FAST = {"theta0": 0.0, "step": 85.0 / 8.0, "count": 9, "samples": 32, "wedges": 16}


def thetas(quality: dict) -> np.ndarray:
    """The θi (degrees) a quality samples."""
    return quality["theta0"] + quality["step"] * np.arange(quality["count"])


VIEW = ViewSpec(
    name="albedo",
    title="Directional albedo",
    dock=("bottom", 0),
    size=(0.31, 0.3),
    short_title="Albedo",
    widget="lab.app.views.albedo:AlbedoView",
    plot=plot,
    order=60,
    page_data={"full": FULL, "fast": FAST},
)

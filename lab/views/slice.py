"""The (θh, θd) image slice of BRDF Explorer (shaders/views/slice.glsl)."""

from __future__ import annotations

import numpy as np

from lab import plots
from lab.views import PlotJob, Setting, ViewSpec


def plot(job: PlotJob) -> None:
    """log10 f_r over (θh, θd) at φd = the light's φ (90° when it is 0)."""
    phi_d = job.phi_i if job.phi_i else 90.0
    fig, ax = plots.figure()
    rgb = job.renderer.slice(job.model, job.values, phi_d=phi_d, size=min(job.size, 512))
    image = plots.luminance(rgb.astype(np.float64))
    shown = ax.imshow(
        np.log10(np.maximum(image, 1e-4)), extent=(0, 90, 0, 90), cmap="magma", aspect="equal"
    )
    fig.colorbar(shown, label="log10 f_r")
    ax.set_xlabel("θh (degrees)")
    ax.set_ylabel("θd (degrees)")
    ax.set_title(f"{job.model.name}: image slice at φd = {phi_d:g}°", fontsize=10)
    plots.save_figure(fig, job.out, job.size)


VIEW = ViewSpec(
    name="slice",
    title="Image slice (θh, θd)",
    settings={"phi_d": Setting(90.0, 0.0, 180.0, "φd", 1.0)},
    dock=("bottom", 0),
    size=(0.34, 0.3),
    short_title="Slice θh θd",
    widget="lab.app.views.slice:SliceView",
    plot=plot,
    order=50,
)

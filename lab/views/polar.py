"""The lobe in the plane of incidence, f_r against θo (shaders/views/polar.glsl)."""

from __future__ import annotations

from lab import plots
from lab.views import PlotJob, Setting, ViewSpec


def plot(job: PlotJob) -> None:
    """The model's lobe on the polar half-disc, light on the right."""
    fig, ax = plots.figure(polar=True)
    lobe = job.renderer.polar(job.model, job.values, job.theta_i, job.phi_i)
    plots.draw_polar(ax, [(lobe, job.model.name, None)], job.theta_i, "f_r (luminance)")
    plots.save_figure(fig, job.out, job.size)


VIEW = ViewSpec(
    name="polar",
    title="Polar plot",
    settings={  # the 3D lobe reads these two as well
        "polar_log": Setting(False, label="log scale"),
        "polar_cos": Setting(False, label="f_r · cos θo"),
        # The plot's plane turned about the normal, out of the plane of incidence (the web
        # page's; the desktop plots the plane of incidence).
        "phi_o": Setting(
            0.0,
            0.0,
            180.0,
            "φo",
            1.0,
            unit="°",
            doc="φo: turn the polar plot's plane about the normal, out of the plane of incidence "
            "(0° = the plane of incidence)",
        ),
    },
    dock=("right", 1),
    size=(0.33, 0.42),
    short_title="Polar",
    widget="lab.app.views.polar:PolarView",
    plot=plot,
    order=20,
)

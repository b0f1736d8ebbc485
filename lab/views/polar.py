"""The lobe in the plane of incidence, f_r against θo (shaders/views/polar.glsl)."""

from __future__ import annotations

from lab.views import Setting, ViewSpec
from lab.views._plots import matplotlib_plot

VIEW = ViewSpec(
    name="polar",
    title="Polar plot",
    settings={  # the 3D lobe reads these two as well
        "polar_log": Setting(False, label="log scale"),
        "polar_cos": Setting(False, label="f_r · cos θo"),
    },
    dock=("right", 1),
    widget="lab.app.views.polar:PolarView",
    plot=matplotlib_plot("polar"),
    order=20,
)

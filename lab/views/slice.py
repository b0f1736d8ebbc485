"""The (θh, θd) image slice of BRDF Explorer (shaders/views/slice.glsl)."""

from __future__ import annotations

from lab.views import Setting, ViewSpec
from lab.views._plots import matplotlib_plot

VIEW = ViewSpec(
    name="slice",
    title="Image slice (θh, θd)",
    settings={"phi_d": Setting(90.0, 0.0, 180.0, "φd", 1.0)},
    dock=("bottom", 0),
    widget="lab.app.views.slice:SliceView",
    plot=matplotlib_plot("slice"),
    order=50,
)

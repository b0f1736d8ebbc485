"""The (θh, θd) image slice of BRDF Explorer (shaders/views/slice.glsl)."""

from __future__ import annotations

from lab.views import Setting, ViewSpec, plot_with_matplotlib

VIEW = ViewSpec(
    name="slice",
    title="Image slice (θh, θd)",
    settings={"phi_d": Setting(90.0, 0.0, 180.0, "φd", 1.0)},
    dock=("bottom", 0),
    widget="lab.app.views:SliceView",
    plot=plot_with_matplotlib("slice"),
    order=50,
)

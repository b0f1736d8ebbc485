"""The 3D lobe: f_r over the hemisphere as a surface drawn by the model's own GLSL
(shaders/views/lobe_mesh*.glsl)."""

from __future__ import annotations

from lab.views import PlotJob, Setting, ViewSpec


def plot(job: PlotJob) -> None:
    from lab.plots import save_lobe3d

    save_lobe3d(
        job.renderer,
        job.model,
        job.values,
        job.theta_i,
        job.phi_i,
        job.out,
        width=max(job.size, 320),
    )


VIEW = ViewSpec(
    name="lobe3d",
    title="3D lobe",
    settings={
        "lobe_yaw": Setting(-0.6, label="yaw"),
        "lobe_pitch": Setting(0.35, -1.5, 1.5, "pitch"),
        "lobe_zoom": Setting(1.0, 0.2, 8.0, "zoom"),
    },
    dock=("right", 1),
    widget="lab.app.views:LobeView",
    plot=plot,
    order=30,
)

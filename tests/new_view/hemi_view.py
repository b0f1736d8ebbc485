"""f_r over the hemisphere of view directions for the light (a view added by a test)."""

from __future__ import annotations

from lab.views import PlotJob, Setting, ViewSpec


def image(renderer, model, values, theta_i: float, phi_i: float, size: int, gain: float = 1.0):
    """(size, size, 4): f_r(L, V) times `gain` at each V of the disc seen from above."""
    from lab.render import direction

    uniforms = {
        "u_resolution": (float(size), float(size)),
        "u_light": tuple(float(c) for c in direction(theta_i, phi_i)),
        "u_gain": gain,
    }
    return renderer.image(model, "hemi", values, size, uniforms)


def plot(job: PlotJob) -> None:
    from lab.plots import save_image

    save_image(image(job.renderer, job.model, job.values, job.theta_i, job.phi_i, 64), job.out)


VIEW = ViewSpec(
    name="hemi",
    title="Hemisphere of f_r",
    settings={
        "hemi_gain": Setting(1.0, 0.5, 4.0, "gain", 0.5, doc="gain: f_r is shown times this")
    },
    dock=("bottom", 1),
    widget="lab.app.views.hemi:HemiView",
    plot=plot,
    order=95,
)

"""Lit spheres: each model on a sphere under the light(s) (shaders/views/sphere.glsl)."""

from __future__ import annotations

from lab.views import PlotJob, Setting, ViewSpec


def plot(job: PlotJob) -> None:
    from lab.plots import save_image

    image = job.renderer.sphere(
        job.model,
        job.values,
        (job.theta_i, job.phi_i),
        size=job.size,
        lights=job.lights,
        ambient=job.ambient,
    )
    save_image(image, job.out, job.exposure)
    from lab.nonfinite import sphere_report
    from lab.render import direction

    problem = sphere_report(image, direction(job.theta_i, job.phi_i))
    if problem:
        job.warnings.append(problem)


VIEW = ViewSpec(
    name="sphere",
    title="Lit spheres",
    settings={
        "exposure": Setting(0.0, -8.0, 8.0, "exposure", 0.1),
        "gamma": Setting(2.2, 1.0, 3.0, "gamma", 0.1),
        "multiply_cos": Setting(True, label="× N·L"),
    },
    dock=("right", 0),
    size=(1.0, 0.28),
    short_title="Spheres",
    widget="lab.app.views.sphere:SphereView",
    plot=plot,
    order=10,
)

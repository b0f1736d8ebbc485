"""Image-based lighting: the sphere under an environment, the reflection equation by
progressive Monte Carlo on the GPU (lab/ibl, shaders/views/ibl.glsl)."""

from __future__ import annotations

from lab.views import PlotJob, Setting, ViewSpec
from lab.views.object import SHAPES

# Kept here (not imported from lab.ibl) so the registry stays light; tests tie them.
ENVIRONMENTS = ("sky", "furnace", "studio", "grey_room")
STRATEGIES = ("uniform", "cosine", "environment", "brdf", "mis_balance", "mis_power", "auto")
SEQUENCES = ("random", "sobol")  # lab.ibl.integrator.SEQUENCES
SEQUENCE_TITLES = ("random", "Sobol'")
# When the view stops refining: an estimated error reached, or a time spent (or the
# samples/pixel cap, ibl_samples).
STOP_ERRORS = (0.02, 0.01, 0.005, 0.0025)
STOP_SECONDS = (10.0, 60.0, 300.0, 1800.0)
COMPARE = ("alone", *(f"vs {s}" for s in STRATEGIES))
# What is lit: the sphere, or the object view's other shapes (its yaw and pitch turn them).
TARGETS = ("sphere", *(shape for shape in SHAPES if shape != "sphere"))


def plot(job: PlotJob) -> None:
    """`brdf-lab render --view ibl`: the CLI puts its --env/--strategy/... on job.ibl."""
    from lab.ibl.png import render_png

    options = getattr(job, "ibl", None) or {}
    for line in render_png(job.model, job.values, job, job.out, **options):
        print(line)


VIEW = ViewSpec(
    name="ibl",
    title="Image-based lighting",
    settings={
        "ibl_env": Setting(0, 0, len(ENVIRONMENTS) - 1, "environment", choices=ENVIRONMENTS),
        "ibl_strategy": Setting(6, 0, len(STRATEGIES) - 1, "sampling", choices=STRATEGIES),
        "ibl_sequence": Setting(1, 0, 1, "numbers", choices=SEQUENCE_TITLES),
        "ibl_stop_error": Setting(
            1,
            0,
            len(STOP_ERRORS) - 1,
            "until error",
            choices=tuple(f"{e * 100:g}%" for e in STOP_ERRORS),
        ),
        "ibl_stop_time": Setting(
            1, 0, len(STOP_SECONDS) - 1, "or time", choices=("10 s", "1 min", "5 min", "30 min")
        ),
        "ibl_compare": Setting(0, 0, len(STRATEGIES), "side by side", choices=COMPARE),
        "ibl_target": Setting(0, 0, len(TARGETS) - 1, "lit", choices=TARGETS),
        "ibl_samples": Setting(65536, 1, 65536, "samples/pixel at most"),
        "ibl_rotation": Setting(0.0, 0.0, 360.0, "rotation", 1.0),
        "ibl_exposure": Setting(0.0, -8.0, 8.0, "exposure", 0.1),
    },
    dock=("right", 0),
    size=(1.0, 0.6),  # opened, its row takes this share: room for the picture and the plot
    short_title="IBL",
    tab_of="sphere",  # behind the lit spheres: its passes run only while it is in front
    widget="lab.app.views.ibl:IBLView",
    plot=plot,
    order=80,
)

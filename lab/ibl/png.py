"""`brdf-lab render --view ibl`: an IBL render saved as a PNG, with the lines to print."""

from __future__ import annotations

from lab.ibl import environments
from lab.ibl.integrator import (
    SHAPES,
    STRATEGIES,
    STRATEGY_TITLES,
    Environment,
    chosen_strategy,
    fallback,
    render,
    ring_peak,
)
from lab.models import Model


def render_png(
    model: Model,
    values,
    job,
    out,
    env: str = "sky",
    strategy: str = "auto",
    samples: int = 256,
    rotation: float = 0.0,
    shape: str = "sphere",
) -> list[str]:
    """`brdf-lab render --view ibl`: render, save the PNG, return the lines to print.
    `job` is the registry's PlotJob (size, exposure); `shape` "sphere" is the lit sphere,
    another of SHAPES the object view's shape."""
    from lab import plots
    from lab.errors import UsageError

    if strategy not in STRATEGIES:
        raise UsageError(f"--strategy {strategy!r}: use one of {', '.join(STRATEGIES)}")
    if not 1 <= samples <= 1_000_000:
        raise UsageError(f"--samples {samples} is outside 1..1000000")
    if shape not in SHAPES:
        raise UsageError(f"--shape {shape!r}: use one of {', '.join(repr(s) for s in SHAPES)}")
    try:
        environment = Environment.load(env)
    except environments.EnvironmentError as err:
        raise UsageError(f"--env: {err}") from None
    lines = []
    note = fallback(model, strategy)
    if note:
        lines.append(f"note: {note}")
    target = None if shape == "sphere" else shape
    image = render(
        model,
        values,
        environment,
        strategy,
        samples,
        job.size,
        rotation,
        shape=target,
        sequence="sobol",
    )
    if environment.name == "furnace" and target is None:
        peak = ring_peak(image)
        if peak > 1.01:
            lines.append(
                f"energy gain: the sphere reflects up to {peak:.2f}x the furnace's radiance "
                "(a physically based BRDF stays at or below 1)"
            )
    plots.save_image(image[..., :3], out, job.exposure)  # the environment behind, opaque
    chosen = chosen_strategy(strategy, environment)
    here = f" (here {STRATEGY_TITLES[chosen]})" if strategy == "auto" else ""
    lines.append(
        f"{samples} samples/pixel, {STRATEGY_TITLES[strategy]}{here}, environment "
        f"{environment.name}" + ("" if target is None else f", the {shape}")
    )
    return lines

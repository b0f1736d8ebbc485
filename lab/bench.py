"""`brdf-lab bench`: speed figures of the renderer (a command, not a timed test)."""

from __future__ import annotations

import time
from functools import partial

import numpy as np

TARGETS = (
    "targets: sphere 512^2 <= 5 ms without readback; albedo curve <= 50 ms; GPU eval >= 5x numpy"
)


def _median_ms(fn, repeat: int) -> float:
    fn()  # warm up: compile and allocate outside the timing
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        fn()
        times.append(time.perf_counter() - start)
    return float(np.median(times) * 1000.0)


def run(quick: bool = False) -> None:
    from rich.console import Console
    from rich.table import Table

    from lab import reference
    from lab.gl import describe, get_context
    from lab.models import load_model, model_names
    from lab.render import Renderer

    console = Console()
    start = time.perf_counter()
    ctx = get_context()
    created = (time.perf_counter() - start) * 1000.0
    console.print(f"context: {describe(ctx)}; created in {created:.1f} ms")
    renderer = Renderer(ctx)
    repeat = 5 if quick else 30
    thetas = np.arange(0.0, 90.0, 1.0)
    rng = np.random.default_rng(1)
    n_pairs = 200_000 if quick else 1_000_000
    cos_theta = rng.uniform(0.0, 1.0, (n_pairs, 2))
    angles = np.column_stack(
        [
            np.degrees(np.arccos(cos_theta[:, 0])),
            rng.uniform(0, 360, n_pairs),
            np.degrees(np.arccos(cos_theta[:, 1])),
            rng.uniform(0, 360, n_pairs),
        ]
    )

    table = Table(title=f"brdf-lab bench ({TARGETS})")
    for column in (
        "model",
        "sphere 512² ms",
        "+readback ms",
        "albedo 90 θi ms",
        f"GPU eval {n_pairs:,} ms",
        "numpy ms",
        "speed-up",
    ):
        table.add_column(column, justify="right")
    for name in model_names():
        model = load_model(name)
        values = model.defaults()
        sphere = _median_ms(partial(renderer.sphere, model, values, readback=False), repeat)
        readback = _median_ms(partial(renderer.sphere, model, values), repeat)
        albedo = _median_ms(partial(renderer.albedo, model, values, thetas), max(3, repeat // 3))
        gpu = _median_ms(partial(renderer.eval_angles, model, values, angles), 3)
        cpu = _median_ms(partial(reference.brdf_angles, name, values, angles), 1)
        table.add_row(
            name,
            f"{sphere:.2f}",
            f"{readback:.2f}",
            f"{albedo:.1f}",
            f"{gpu:.0f}",
            f"{cpu:.0f}",
            f"{cpu / gpu:.1f}x",
        )
    console.print(table)

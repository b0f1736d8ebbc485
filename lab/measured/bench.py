"""`brdf-lab measured-bench`: load, render and fit timings against the issue's targets."""

from __future__ import annotations

import tempfile
import time
from pathlib import Path

import numpy as np

from lab.measured import fit as fitting
from lab.measured.merl import read_merl, write_merl
from lab.measured.model import measured_model
from lab.measured.tabulate import tabulate

TARGETS = {"load": 1.0, "render_ratio": 2.0, "fit": 30.0}


def _best(fn, repeats: int) -> float:
    best = float("inf")
    for _ in range(repeats):
        start = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - start)
    return best


def run(quick: bool = False) -> dict[str, float]:
    """Print the figures and return them (seconds)."""
    from lab.gl import describe
    from lab.render import Renderer

    renderer = Renderer()
    print(f"device: {describe(renderer.ctx)}")
    repeats = 3 if quick else 10
    truth = {"kd": (0.15, 0.08, 0.05), "ks": (0.7, 0.7, 0.7), "m": 0.25}
    start = time.perf_counter()
    table = tabulate("cook_torrance", truth, noise=0.02, renderer=renderer)
    figures = {"tabulate": time.perf_counter() - start}
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "bench.binary"
        write_merl(table, path)
        figures["load"] = _best(lambda: read_merl(path), repeats)
    model = measured_model(table)
    for name, m, values in (
        ("render_cook_torrance", "cook_torrance", {}),
        ("render_measured_linear", model, {"interpolation": "linear"}),
        ("render_measured_nearest", model, {"interpolation": "nearest"}),
    ):
        renderer.sphere(m, values, size=512, readback=False)  # compile, upload
        figures[name] = _best(
            lambda m=m, v=values: renderer.sphere(m, v, size=512, readback=False), repeats * 3
        )
    samples = fitting.select_samples(table, 20000)
    for name in fitting.FIT_MODELS:
        result = fitting.fit(samples, name)
        figures[f"fit_{name}"] = result.seconds
        figures[f"fit_{name}_error"] = result.error
    ratio = figures["render_measured_linear"] / figures["render_cook_torrance"]
    ok = {True: "ok", False: "OVER TARGET"}
    print(f"tabulate 90x90x180 on the GPU:  {figures['tabulate']:.2f} s")
    print(
        f"load a MERL-size file:          {figures['load'] * 1e3:.0f} ms   "
        f"(target <= 1 s: {ok[figures['load'] <= TARGETS['load']]})"
    )
    print(f"512^2 sphere, cook_torrance:    {figures['render_cook_torrance'] * 1e3:.2f} ms")
    print(
        f"512^2 sphere, measured linear:  {figures['render_measured_linear'] * 1e3:.2f} ms   "
        f"({ratio:.2f}x cook_torrance; target <= 2x: {ok[ratio <= TARGETS['render_ratio']]})"
    )
    print(f"512^2 sphere, measured nearest: {figures['render_measured_nearest'] * 1e3:.2f} ms")
    for name in fitting.FIT_MODELS:
        seconds = figures[f"fit_{name}"]
        print(
            f"fit {name:14s} (20000 bins):  {seconds:5.1f} s, error "
            f"{figures[f'fit_{name}_error']:.4f}   (target <= 30 s: "
            f"{ok[seconds <= TARGETS['fit']]})"
        )
    figures["render_ratio"] = float(np.float64(ratio))
    return figures

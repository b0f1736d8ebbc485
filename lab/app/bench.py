"""`brdf-lab app --bench`: frame time from a slider change until every visible view redrew.

Three models, every view visible, a 1280x800 window. Each sample moves a real slider
(the selected model's first float parameter, then the light's theta) and runs the event
loop until the frame is drawn and painted. Refinement passes run between samples, as they
would while a user pauses, and the slowest single refinement step is reported too.
"""

from __future__ import annotations

import time

import numpy as np

BENCH_MODELS = ("phong", "cook_torrance", "ward")
CHANGES = 200


def process_age() -> float | None:
    """Seconds since this process started (Linux), for launch-to-first-frame."""
    try:
        with open("/proc/self/stat") as handle:
            start_ticks = int(handle.read().rsplit(")", 1)[1].split()[19])
        with open("/proc/uptime") as handle:
            uptime = float(handle.read().split()[0])
        import os

        return uptime - start_ticks / os.sysconf("SC_CLK_TCK")
    except (OSError, ValueError, IndexError):
        return None


def wait_frame(app, window, before: int) -> None:
    while window.frames == before:
        app.processEvents()
    app.processEvents()  # the paint events the frame posted


def measure(app, window, move, count: int) -> np.ndarray:
    times = []
    for i in range(count):
        before = window.frames
        start = time.perf_counter()
        move(i)
        wait_frame(app, window, before)
        times.append(time.perf_counter() - start)
        if i % 20 == 19:
            window.settle()  # let refinement run, as during a pause
            app.processEvents()
    return np.array(times) * 1000.0


def run_bench(app, launched: float) -> int:
    from lab.app.state import load_any
    from lab.app.window import MainWindow

    window = MainWindow()
    for name in BENCH_MODELS:
        window.lab.add(load_any(name))
    window.resize(1280, 800)
    window.show()
    before = window.frames
    window.request()
    wait_frame(app, window, before)
    age = process_age()
    first_frame = age if age is not None else time.perf_counter() - launched
    window.settle()
    refine_steps = []
    state = window.lab.selected
    control = next(c for c in window.params.controls.values() if c.param.kind == "float")
    slider = control.slider

    def move_param(i: int) -> None:
        slider.setValue(200 + (i * 37) % 600)

    def move_light(i: int) -> None:
        window.theta_slider.slider.setValue(20 + (i * 7) % 140)

    window.frame_times.clear()
    params = measure(app, window, move_param, CHANGES)
    compute_params = np.array(window.frame_times) * 1000.0
    window.frame_times.clear()
    light = measure(app, window, move_light, CHANGES)
    compute_light = np.array(window.frame_times) * 1000.0
    # The slowest refinement step (each runs alone in one event-loop turn).
    for _ in range(3):
        state.set_value(control.param.name, slider_value_of(control, 300 + 100 * _))
        window.frame()
        for view in list(window._refine):
            start = time.perf_counter()
            view.redraw(fast=False)
            refine_steps.append((time.perf_counter() - start) * 1000.0)
        window._refine = []
    from lab.gl import describe

    print(f"brdf-lab app benchmark: {describe(window.renderer.ctx)}")
    print(f"window {window.width()}x{window.height()}, models: {', '.join(BENCH_MODELS)}, "
          f"views: {', '.join(v.name for v in window.views if v.is_shown())}")
    for label, times in (("parameter slider", params), ("light slider (all models)", light)):
        print(f"{label}: {len(times)} changes, frame p50 {np.percentile(times, 50):.1f} ms, "
              f"p95 {np.percentile(times, 95):.1f} ms, max {times.max():.1f} ms")
    for label, times in (("parameter", compute_params), ("light", compute_light)):
        print(f"  {label}: redraw work alone (no Qt painting) p50 "
              f"{np.percentile(times, 50):.1f} ms, p95 {np.percentile(times, 95):.1f} ms")
    if refine_steps:
        print(f"refinement: slowest single step {max(refine_steps):.1f} ms "
              f"(runs {REFINE_NOTE})")
    print(f"launch to first frame: {first_frame:.2f} s")
    window.close()
    return 0


REFINE_NOTE = "150 ms after the last change, one view per event-loop turn"


def slider_value_of(control, position: int) -> float:
    from lab.app.widgets import slider_value

    return slider_value(control.param, position)

"""`brdf-lab ibl-bench`: throughput of the IBL integrator and each strategy's time to 1% error.

Throughput: sample evaluations per second for a 512x512 sphere (pixels on the sphere times
samples per pixel). Convergence: a glossy GGX (alpha = 0.1) under the sky; each strategy
accumulates until its relative RMS error against a converged reference (MIS, power
heuristic, many samples, another seed) is below 1%, or its time budget runs out, in which
case the time is extrapolated with the Monte Carlo rate error ~ 1/sqrt(N) and marked so.
The reference's own error (from its two independent halves) is taken out in quadrature.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np

from lab.ibl.integrator import STRATEGIES, Environment, IBLRenderer, Progressive

GLOSSY = ("ggx", {"alpha": 0.1})
TARGET = 0.01


def relative_rms(image: np.ndarray, reference: np.ndarray) -> float:
    """RMS of the difference over the sphere's pixels, relative to the reference's RMS."""
    mask = reference[..., 3] > 0.5
    diff = image[..., :3][mask] - reference[..., :3][mask]
    return float(np.sqrt(np.mean(diff**2)) / np.sqrt(np.mean(reference[..., :3][mask] ** 2)))


@dataclass
class Convergence:
    strategy: str
    samples: list[int] = field(default_factory=list)
    seconds: list[float] = field(default_factory=list)  # GPU time, error checks excluded
    errors: list[float] = field(default_factory=list)

    def time_to(self, target: float = TARGET) -> tuple[float, bool]:
        """(seconds to reach `target`, measured?); extrapolated by 1/sqrt(N) otherwise."""
        for seconds, error in zip(self.seconds, self.errors, strict=True):
            if error <= target:
                return seconds, True
        return self.seconds[-1] * (self.errors[-1] / target) ** 2, False


def converge(
    renderer: IBLRenderer,
    model,
    values,
    env: Environment,
    strategy: str,
    reference: np.ndarray,
    size: int,
    budget_s: float = 20.0,
    target: float = TARGET,
    reference_error: float = 0.0,
) -> Convergence:
    """Accumulate in doubling sample counts, recording the error after each; the
    reference's own (independent) error is taken out in quadrature."""
    job = Progressive(renderer, model, values, env, strategy, size, seed=1)
    result = Convergence(strategy)
    elapsed = 0.0
    try:
        while True:
            count = max(job.samples, 1)
            start = time.perf_counter()
            while job.samples < 2 * count or job.samples == 0:
                job.add(min(16, 2 * count - job.samples) if job.samples else 1)
                if job.samples == 1:
                    break
            renderer.ctx.finish()
            elapsed += time.perf_counter() - start
            raw = relative_rms(job.image(), reference)
            error = math.sqrt(max(raw**2 - reference_error**2, 0.0))
            result.samples.append(job.samples)
            result.seconds.append(elapsed)
            result.errors.append(error)
            if error <= target or elapsed > budget_s:
                return result
    finally:
        job.release()


def reference_image(renderer, model, values, env, size: int, samples: int):
    """The converged reference and its own relative RMS error, estimated from two
    independent halves: RMS(A - B) / 2 is the error of their mean (A + B) / 2."""
    halves = []
    for seed in (12345, 54321):
        job = Progressive(renderer, model, values, env, "mis_power", size, seed=seed)
        try:
            halves.append(job.run(samples // 2, spp=32).image())
        finally:
            job.release()
    reference = 0.5 * (halves[0] + halves[1])
    mask = reference[..., 3] > 0.5
    diff = halves[0][..., :3][mask] - halves[1][..., :3][mask]
    own = float(np.sqrt(np.mean(diff**2)) / 2.0 / np.sqrt(np.mean(reference[..., :3][mask] ** 2)))
    return reference, own


def throughput(renderer: IBLRenderer, env: Environment, strategy: str, size=512, spp=4) -> float:
    """Sample evaluations per second on the sphere (its pixels times samples per pixel)."""
    job = Progressive(renderer, *GLOSSY, env, strategy, size)
    try:
        job.add(1)
        renderer.ctx.finish()
        start = time.perf_counter()
        passes = 0
        while time.perf_counter() - start < 1.0 or passes < 2:
            job.add(spp)
            renderer.ctx.finish()
            passes += 1
        seconds = time.perf_counter() - start
    finally:
        job.release()
    return math.pi / 4.0 * size * size * spp * passes / seconds


def convergence_plot(runs: list[Convergence], path) -> None:
    """Log-log error against samples per pixel, one line per strategy, with 1/sqrt(N)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6.4, 4.4), dpi=120)
    for run in runs:
        ax.loglog(run.samples, run.errors, marker="o", ms=3, label=run.strategy)
    first = runs[0]
    n = np.array([first.samples[0], max(r.samples[-1] for r in runs)], dtype=float)
    ax.loglog(n, first.errors[0] * np.sqrt(n[0] / n), "k--", lw=1, label="1/√N")
    ax.axhline(TARGET, color="grey", lw=0.8, ls=":")
    ax.set_xlabel("samples per pixel")
    ax.set_ylabel("relative RMS error vs converged reference")
    ax.set_title("glossy GGX (α = 0.1) under the sky")
    ax.legend(fontsize=8)
    ax.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)


def run(size: int = 64, reference_samples: int = 8192, budget_s: float = 20.0, plot=None) -> dict:
    """Print the figures (and save the convergence plot to `plot`); returns them too."""
    renderer = IBLRenderer()
    env = Environment.load("sky")
    print(f"renderer: {renderer.ctx.info['GL_RENDERER']}")
    print("throughput, 512x512 sphere, ggx alpha=0.1 under the sky:")
    rates = {}
    for strategy in STRATEGIES:
        rates[strategy] = throughput(renderer, env, strategy)
        print(f"  {strategy:12s} {rates[strategy] / 1e6:7.2f} M samples/s")
    print(
        f"time to {TARGET:.0%} relative RMS error, {size}x{size} sphere, reference "
        f"{reference_samples} samples/pixel (MIS power):"
    )
    reference, own = reference_image(renderer, *GLOSSY, env, size, reference_samples)
    print(f"  (the reference's own error, {own:.2%}, is taken out in quadrature)")
    times, runs = {}, []
    for strategy in STRATEGIES:
        c = converge(renderer, *GLOSSY, env, strategy, reference, size, budget_s, TARGET, own)
        runs.append(c)
        seconds, measured = c.time_to()
        samples = c.samples[-1] * (c.errors[-1] / TARGET) ** 2 if not measured else None
        times[strategy] = seconds
        how = "measured" if measured else f"extrapolated from {c.errors[-1]:.1%} at"
        at = (
            c.samples[-1]
            if not measured
            else next(n for n, e in zip(c.samples, c.errors, strict=True) if e <= TARGET)
        )
        extra = f" (~{samples:.0f} samples/pixel)" if samples else ""
        print(f"  {strategy:12s} {seconds:9.2f} s  {how} {at} samples/pixel{extra}")
    uniform, best = times["uniform"], min(times[s] for s in ("brdf", "mis_balance", "mis_power"))
    print(f"importance sampling reaches {TARGET:.0%} {uniform / best:.0f}x sooner than uniform")
    if plot:
        convergence_plot(runs, plot)
        print(f"wrote {plot}")
    return {"throughput": rates, "time_to_target": times}

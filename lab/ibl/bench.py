"""`brdf-lab ibl-bench`: throughput of the IBL integrator and each strategy's time to 1% error.

Throughput: sample evaluations per second for a 512x512 sphere (pixels on the sphere times
samples per pixel). Convergence: a glossy GGX (alpha = 0.1) under the sky; each strategy
accumulates until its relative RMS error against a converged reference (MIS, power
heuristic, many samples, another seed) is below 1%, or its time budget runs out, in which
case the time is extrapolated with the Monte Carlo rate error ~ 1/sqrt(N) and marked so.
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
) -> Convergence:
    """Accumulate in doubling sample counts, recording the error after each."""
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
            error = relative_rms(job.image(), reference)
            result.samples.append(job.samples)
            result.seconds.append(elapsed)
            result.errors.append(error)
            if error <= target or elapsed > budget_s:
                return result
    finally:
        job.release()


def reference_image(renderer, model, values, env, size: int, samples: int) -> np.ndarray:
    job = Progressive(renderer, model, values, env, "mis_power", size, seed=12345)
    try:
        return job.run(samples, spp=32).image()
    finally:
        job.release()


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


def run(size: int = 64, reference_samples: int = 8192, budget_s: float = 20.0) -> dict:
    """Print the figures; returns them too (for tests)."""
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
    reference = reference_image(renderer, *GLOSSY, env, size, reference_samples)
    times = {}
    for strategy in STRATEGIES:
        c = converge(renderer, *GLOSSY, env, strategy, reference, size, budget_s)
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
    return {"throughput": rates, "time_to_target": times}

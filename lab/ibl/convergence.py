"""Error against samples for one IBL configuration: the measurements `ibl-bench` prints.

A run accumulates a Progressive render and records its relative RMS error against a
converged reference at sample counts growing by about sqrt(2) (so prefixes that are not
powers of two are measured too). The reference's own error, from its two independent
halves, is taken out in quadrature.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np

from lab.ibl.integrator import Environment, IBLRenderer, Progressive

TARGET = 0.01


def relative_rms(image: np.ndarray, reference: np.ndarray) -> float:
    """RMS of the difference over the sphere's pixels, relative to the reference's RMS."""
    mask = reference[..., 3] > 0.5
    diff = image[..., :3][mask] - reference[..., :3][mask]
    return float(np.sqrt(np.mean(diff**2)) / np.sqrt(np.mean(reference[..., :3][mask] ** 2)))


def checkpoints(limit: int) -> list[int]:
    """1, 2, 3, 4, 6, 8, 11, 16, 23, 32, ...: sample counts about sqrt(2) apart."""
    out, k = [], 0
    while True:
        n = round(2 ** (k / 2))
        if n > limit:
            return out
        if not out or n > out[-1]:
            out.append(n)
        k += 1


@dataclass
class Convergence:
    strategy: str
    sequence: str = "random"
    samples: list[int] = field(default_factory=list)
    seconds: list[float] = field(default_factory=list)  # GPU time, error checks excluded
    errors: list[float] = field(default_factory=list)

    def samples_to(self, target: float = TARGET) -> tuple[float, bool]:
        """(samples per pixel to reach `target`, measured?): log-log interpolation between
        the checkpoints around the first one at or under it; else extrapolated from the
        last by 1/sqrt(N), the slowest rate an unbiased estimator falls at."""
        for i, (n, error) in enumerate(zip(self.samples, self.errors, strict=True)):
            if error <= target:
                if i == 0 or error <= 0.0:
                    return float(n), True
                n0, e0 = self.samples[i - 1], self.errors[i - 1]
                slope = math.log(error / e0) / math.log(n / n0)
                if slope >= 0.0:
                    return float(n), True
                return float(n0 * (target / e0) ** (1.0 / slope)), True
        return self.samples[-1] * (self.errors[-1] / target) ** 2, False

    def time_to(self, target: float = TARGET) -> tuple[float, bool]:
        """(seconds to reach `target` at this run's size, measured?), by the run's rate."""
        samples, measured = self.samples_to(target)
        return self.seconds[-1] / self.samples[-1] * samples, measured

    def error_at(self, n: int) -> float:
        return self.errors[self.samples.index(n)]


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
    sequence: str = "random",
    max_samples: int = 1 << 16,
) -> Convergence:
    """Accumulate up to each checkpoint, recording the error there, until the error is
    under `target` (and one checkpoint more, to see the slope), or `max_samples`, or the
    time budget is spent."""
    job = Progressive(renderer, model, values, env, strategy, size, seed=1, sequence=sequence)
    result = Convergence(strategy, sequence)
    elapsed = 0.0
    reached = 0
    try:
        for n in checkpoints(max_samples):
            start = time.perf_counter()
            job.run(n, spp=64)
            renderer.ctx.finish()
            elapsed += time.perf_counter() - start
            raw = relative_rms(job.image(), reference)
            error = math.sqrt(max(raw**2 - reference_error**2, 0.0))
            result.samples.append(job.samples)
            result.seconds.append(elapsed)
            result.errors.append(error)
            reached += error <= target
            if reached >= 2 or elapsed > budget_s:
                break
        return result
    finally:
        job.release()


def reference_image(renderer, model, values, env, size: int, samples: int):
    """The converged reference (MIS, power heuristic, on Sobol' points) and its own relative RMS
    error, from two independent halves: RMS(A - B) / 2 is the error of their mean."""
    halves = []
    for seed in (12345, 54321):
        job = Progressive(
            renderer, model, values, env, "mis_power", size, seed=seed, sequence="sobol"
        )
        try:
            halves.append(job.run(samples // 2, spp=64).image())
        finally:
            job.release()
    reference = 0.5 * (halves[0] + halves[1])
    mask = reference[..., 3] > 0.5
    diff = halves[0][..., :3][mask] - halves[1][..., :3][mask]
    own = float(np.sqrt(np.mean(diff**2)) / 2.0 / np.sqrt(np.mean(reference[..., :3][mask] ** 2)))
    return reference, own


def throughput(
    renderer: IBLRenderer,
    model,
    values,
    env,
    strategy: str,
    sequence="random",
    size=317,
    spp=16,
    windows: int = 3,
) -> float:
    """Sample evaluations per second on a size x size sphere (its pixels times samples per
    pixel), in passes of `spp` as the app runs them, after one warm-up pass: the best of
    `windows` windows of at least 0.3 s (others' work on a shared machine only slows)."""
    job = Progressive(renderer, model, values, env, strategy, size, sequence=sequence)
    best = 0.0
    try:
        job.add(1)
        renderer.ctx.finish()
        for _ in range(windows):
            start = time.perf_counter()
            passes = 0
            while time.perf_counter() - start < 0.3 or passes < 1:
                job.add(spp)
                renderer.ctx.finish()
                passes += 1
            seconds = time.perf_counter() - start
            best = max(best, math.pi / 4.0 * size * size * spp * passes / seconds)
    finally:
        job.release()
    return best

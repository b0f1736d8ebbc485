"""`kind = "ibl_render"`: the lit sphere under an `environment` with the student's sampler
alone (the IBL view's BRDF strategy), in `converged / samples` independent passes of
`samples` per pixel; the reference is the solution's estimator run the same way, from other
random numbers, the environment turned by `phi_i` about the vertical (hidden mode draws
it). With `estimator = true` the student's file is the estimate itself, not a sampler.
Passes when the estimator is unbiased (a z-test of the two means per ring
of equal view angle and over the sphere, with both estimators' own variances from their
passes, failing a correct program with probability `alpha`) and its RMS error at `samples`
per pixel is at most `factor` times the solution's: what importance sampling buys (the
check's `ranges` keep hidden mode's exponent where that separates samplers)."""

from __future__ import annotations

import base64
import math
from statistics import NormalDist

import numpy as np

from lab.grading import mistakes, sampling
from lab.grading.compare import png, tonemap
from lab.grading.kinds.sampled import SampledKind
from lab.grading.kinds.values import floats_b64
from lab.grading.result import CheckResult, failed, passed
from lab.grading.spec import Check, ExerciseError
from lab.ibl.environments import PROCEDURAL
from lab.ibl.integrator import Progressive, local_view


def estimate_fingerprint(renderer, model, params, env: str, rotation: float, seed: int):
    """(pixels, 3): an estimator exercise's estimate (the student writes it, not a sampler)
    at 4 samples per pixel of a 16-pixel sphere, from random numbers fixed by `seed` alone:
    programs that draw and weigh alike give the same rows."""
    ibl = sampling.ibl_renderer(renderer)
    job = Progressive(ibl, model, params, sampling.environment(env), "brdf", 16, rotation, seed)
    try:
        job.add(4)
        image = job.image()
    finally:
        job.release()
    return image[sampling._sphere(16)][:, :3].astype(np.float64)


ALIKE_ALPHA = 1e-3  # two estimators converge alike when no ring's z-test fails at this level


def converge_distance(got: np.ndarray, other: np.ndarray, passes: int) -> float | None:
    """How unlike two estimators' renders (render_raw's arrays) are, or None where they
    converge to different images (a ring's or the sphere's z-test of their means, with both
    variances, fails at ALIKE_ALPHA): the largest |z| over its limit plus the log of their
    noise ratio, so that of two alike the one as noisy as `got` is nearer."""
    got, other = got.astype(np.float64), other.astype(np.float64)
    if not (np.isfinite(got).all() and np.isfinite(other).all()):
        return None
    z, words = sampling.bias_z(got, other, passes)
    limits = np.array([sampling.t_limit(ALIKE_ALPHA, len(z), dof) for _, _, dof in words])
    worst = float(np.max(np.abs(z) / limits))
    if worst > 1.0:
        return None
    mask = sampling._sphere(got.shape[1])
    mine, theirs = got[2][..., 0][mask].mean(), other[2][..., 0][mask].mean()
    return worst + 0.5 * abs(math.log(max(mine, 1e-30) / max(theirs, 1e-30)))


def _picture(image: np.ndarray) -> bytes:
    rgb = np.nan_to_num(image[..., :3].astype(np.float32), nan=0.0, posinf=1e3)
    return png((np.clip(tonemap(rgb), 0, 1) * 255 + 0.5).astype(np.uint8))


class IBLRenderKind(SampledKind):
    name = "ibl_render"
    order = 52
    fields = {
        "samples": 16,
        "converged": 256,
        "environment": "grey_room",
        "factor": 2.0,
        "alpha": 1e-5,
    }

    def where(self, check: Check, x: int, y: int) -> str:
        return f"pixel ({x}, {y}) of the render (row 0 at the bottom)"

    captions = {
        "converged reference": "the solution's estimator, converged (the reference)",
        "solution": "the solution's estimator at the same samples",
        "yours": "your estimator at the same samples",
        "yours, converged": "your estimator run longer: what it converges to",
    }

    def validate(self, check: Check, where: str) -> None:
        o = check.options
        if not (1 <= o["samples"] and 4 * o["samples"] <= o["converged"] <= 65536):
            raise ExerciseError(
                f"{where}: check {check.name}: need 1 <= samples, 4 * samples <= converged "
                "<= 65536 (the passes estimate the noise)"
            )
        if o["environment"] not in PROCEDURAL:
            raise ExerciseError(
                f"{where}: check {check.name}: environment {o['environment']!r} is not one "
                f"of {', '.join(PROCEDURAL)}"
            )
        if not (o["factor"] >= 1.0 and 0.0 < o["alpha"] < 0.1 and 8 <= check.size <= 256):
            raise ExerciseError(
                f"{where}: check {check.name}: need factor >= 1, 0 < alpha < 0.1, size 8..256"
            )

    @staticmethod
    def rotation(check: Check) -> float:
        """The environment's turn about the vertical in degrees, as render() draws it and the
        page's render follows: the light's azimuth phi_i (hidden mode draws it)."""
        return check.phi_i

    @staticmethod
    def passes(check: Check) -> int:
        return check.options["converged"] // check.options["samples"]

    def render(self, renderer, model, check: Check) -> np.ndarray:
        o = check.options
        return sampling.render_raw(
            renderer,
            model,
            check.params,
            o["environment"],
            check.size,
            o["samples"],
            self.passes(check),
            check.seed,
            self.rotation(check),
        )

    def stored(self, raw: np.ndarray, check: Check) -> np.ndarray:
        """Float32: one pass, the mean of all passes and the passes' variance."""
        return np.clip(np.nan_to_num(raw, nan=3e38, posinf=3e38), -3e38, 3e38).astype(np.float32)

    def _judge(self, check: Check, raw: np.ndarray, reference) -> tuple[bool, str, dict]:
        o = check.options
        return sampling.judge_render(
            raw, reference, o["samples"], self.passes(check), o["factor"], o["alpha"]
        )

    def compare(self, check: Check, expected: np.ndarray, raw: np.ndarray) -> CheckResult:
        ok, message, stats = self._judge(check, raw, expected)
        images = {"yours": _picture(raw[0]), "yours, converged": _picture(raw[1])}
        if expected is not None and np.shape(expected) == np.shape(raw):
            images = {
                "converged reference": _picture(expected[1]),
                "solution": _picture(expected[0]),
                **images,
            }
        verdict = passed if ok else failed
        return verdict(check, message, images=images, extra=stats)

    def practice(self, exercise, check: Check, values) -> dict:
        """What the page's iblcheck.js needs to judge a render as judge_render does, all made
        here by the grader's code: the reference (the solution's pass, mean and variance),
        each pixel's group of the z-test (an index into `groups`, 255 off the sphere) and
        ring of the diagnosis' ring means, the normal quantile of the groups' Bonferroni
        limit, and each stored mistake's converged ring means (nearest, without its render)."""
        size, o = check.size, check.options
        theta, _, mask = local_view(size)
        zone = np.minimum((theta / 90.0 * sampling.Z_GROUPS).astype(int), sampling.Z_GROUPS - 1)
        zones = np.full((size, size), 255, np.uint8)
        groups = []
        for r in range(sampling.Z_GROUPS):
            if (mask & (zone == r)).any():
                zones[mask & (zone == r)] = len(groups)
                low, high = 90 * r / sampling.Z_GROUPS, 90 * (r + 1) / sampling.Z_GROUPS
                groups.append(sampling.WORDS["ring"].format(low=low, high=high))  # as bias_z
        groups.append(sampling.WORDS["whole_sphere"])
        ring = np.minimum((theta / 90.0 * sampling.RINGS).astype(int), sampling.RINGS - 1)
        rings = np.where(mask, ring, 255).astype(np.uint8)
        hints = mistakes.read_hints(exercise)
        try:
            with np.load(exercise.references / mistakes.VALUES) as data:
                prefix = f"{check.name}|"
                stored = {k[len(prefix) :]: data[k] for k in data.files if k.startswith(prefix)}
        except (OSError, ValueError):
            stored = {}
        return {
            "passes": self.passes(check),
            "rotation": self.rotation(check),
            "reference": floats_b64(values[check.name]),
            "zones": base64.b64encode(zones.tobytes()).decode(),
            "rings": base64.b64encode(rings.tobytes()).decode(),
            "groups": groups,
            "words": {k: v for k, v in sampling.WORDS.items() if k.startswith("render_")},
            "captions": self.captions,  # the renders' titles, as the report's
            "z_normal": NormalDist().inv_cdf(1.0 - o["alpha"] / (2.0 * len(groups))),
            "same_render": sampling.SAME_RENDER,
            "ring_count": sampling.RINGS,
            "ring_means": {
                key: sampling.ring_means(value[1]).tolist()
                for key, value in stored.items()
                if key in hints and value.shape == values[check.name].shape
            },
            # The page keeps the ring means above, not the stored renders themselves.
            "diagnosis": {"candidates": {}, "terms": {}},
        }

    def differs(self, check: Check, values: np.ndarray, reference: np.ndarray) -> bool:
        if values.shape != reference.shape:
            return True
        return not self._judge(check, values, reference)[0]

    def live_values(self, renderer, model, check: Check) -> np.ndarray:
        """An estimator exercise's estimate at fixed random numbers (it has no sampler of
        its own to fingerprint); a sampler's rows otherwise."""
        if getattr(model, "estimator", False):
            o = check.options
            return estimate_fingerprint(
                renderer, model, check.params, o["environment"], check.phi_i, check.seed
            )
        return super().live_values(renderer, model, check)

    def nearest(self, check: Check, got, expected, candidates: dict) -> str | None:
        """The known mistake whose estimator converges like the student's (the closest
        ring means); where none is that close, the one that passes a z-test against the
        student's render with both estimators' noise, and is as noisy (noisy renders)."""
        best, best_off = None, sampling.SAME_RENDER
        shaped = {k: v for k, v in candidates.items() if np.shape(v) == np.shape(got)}
        for key, other in shaped.items():
            off = sampling.ring_deviation(got[1], other[1])
            if off <= best_off:
                best, best_off = key, off
        if best is not None or np.ndim(got) != 4 or len(got) != 3:
            return best
        distances = {k: converge_distance(got, v, self.passes(check)) for k, v in shaped.items()}
        alike = {k: d for k, d in distances.items() if d is not None}
        return min(alike, key=alike.get) if alike else None


KIND = IBLRenderKind()

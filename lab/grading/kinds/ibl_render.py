"""`kind = "ibl_render"`: the lit sphere under an `environment` with the student's sampler
alone (the IBL view's BRDF strategy), `samples` per pixel, and the same estimator run to
`converged` samples. Passes when its error at equal samples is at most `factor` times the
solution's and its limit agrees with the solution's within `bias` in every ring of equal
view angle."""

from __future__ import annotations

import base64

import numpy as np

from lab.grading import sampling
from lab.grading.compare import png, tonemap
from lab.grading.kinds.sampled import SampledKind
from lab.grading.result import CheckResult, failed, passed
from lab.grading.spec import Check, ExerciseError
from lab.ibl.environments import PROCEDURAL


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
        "factor": 1.5,
        "bias": 0.05,
    }

    def where(self, check: Check, x: int, y: int) -> str:
        return f"pixel ({x}, {y}) of the render (row 0 at the bottom)"

    captions = {
        "converged reference": "the solution's estimator, converged",
        "solution": "the solution's sampler at the same samples",
        "yours": "your sampler at the same samples",
        "yours, converged": "your estimator run longer: what it converges to",
    }

    def validate(self, check: Check, where: str) -> None:
        o = check.options
        if not 1 <= o["samples"] < o["converged"] <= 65536:
            raise ExerciseError(
                f"{where}: check {check.name}: need 1 <= samples < converged <= 65536"
            )
        if o["environment"] not in PROCEDURAL:
            raise ExerciseError(
                f"{where}: check {check.name}: environment {o['environment']!r} is not one "
                f"of {', '.join(PROCEDURAL)}"
            )
        if not (o["factor"] >= 1.0 and 0.0 < o["bias"] < 1.0 and 8 <= check.size <= 256):
            raise ExerciseError(
                f"{where}: check {check.name}: need factor >= 1, 0 < bias < 1, size 8..256"
            )

    def render(self, renderer, model, check: Check) -> np.ndarray:
        o = check.options
        return sampling.render_raw(
            renderer,
            model,
            check.params,
            o["environment"],
            check.size,
            o["samples"],
            o["converged"],
            check.seed,
        )

    def stored(self, raw: np.ndarray, check: Check) -> np.ndarray:
        """RGB in half floats: the images' noise is far above their rounding."""
        return np.clip(np.nan_to_num(raw[..., :3], nan=6e4, posinf=6e4), -6e4, 6e4).astype(
            np.float16
        )

    def compare(self, check: Check, expected: np.ndarray, raw: np.ndarray) -> CheckResult:
        o = check.options
        ok, message = sampling.judge_render(raw, expected, o["samples"], o["factor"], o["bias"])
        images = {
            "converged reference": _picture(expected[1]),
            "solution": _picture(expected[0]),
            "yours": _picture(raw[0]),
            "yours, converged": _picture(raw[1]),
        }
        return (
            passed(check, message, images=images) if ok else failed(check, message, images=images)
        )

    def practice(self, exercise, check: Check, values) -> dict:
        """The committed reference (half floats, as stored) for the page's practice mode."""
        stored = np.ascontiguousarray(values[check.name], dtype="<f2")
        return {"reference": base64.b64encode(stored.tobytes()).decode()}

    def differs(self, check: Check, values: np.ndarray, reference: np.ndarray) -> bool:
        if values.shape != reference.shape:
            return True
        o = check.options
        return not sampling.judge_render(values, reference, o["samples"], o["factor"], o["bias"])[0]

    def nearest(self, check: Check, got, expected, candidates: dict) -> str | None:
        """The known mistake whose estimator converges like the student's (the closest)."""
        best, best_off = None, sampling.SAME_RENDER
        for key, other in candidates.items():
            if other.shape == got.shape:
                off = sampling.ring_deviation(got[1], other[1])
                if off <= best_off:
                    best, best_off = key, off
        return best


KIND = IBLRenderKind()

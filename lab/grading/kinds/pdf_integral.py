"""`kind = "pdf_integral"`: the student's pdf integrated over the sphere per view (adaptive
quadrature in the turned frames of chi_square) against what the student's own sampler
does: a density of the sampler's draws integrates to 1 less the share of draws that fail
(pdf 0 where they land), within `tolerance` and the noise of that share measured from
`samples` draws. The solution's share plays no part: a mixture that wastes fewer samples
than the solution is as right."""

from __future__ import annotations

import numpy as np

from lab.grading import sampling
from lab.grading.kinds.sampled import SampledKind
from lab.grading.result import CheckResult, failed, passed
from lab.grading.spec import Check, ExerciseError


class PdfIntegralKind(SampledKind):
    name = "pdf_integral"
    order = 51
    fields = {"views": [[5.0, 0.0], [60.0, 300.0]], "tolerance": 0.005, "samples": 100_000}

    def validate(self, check: Check, where: str) -> None:
        super().validate(check, where)
        if not 0.0 < check.options["tolerance"] < 0.5:
            raise ExerciseError(f"{where}: check {check.name}: tolerance must lie in (0, 0.5)")
        if not 1000 <= check.options["samples"] <= 4_000_000:
            raise ExerciseError(f"{where}: check {check.name}: samples must be 1000 to 4000000")

    def render(self, renderer, model, check: Check) -> np.ndarray:
        return sampling.pdf_integral_raw(
            renderer, model, check.params, self.views(check), check.seed, check.options["samples"]
        )

    def stored(self, raw: np.ndarray, check: Check) -> np.ndarray:
        return raw.astype(np.float64)

    def _judge(self, check: Check, values: np.ndarray) -> tuple[bool, str, int]:
        o = check.options
        return sampling.judge_pdf_integral(values, self.views(check), o["samples"], o["tolerance"])

    def compare(self, check: Check, expected: np.ndarray, raw: np.ndarray) -> CheckResult:
        ok, message, _ = self._judge(check, raw)
        integrals = np.nan_to_num(np.asarray(raw, np.float64).reshape(-1, 2)[:, 0])
        extra = {"extra": {"integrals": [float(v) for v in integrals]}}
        return passed(check, message, **extra) if ok else failed(check, message, **extra)

    def practice(self, exercise, check: Check, values) -> dict:
        return {**self.practice_views(check), "reference": values[check.name].tolist()}

    def differs(self, check: Check, values: np.ndarray, reference: np.ndarray) -> bool:
        if values.shape != reference.shape:
            return True
        return not self._judge(check, values)[0]

    def nearest(self, check: Check, got, expected, candidates: dict) -> str | None:
        """The known mistake whose pdf integrates as the student's does (within half the
        tolerance at every view)."""
        best, best_off = None, check.options["tolerance"] / 2.0
        mine = np.nan_to_num(np.asarray(got, np.float64), nan=np.inf).reshape(-1, 2)[:, 0]
        for key, other in candidates.items():
            if other.shape != got.shape:
                continue
            off = float(np.max(np.abs(mine - other.reshape(-1, 2)[:, 0])))
            if off <= best_off:
                best, best_off = key, off
        return best


KIND = PdfIntegralKind()

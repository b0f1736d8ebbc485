"""`kind = "pdf_integral"`: the student's pdf integrated over the sphere per view (adaptive
quadrature in the turned frames of chi_square), against the solution's within `tolerance`:
a density integrates to 1, less the share of samples the sampler wastes."""

from __future__ import annotations

import numpy as np

from lab.grading import sampling
from lab.grading.kinds.sampled import SampledKind
from lab.grading.result import CheckResult, failed, passed
from lab.grading.spec import Check, ExerciseError


class PdfIntegralKind(SampledKind):
    name = "pdf_integral"
    order = 51
    fields = {"views": [[5.0, 0.0], [60.0, 300.0]], "tolerance": 0.01}

    def validate(self, check: Check, where: str) -> None:
        super().validate(check, where)
        if not 0.0 < check.options["tolerance"] < 0.5:
            raise ExerciseError(f"{where}: check {check.name}: tolerance must lie in (0, 0.5)")

    def render(self, renderer, model, check: Check) -> np.ndarray:
        return sampling.pdf_integral_raw(
            renderer, model, check.params, self.views(check), check.seed
        )

    def stored(self, raw: np.ndarray, check: Check) -> np.ndarray:
        return raw.astype(np.float64)

    def compare(self, check: Check, expected: np.ndarray, raw: np.ndarray) -> CheckResult:
        ok, message, _ = sampling.judge_pdf_integral(
            raw, expected, self.views(check), check.options["tolerance"]
        )
        extra = {"extra": {"integrals": [float(v) for v in np.nan_to_num(raw)]}}
        return passed(check, message, **extra) if ok else failed(check, message, **extra)

    def practice(self, exercise, check: Check, values) -> dict:
        return {**self.practice_views(check), "reference": values[check.name].tolist()}

    def differs(self, check: Check, values: np.ndarray, reference: np.ndarray) -> bool:
        if values.shape != reference.shape:
            return True
        views = self.views(check)
        return not sampling.judge_pdf_integral(
            values, reference, views, check.options["tolerance"]
        )[0]

    def nearest(self, check: Check, got, expected, candidates: dict) -> str | None:
        best, best_off = None, check.options["tolerance"] / 2.0
        for key, other in candidates.items():
            if other.shape != got.shape:
                continue
            off = float(np.max(np.abs(np.nan_to_num(got, nan=np.inf) - other)))
            if off <= best_off:
                best, best_off = key, off
        return best


KIND = PdfIntegralKind()

"""The shared part of kinds that evaluate the BRDF at direction pairs (probe, polar)."""

from __future__ import annotations

import base64

import numpy as np

from lab.grading import diagnosis
from lab.grading.compare import compare_values
from lab.grading.kinds import CheckKind
from lab.grading.result import CheckResult
from lab.grading.spec import Check


def floats_b64(array: np.ndarray) -> str:
    """Little-endian float32 bytes in base64 (how the web page reads arrays)."""
    return base64.b64encode(np.ascontiguousarray(array, dtype="<f4").tobytes()).decode()


class ValueKind(CheckKind):
    """f_r at the rows of `angles`, within atol + rtol |expected| of the solution's."""

    what = "values"  # the rows, in the check's messages ("all 274 direction pairs match")
    diagnose_terms = True

    def angles(self, check: Check) -> np.ndarray:
        raise NotImplementedError

    def render(self, renderer, model, check: Check) -> np.ndarray:
        return renderer.eval_angles(model, check.params, self.angles(check))

    def compare(self, check: Check, expected: np.ndarray, raw: np.ndarray) -> CheckResult:
        return compare_values(check, self.angles(check), expected, raw, self.what)

    def differs(self, check: Check, values: np.ndarray, reference: np.ndarray) -> bool:
        return not diagnosis.same(check, values, reference) or bool(
            (~np.isfinite(values)).any() or (values < 0).any()
        )

    def nearest(self, check, got, expected, candidates) -> str | None:
        wrong = ~diagnosis.within(check, got, expected, slack=1.0)
        return diagnosis.nearest(check, got, candidates, wrong)

    def explain(self, explainer, exercise, check, model, expected, got, live: bool) -> str:
        """Which declared term is wrong, else the shape of the error, else a swap of L and V
        or of the tangent axes, else the lobe's peak or width (lobe)."""
        angles = self.angles(check)
        text = explainer.terms(exercise, check, model, angles, live)
        text = text or diagnosis.shape(check, angles, expected, got)
        text = text or explainer.swaps(check, model, angles, expected)
        return text or self.lobe(check, angles, expected, got, exercise.model_name)

    def lobe(self, check: Check, angles: np.ndarray, expected, got, model: str = "") -> str:
        """What the values' lobe says (peak, width), where the rows form one; '' here."""
        return ""

    def practice(self, exercise, check: Check, values) -> dict:
        angles = self.angles(check)
        return {
            "what": self.what,
            "angles": floats_b64(angles),  # degrees: theta_i, phi_i, theta_o, phi_o
            "expected": floats_b64(values[check.name][:, :3]),
            "count": len(angles),
        }

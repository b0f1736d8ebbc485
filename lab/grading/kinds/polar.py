"""`kind = "polar"`: f_r along the plane of incidence for a light at (`theta_i`, `phi_i`),
reported with the two polar curves."""

from __future__ import annotations

import numpy as np

from lab.constants import LUMA
from lab.grading import diagnosis
from lab.grading.compare import luminance, wrong_values
from lab.grading.kinds.values import ValueKind
from lab.grading.result import CheckResult
from lab.grading.spec import Check


def polar_angles(check: Check) -> np.ndarray:
    """Rows for the plane of incidence, theta_o from -88 to 88 deg (negative: light side).

    Exactly grazing views are left out: there N.V is 0 up to rounding and f_r of
    microfacet models swings with the last bit of the driver's arithmetic.
    """
    theta = np.arange(-88.0, 88.5, 1.0)
    phi_o = np.where(theta >= 0.0, check.phi_i + 180.0, check.phi_i)
    return np.stack(
        [
            np.full_like(theta, check.theta_i),
            np.full_like(theta, check.phi_i),
            np.abs(theta),
            phi_o % 360.0,
        ],
        axis=1,
    )


def signed_theta(check: Check, angles: np.ndarray) -> np.ndarray:
    """theta_o of each row, negative on the light's side."""
    return np.where(angles[:, 3] == check.phi_i % 360.0, -angles[:, 2], angles[:, 2])


class PolarKind(ValueKind):
    name = "polar"
    order = 30
    what = "points of the polar curve"

    def angles(self, check: Check) -> np.ndarray:
        return polar_angles(check)

    def compare(self, check: Check, expected: np.ndarray, raw: np.ndarray) -> CheckResult:
        result = super().compare(check, expected, raw)
        angles = self.angles(check)
        tolerance = self.tolerance(check, angles, expected, raw)
        result.failing = np.nonzero(wrong_values(check, expected, raw, tolerance))[0].tolist()
        result.curve = {
            "theta_o": signed_theta(check, angles).tolist(),
            "expected": luminance(expected),
            "got": luminance(raw),
            "theta_i": check.theta_i,
        }
        return result

    def lobe(self, check: Check, angles: np.ndarray, expected, got, model: str = "") -> str:
        """The polar curve's peak and width (luminance), against the solution's."""
        lum = np.array(LUMA)
        return diagnosis.lobe(
            check,
            signed_theta(check, angles),
            expected @ lum,
            np.nan_to_num(got) @ lum,
            check.params,
            model,
        )


KIND = PolarKind()

"""The shared part of kinds that evaluate the BRDF at direction pairs (probe, polar)."""

from __future__ import annotations

import base64
import functools

import numpy as np

from lab.grading import diagnosis, tables
from lab.grading.compare import compare_values
from lab.grading.kinds import CheckKind
from lab.grading.result import CheckResult
from lab.grading.spec import Check


def floats_b64(array: np.ndarray) -> str:
    """Little-endian float32 bytes in base64 (how the web page reads arrays)."""
    return base64.b64encode(np.ascontiguousarray(array, dtype="<f4").tobytes()).decode()


# How far a correct program written in another form may be from the solution at a row,
# measured on the float64 reference (lab.reference) at directions moved by DELTA radians:
# float32 rounds a cosine near +-1 by about 1e-7, which is an angle of sqrt(2e-7) = DELTA
# (L + V nearly 0, N.H near 1: a rewrite's H or N.H can be that far off). Elsewhere the
# first-order change is scaled to FIRST radians, the angle error of float32 directions with
# a wide margin. The tolerance of a row is the check's, or GROW times that estimate, or
# ROUNDING times the solution's own float32 error against the float64 reference there.
DELTA = 4.5e-4
FIRST = 1e-5
GROW = 4.0
ROUNDING = 2.0
TRIALS = 6


def _frozen(value):
    return tuple(value) if isinstance(value, (list, tuple, np.ndarray)) else value


@functools.lru_cache(maxsize=128)
def _spread(model: str, params: tuple, angles: bytes, n: int) -> tuple | None:
    """(n, 3) float32 error a correct float32 program may make at each row and the float64
    values there, or None where lab.reference has no such model (then the check's own
    tolerance stands)."""
    from lab import reference

    rows = np.frombuffer(angles, dtype=np.float64).reshape(n, 4)
    try:
        theta = np.radians(rows)
        L = reference.direction(theta[:, 0], theta[:, 1])
        V = reference.direction(theta[:, 2], theta[:, 3])
        settings = dict(params)
        base = reference.brdf(model, settings, L, V)
    except (ValueError, KeyError, TypeError):
        return None
    rng = np.random.default_rng(12345)
    spread = np.zeros_like(base)
    below = (L[:, 2] <= 0.0) | (V[:, 2] <= 0.0)
    for _ in range(TRIALS):
        moves = [rng.normal(size=L.shape) for _ in range(2)]
        moves = [m / np.linalg.norm(m, axis=1, keepdims=True) * DELTA for m in moves]
        values = []
        for sign in (1.0, -1.0):
            dl, dv = (normalize(d + sign * m) for d, m in zip((L, V), moves, strict=True))
            values.append(reference.brdf(model, settings, dl, dv))
        first = np.abs(values[0] - values[1]) * (0.5 * FIRST / DELTA)
        second = np.abs(0.5 * (values[0] + values[1]) - base)
        spread = np.maximum(spread, first + second)
    # A row below the horizon is 0 for every correct program; one moved across the horizon
    # by DELTA (within a hundredth of a degree of it) says nothing about the formula.
    spread[below] = 0.0
    spread *= GROW
    spread.flags.writeable = base.flags.writeable = False
    return spread, base


def normalize(v: np.ndarray) -> np.ndarray:
    return v / np.linalg.norm(v, axis=1, keepdims=True)


def row_tolerance(check: Check, angles: np.ndarray, expected: np.ndarray) -> np.ndarray | None:
    """Each value's tolerance: the check's atol + rtol |expected|, or more where the exact
    answer is ill-conditioned (a correct program in another form is as far off); None when
    the check's model is not in lab.reference (the plain tolerance then)."""
    if not check.model:
        return None
    params = {**check.defaults, **check.params}
    key = tuple(sorted((k, _frozen(v)) for k, v in params.items()))
    rows = np.ascontiguousarray(angles, dtype=np.float64)
    found = _spread(check.model, key, rows.tobytes(), len(rows))
    if found is None or found[0].shape != expected.shape[:1] + (3,):
        return None
    spread, exact = found
    plain = check.atol + check.rtol * np.abs(expected[:, :3])
    with np.errstate(invalid="ignore"):
        rounding = ROUNDING * np.nan_to_num(np.abs(expected[:, :3] - exact))
    return np.maximum(np.maximum(plain, spread), rounding).astype(np.float32)


class ValueKind(CheckKind):
    """f_r at the rows of `angles`, within atol + rtol |expected| of the solution's."""

    what = "values"  # the rows, in the check's messages ("all 274 direction pairs match")
    diagnose_terms = True

    def angles(self, check: Check) -> np.ndarray:
        raise NotImplementedError

    def render(self, renderer, model, check: Check) -> np.ndarray:
        return renderer.eval_angles(model, check.params, self.angles(check))

    def compare(self, check: Check, expected: np.ndarray, raw: np.ndarray) -> CheckResult:
        angles = self.angles(check)
        tolerance = self.tolerance(check, angles, expected, raw)
        return compare_values(check, angles, expected, raw, self.what, tolerance)

    @staticmethod
    def tolerance(check: Check, angles, expected, raw) -> np.ndarray | None:
        """Per value: the check's tolerance, grown where the exact answer is ill-conditioned
        (row_tolerance); None (the check's own) where the shapes are not per row RGB."""
        if expected.ndim != 2 or expected.shape[1] < 3 or raw.shape[:1] != expected.shape[:1]:
            return None
        tolerance = row_tolerance(check, angles, expected[:, :3])
        lookup = tables.spread(check, angles)  # a table's lookup is as well-conditioned
        if lookup is not None and lookup.shape == expected[:, :3].shape:
            plain = check.atol + check.rtol * np.abs(expected[:, :3])
            base = plain if tolerance is None else tolerance
            tolerance = np.maximum(base, plain + lookup).astype(np.float32)
        if tolerance is None or expected.shape[1] == 3:
            return tolerance
        pad = check.atol + check.rtol * np.abs(expected[:, 3:])  # channels past RGB as before
        return np.concatenate([tolerance, pad], axis=1)

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
        expected = values[check.name][:, :3]
        entry = {
            "what": self.what,
            "angles": floats_b64(angles),  # degrees: theta_i, phi_i, theta_o, phi_o
            "expected": floats_b64(expected),
            "count": len(angles),
        }
        tolerance = self.tolerance(check, angles, expected, expected)  # a table's too
        if tolerance is not None:  # the grader's own, row by row
            entry["tolerance"] = floats_b64(tolerance)
        return entry

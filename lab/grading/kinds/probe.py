"""`kind = "probe"`: f_r at random direction pairs (fixed by `seed`, `pairs` of them) and at
the special directions where formulas divide by zero."""

from __future__ import annotations

import functools

import numpy as np

from lab.grading.kinds.values import ValueKind
from lab.grading.spec import Check


def probe_angles(check: Check) -> np.ndarray:
    """(pairs + 18, 4) rows theta_i, phi_i, theta_o, phi_o in degrees, fixed by the check's
    seed; the last 18 are the special directions (special_angles).

    Half the pairs are spread over the hemisphere, 3/8 lie near the mirror direction
    (where the highlights are) and 1/8 have L or V below the horizon (must give 0).
    The rows are made once per (seed, pairs) and shared read-only: every student's check
    evaluates, compares and explains the same rows.
    """
    return _probe_rows(int(check.seed), int(check.pairs))


@functools.lru_cache(maxsize=256)
def _probe_rows(seed: int, n: int) -> np.ndarray:
    rng = np.random.default_rng(seed)
    n_mirror, n_below = 3 * n // 8, n // 8
    n_spread = n - n_mirror - n_below
    theta_i = np.degrees(np.arccos(rng.uniform(0.05, 1.0, n)))
    phi_i = rng.uniform(0.0, 360.0, n)
    theta_o = np.degrees(np.arccos(rng.uniform(0.05, 1.0, n)))
    phi_o = rng.uniform(0.0, 360.0, n)
    near = slice(n_spread, n_spread + n_mirror)
    theta_o[near] = np.clip(theta_i[near] + rng.normal(0.0, 4.0, n_mirror), 0.5, 88.0)
    phi_o[near] = phi_i[near] + 180.0 + rng.normal(0.0, 6.0, n_mirror)
    below = slice(n_spread + n_mirror, n)
    flip_light = rng.random(n_below) < 0.5
    theta_i[below] = np.where(flip_light, 180.0 - theta_i[below], theta_i[below])
    theta_o[below] = np.where(flip_light, theta_o[below], 180.0 - theta_o[below])
    rows = np.stack([theta_i, phi_i % 360.0, theta_o, phi_o % 360.0], axis=1)
    table = np.concatenate([rows, special_angles(float(rng.uniform(0.0, 360.0)))])
    table.flags.writeable = False
    return table


def special_angles(phi: float) -> np.ndarray:
    """Rows where formulas divide by zero or lose precision: L = N, V = N, L = V, the exact
    mirror direction, beside it in the plane of incidence and across it, and 89.9 degrees
    from the normal (an Inf or NaN at any of them fails the check)."""
    back = phi + 180.0
    rows = [
        (0.0, 0.0, 0.0, 0.0),  # L = V = N
        (0.0, 0.0, 35.0, phi),  # L = N
        (0.0, 0.0, 70.0, back),
        (35.0, phi, 0.0, 0.0),  # V = N
        (70.0, phi, 0.0, 0.0),
        (30.0, phi, 30.0, phi),  # L = V
        (75.0, phi, 75.0, phi),
        (20.0, phi, 20.0, back),  # the exact mirror direction
        (45.0, phi, 45.0, back),
        (70.0, phi, 70.0, back),
        (45.0, phi, 35.0, back),  # in the plane of incidence, beside the mirror
        (45.0, phi, 55.0, back),
        (45.0, phi, 45.0, phi + 90.0),  # perpendicular to the plane of incidence
        (45.0, phi, 45.0, phi + 270.0),
        (89.9, phi, 30.0, back),  # grazing light, grazing view, both
        (30.0, phi, 89.9, back),
        (89.9, phi, 89.9, back),
        (89.9, phi, 89.9, phi + 90.0),
    ]
    table = np.array(rows, dtype=np.float64)
    table[:, [1, 3]] %= 360.0
    return table


class ProbeKind(ValueKind):
    name = "probe"
    order = 10
    purpose_of = ""  # its rows are drawn from `seed`: spread, near the mirror and below
    what = "direction pairs"

    def angles(self, check: Check) -> np.ndarray:
        return probe_angles(check)


KIND = ProbeKind()

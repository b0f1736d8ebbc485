"""`kind = "bin_edges"`: f_r at direction pairs placed on a tabulated BRDF's bin grid: bin
centres, just either side of bin edges (theta_h's square-root spacing near the peak,
theta_d, phi_d and its fold at 0 and 180 degrees) and at grazing theta_d, where a lookup
that misplaces a bin, forgets to fold or fails to wrap or clamp differs from the solution
while random pairs rarely show it.

The grid is that of the check's `table` (lab.grading.tables), else the MERL grid
(90, 90, 180). Rows are drawn from `seed` (`pairs` of them) and turned about the normal by
a random azimuth each (an isotropic table does not depend on it).
"""

from __future__ import annotations

import functools
import math

import numpy as np

from lab.grading.kinds.values import ValueKind
from lab.grading.spec import Check
from lab.measured.merl import MERL_DIMS, continuous_index, directions, half_diff

# How far from an edge a row lies, in bins: float32 places a pair to about 1e-4 of a bin
# (theta_h's first bins are 0.01 degrees wide), so a correct float32 program puts each row
# in the same bin as the solution; a misplaced bin or a missing fold moves it a whole bin.
MARGIN = 0.05
ABOVE = 2e-3  # cos(theta) of both directions at least this: the pair is above the horizon
# A row is kept only where its position is well-conditioned: directions moved by JITTER
# radians (about ten times float32's error in them) keep its bin and move it less than
# STEADY bins on each axis (a float32 program then moves it about a twentieth of that, and
# a linear lookup's value by far less than the tolerance). Near H = N, phi_h and with it
# phi_d are lost to rounding (below theta_h's second bin), and a grazing pair's H is too
# (L + V nearly 0): such rows would test the arithmetic, not the index.
JITTER = 1e-6
STEADY = 0.1
TRIALS = 4


def edge_angles(check: Check) -> np.ndarray:
    """(pairs, 4) rows theta_i, phi_i, theta_o, phi_o in degrees on the check's bin grid."""
    dims = check.table[0].dims if getattr(check, "table", ()) else MERL_DIMS
    return _rows(int(check.seed), int(check.pairs), tuple(dims))


def _positions(rng: np.random.Generator, kind: str, n: int, dims) -> np.ndarray:
    """(n, 3) positions in bin units (theta_h, theta_d, phi_d) for one class of rows: the
    coordinates a class does not test lie well inside a bin (0.15 to 0.85 of it)."""
    n_h, n_d, n_p = dims
    inside = rng.uniform(0.15, 0.85, (n, 3))
    pos = np.floor(rng.uniform(0.0, 1.0, (n, 3)) * np.array(dims)) + inside
    side = np.where(rng.random(n) < 0.5, -MARGIN, MARGIN)
    low_h = np.floor(rng.uniform(0.0, 0.6, n) ** 2 * n_h) + inside[:, 0]  # towards the peak
    low_d = np.floor(rng.uniform(0.0, 0.6, n) * n_d) + inside[:, 1]  # both above the horizon
    if kind == "centre":
        pos = np.floor(pos) + 0.5
    elif kind == "theta_h":  # half of them in the first bins, a few hundredths of a degree
        near = rng.integers(min(2, n_h - 1), min(5, n_h), n)
        anywhere = rng.integers(1, n_h, n)
        pos[:, 0] = np.where(rng.random(n) < 0.5, near, anywhere) + side
        pos[:, 1] = low_d
    elif kind == "theta_d":
        pos[:, 0] = low_h
        pos[:, 1] = rng.integers(1, n_d, n) + side
    elif kind == "phi_d":  # half at the fold: just above 0 and just below 180 degrees
        wrap = rng.random(n) < 0.5
        pos[:, 2] = np.where(wrap, 0, rng.integers(1, n_p, n)) + side
        pos[:, 2] = np.where(pos[:, 2] < 0.0, pos[:, 2] + n_p, pos[:, 2])
        pos[:, :2] = np.stack([low_h, low_d], axis=1)
    elif kind == "grazing":  # theta_d in its last bins: L and V near the horizon
        pos[:, 0] = np.floor(rng.uniform(0.0, 0.1, n) * n_h) + inside[:, 0]
        pos[:, 1] = n_d - 1 - np.floor(rng.uniform(0.0, 0.06 * n_d, n)) + inside[:, 1]
    return pos


@functools.lru_cache(maxsize=64)
def _rows(seed: int, n: int, dims: tuple[int, int, int]) -> np.ndarray:
    rng = np.random.default_rng(seed)
    shares = {"centre": 2, "theta_h": 5, "theta_d": 2, "phi_d": 4, "grazing": 3}
    total = sum(shares.values())
    counts = {k: n * v // total for k, v in shares.items()}
    counts["theta_h"] += n - sum(counts.values())
    n_h, n_d, n_p = dims
    rows = []
    for kind, count in counts.items():
        found: list[np.ndarray] = []
        have = 0
        for _ in range(50):
            if have >= count:
                break
            pos = _positions(rng, kind, 4 * max(count, 1), dims)
            theta_h = (np.maximum(pos[:, 0], 0.0) / n_h) ** 2 * (math.pi / 2)
            theta_d = np.clip(pos[:, 1], 0.0, n_d) / n_d * (math.pi / 2)
            phi_d = pos[:, 2] / n_p * math.pi
            # phi_d and phi_d - 180 degrees are one bin: half of the rows come the other way
            phi_d = np.where(rng.random(len(pos)) < 0.5, phi_d - math.pi, phi_d)
            L, V = directions(theta_h, theta_d, phi_d)
            keep = (L[:, 2] > ABOVE) & (V[:, 2] > ABOVE) & _steady(rng, L, V, dims)
            turn = rng.uniform(0.0, 2.0 * math.pi, len(pos))
            pair = np.concatenate([_angles(L, turn), _angles(V, turn)], axis=1)[keep]
            found.append(pair)
            have += len(pair)
        if have < count:  # the classes are built to fill easily; a tiny custom grid may not
            raise ValueError(f"bin_edges: only {have} of {count} {kind} rows on grid {dims}")
        rows.append(np.concatenate(found)[:count])
    table = np.concatenate(rows)
    table.flags.writeable = False
    return table


def _steady(rng: np.random.Generator, L: np.ndarray, V: np.ndarray, dims) -> np.ndarray:
    """Rows whose bin position stays put when L and V move by JITTER (see STEADY)."""
    base = np.stack(continuous_index(*half_diff(L, V), dims), axis=1)
    ok = np.ones(len(L), dtype=bool)
    period = float(dims[2])
    for _ in range(TRIALS):
        moved = []
        for d in (L, V):
            step = rng.normal(size=d.shape)
            d = d + JITTER * step / np.linalg.norm(step, axis=1, keepdims=True)
            moved.append(d / np.linalg.norm(d, axis=1, keepdims=True))
        pos = np.stack(continuous_index(*half_diff(*moved), dims), axis=1)
        change = np.abs(pos - base)
        change[:, 2] = np.minimum(change[:, 2], period - change[:, 2])  # phi_d wraps
        ok &= (change < STEADY).all(axis=1) & (np.floor(pos) == np.floor(base)).all(axis=1)
    return ok


def _angles(d: np.ndarray, turn: np.ndarray) -> np.ndarray:
    """(n, 2) theta, phi in degrees of directions d turned by `turn` about the normal."""
    theta = np.degrees(np.arccos(np.clip(d[:, 2], -1.0, 1.0)))
    phi = (np.degrees(np.arctan2(d[:, 1], d[:, 0]) + turn)) % 360.0
    return np.stack([theta, phi], axis=1)


class BinEdgesKind(ValueKind):
    name = "bin_edges"
    order = 62
    purpose_of = ""  # its rows are drawn from `seed` on the table's grid
    what = "pairs on the table's bin grid"

    def angles(self, check: Check) -> np.ndarray:
        return edge_angles(check)


KIND = BinEdgesKind()

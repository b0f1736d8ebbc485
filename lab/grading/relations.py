"""How two arrays of values relate: agreement within float32 noise, and the simple
relations a slip leaves between a student's value and the quantity it stands for (opposite
sign, a constant factor, 1 − x, a missing clamp, a power, a term too many or too few, a
factor too many or too few). Plain numpy; lab.grading.localise applies it to traces."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

AGREE = 0.97  # share of the rows both ran on that must agree for a match or a relation
RTOL, ATOL = 2e-3, 1e-5
MIN_ROWS = 8
NICE_POWERS = {k / 2 for k in range(-8, 9)} | {1 / n for n in range(2, 11)}
NAMED_FACTORS = (
    (math.pi, "π"),
    (1 / math.pi, "1/π"),
    (2.0, "2"),
    (0.5, "1/2"),
    (4.0, "4"),
    (0.25, "1/4"),
    (180 / math.pi, "180/π (degrees where radians belong)"),
    (math.pi / 180, "π/180 (radians where degrees belong)"),
    (8.0, "8"),
    (0.125, "1/8"),
    (2 * math.pi, "2π"),
    (1 / (2 * math.pi), "1/(2π)"),
)


@dataclass
class Quantity:
    label: str
    values: np.ndarray  # (rows, components)
    ran: np.ndarray  # bool (rows,)
    name: str = ""  # the variable it is kept in, if any
    text: str = ""  # what it is computed as, for a named quantity


def agree(a: np.ndarray, b: np.ndarray, scale: float | None = None) -> np.ndarray:
    """Rows where two value arrays agree within the float32 noise of a rewrite (`scale`:
    the size of the values, for the absolute part; by default b's mean)."""
    with np.errstate(invalid="ignore"):
        size = float(np.nanmean(np.abs(b))) if scale is None else scale
        tol = RTOL * np.maximum(np.abs(a), np.abs(b)) + ATOL * (1.0 + size)
        close = np.abs(a - b) <= tol
    close |= np.isnan(a) & np.isnan(b)
    return close.all(axis=-1)


def shared_rows(s_ran: np.ndarray, q: Quantity) -> np.ndarray | None:
    joint = s_ran & q.ran & np.isfinite(q.values).all(axis=-1)
    return joint if joint.sum() >= max(MIN_ROWS, 0.25 * s_ran.sum()) else None


def matches(values: np.ndarray, ran: np.ndarray, q: Quantity) -> bool:
    if values.shape[1] != q.values.shape[1]:
        return False
    joint = shared_rows(ran, q)
    if joint is None:
        return False
    return bool(agree(values[joint], q.values[joint]).mean() >= AGREE)


def varies(q: np.ndarray) -> bool:
    """Do the values change over the rows (more than float32 noise)?"""
    q = np.asarray(q, np.float64)
    if q.size == 0 or not np.isfinite(q).all():
        return bool(q.size) and _varies_slow(q)
    spread = float(q.std())
    return spread > 1e-4 * (1.0 + float(np.abs(q).mean()))


def _varies_slow(q: np.ndarray) -> bool:
    spread = np.nanstd(q)
    return bool(np.isfinite(spread) and spread > 1e-4 * (1.0 + np.nanmean(np.abs(q))))


def factor_name(c: float) -> str:
    for value, name in NAMED_FACTORS:
        if abs(c - value) <= 2e-3 * value:
            return name
    return f"{c:.3g}"


def named_factor(phrase: str) -> bool:
    """Is a relation() phrase a named constant factor ('is 2 × {q}', 'is π × {q}')?"""
    return any(phrase == f"is {name} × {{q}}" for _, name in NAMED_FACTORS)


def relation(s: np.ndarray, q: np.ndarray) -> str:
    """How the student's values s relate to a quantity's q on the same rows: a phrase with
    {q} for the quantity's name, or '' when no simple relation holds nearly everywhere."""
    if not varies(q):
        return ""
    ok = judge(s, q)
    if ok(-q):
        return "has the opposite sign of {q}"
    big = np.abs(q) > 1e-3 * np.abs(q).max()
    if big.sum() >= MIN_ROWS:
        c = float(np.median(s[big] / q[big]))
        if np.isfinite(c) and abs(c - 1.0) > 1e-2 and c != 0.0 and ok(c * q):
            return f"is {factor_name(c)} × {{q}}"
        total = float(np.median(s + q))
        if abs(total) > 1e-3 and ok(total - q):
            return (
                f"is {total:.3g} − {{q}}"
                if abs(total - round(total)) > 1e-3
                else (f"is {round(total)} − {{q}}")
            )
    if ok(np.maximum(q, 0.0)) and (q < -1e-4).mean() > 0.01:
        return "is clamped at 0 where {q} goes negative"
    if (q >= 0).all() and ok(np.where(q > 0, q, np.minimum(s, 0.0))) and (s < -1e-4).any():
        return "is not clamped at 0: it goes negative where {q} is 0"
    inside = ((q > 1e-3) & (q < 0.999) & (s > 1e-30)).all(axis=-1)
    if inside.sum() >= max(MIN_ROWS, len(q) // 10) and s.shape[1] == 1:
        p = float(np.median(np.log(s[inside]) / np.log(q[inside])))
        nice = any(abs(p - n) < 2e-3 * max(1.0, abs(n)) for n in NICE_POWERS)
        with np.errstate(all="ignore"):
            powered = np.sign(q) * np.abs(q) ** p
        if nice and abs(p - 1.0) > 1e-2 and ok(powered):
            return f"is {{q}} to the power {p:.3g}"
    return ""


def judge(s: np.ndarray, q: np.ndarray):
    """A test of a guessed relation: s agrees with the guess on nearly every row where s
    or q is not negligible (two lobes that are both nearly 0 away from their peaks
    agree there whatever their relation)."""
    size = np.abs(s).max(axis=-1) + np.abs(q).max(axis=-1)
    rows = size > 1e-3 * np.nanmax(size) if np.isfinite(size).any() else size > 0
    scale = float(np.nanmean(np.abs(q))) if np.isfinite(q).any() else 0.0

    def ok(guess: np.ndarray) -> bool:
        if rows.sum() < MIN_ROWS:
            return False
        guess = np.broadcast_to(guess, s.shape)
        return bool(agree(s[rows], guess[rows], scale).mean() >= AGREE)

    return ok


def term(
    s: np.ndarray, q: np.ndarray, joint: np.ndarray, others: list[Quantity], meant: Quantity
) -> str:
    """s is q with one of its terms or factors changed: a missing or extra term r
    (s = q + c r), or a factor r too many or too few (s = q r, s = q / r)."""
    diff, ok = s - q, judge(s, q)
    usable = []
    for other in others:
        if other is meant or other.values.shape[1] not in (1, s.shape[1]):
            continue
        r = other.values[joint]
        if not other.ran[joint].all() or not np.isfinite(r).all():
            continue
        big = (np.abs(r) > 1e-6).all(axis=-1)
        if big.sum() >= MIN_ROWS:
            usable.append((other, r, big))
    # A whole term missing first: where ks = 0.5, a missing ks·(N·H)^ke is also "(N·H)^ke
    # multiplied by 1/2", which reads as a factor slip the student never made.
    scaled = []
    for other, r, big in usable:
        ratios = diff[big] / r[big]
        c = float(np.median(ratios))
        k = c + 1.0
        steady = np.abs(ratios - c).mean() <= 0.05 * abs(c)  # a first look, before `ok`
        if np.isfinite(c) and abs(c) > 1e-3 and steady and ok(q + c * r):
            if abs(k) < 1e-3:
                return f"lacks the term {other.label} that {meant.label} has"
            if factor_name(k) != f"{k:.3g}":  # a named factor: π, 2, 1/2...
                scaled.append(f"is {meant.label} with its term {other.label} multiplied by ")
                scaled[-1] += factor_name(k)
    if scaled:
        return scaled[0]
    for other, r, _ in usable:
        if not varies(r):
            continue
        if ok(q * r):
            return f"is {meant.label} multiplied by {other.label}"
        if ok(q / np.where(r == 0, np.nan, r)):
            return f"is {meant.label} divided by {other.label}"
    return ""


class Matcher:
    """`matches` against many quantities at once (one array operation per student value,
    not one per pair: a trace has a hundred values and the solution a hundred more)."""

    def __init__(self, quantities: list[Quantity]) -> None:
        self.quantities = quantities
        self.groups: dict[int, tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]] = {}
        for count in {q.values.shape[1] for q in quantities}:
            index = np.array([i for i, q in enumerate(quantities) if q.values.shape[1] == count])
            values = np.stack([quantities[i].values for i in index])  # (Q, rows, count)
            ran = np.stack([quantities[i].ran for i in index])
            ran &= np.isfinite(values).all(axis=-1)
            with np.errstate(invalid="ignore", over="ignore"):
                total = np.where(ran[..., None], np.abs(values), 0.0).sum(axis=(1, 2))
            size = total / np.maximum(ran.sum(axis=1) * count, 1)
            self.groups[count] = (index, values, ran, np.nan_to_num(size))

    def which(self, values: np.ndarray, ran: np.ndarray) -> set[int]:
        """Indices of the quantities the values match (as `matches` would say)."""
        group = self.groups.get(values.shape[1])
        if group is None:
            return set()
        index, known, known_ran, size = group
        joint = ran[None, :] & known_ran
        count = joint.sum(axis=1)
        enough = count >= max(MIN_ROWS, 0.25 * ran.sum())
        with np.errstate(invalid="ignore", over="ignore"):
            a = values[None]
            tol = RTOL * np.maximum(np.abs(a), np.abs(known)) + ATOL * (1.0 + size)[:, None, None]
            close = (np.abs(a - known) <= tol) | (np.isnan(a) & np.isnan(known))
        agreeing = (close.all(axis=-1) & joint).sum(axis=1)
        hit = enough & (agreeing >= AGREE * np.maximum(count, 1))
        return {int(i) for i in index[hit]}

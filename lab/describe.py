"""Words and tables for a lobe plot, for readers who cannot see it (WCAG 1.1.1).

A lobe is the luminance of f_r (or f_r cos θo) in the plane of incidence at θo = -90..90°;
positive θo lies on the far side from the light, so θo = θi is the mirror direction
(lab.geometry.plane_of_incidence). The page says the same words: lab/web/static/describe.js
mirrors this module and tests/test_a11y_describe.py holds the two to one fixture.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np

from lab.constants import GRAZING_DEG, LUMA

UNIT = "sr⁻¹"
NEAR_DEG = 2.0  # a peak this close to the mirror, the light or the normal is said to be there
FLAT = 0.97  # a lobe whose lowest value is this share of its peak is constant
SAME = 1.01  # peaks closer than this ratio are said to be the same height
TABLE_STEP = 5  # degrees between the rows of the table


def fmt(x: float) -> str:
    """Three significant digits, no exponent, no trailing zeros (describe.js: fmt)."""
    if not math.isfinite(x):
        return "∞" if x > 0 else "not a number"
    if x == 0:
        return "0"
    digits = max(0, 2 - math.floor(math.log10(abs(x))))
    text = f"{x:.{digits}f}"
    if "." in text:
        text = text.rstrip("0").rstrip(".")
    return text.replace("-", "−") if text not in ("-0", "0") else "0"


def deg(x: float) -> str:
    """An angle in whole degrees with a real minus sign."""
    value = int(round(x))
    return f"{value}°".replace("-", "−") if value else "0°"


@dataclass
class Lobe:
    """One model's lobe: its name, θo (degrees) and values; a δ spike's reflectance."""

    name: str
    theta_o: np.ndarray
    values: np.ndarray
    spike: float | None = None


@dataclass
class Summary:
    """What a description says of one lobe."""

    peak_theta: float
    peak: float
    floor: float
    half_width: float | None  # None: flat or zero
    wide: bool  # the half maximum is not reached on one side before the horizon


def summarise(lobe: Lobe) -> Summary:
    """Peak (away from grazing), half width at half maximum and the lowest value."""
    t = np.asarray(lobe.theta_o, dtype=np.float64)
    v = np.nan_to_num(np.asarray(lobe.values, dtype=np.float64), nan=0.0, posinf=0.0)
    v = np.maximum(v, 0.0)
    inside = np.abs(t) <= GRAZING_DEG
    k = int(np.flatnonzero(inside)[np.argmax(v[inside])])
    peak = float(v[k])
    floor = float(v[inside].min())
    if peak <= 0 or floor >= FLAT * peak:
        return Summary(float(t[k]), peak, floor, None, False)
    half = peak / 2
    wide = False

    def crossing(indices) -> float:
        nonlocal wide
        previous = k
        for j in indices:
            if v[j] < half:  # between samples previous and j, linearly
                a = (v[previous] - half) / (v[previous] - v[j])
                return float(t[previous] + a * (t[j] - t[previous]))
            previous = j
        wide = True
        return float(t[previous])

    left = crossing(range(k - 1, -1, -1))
    right = crossing(range(k + 1, len(t)))
    return Summary(float(t[k]), peak, floor, (right - left) / 2, wide)


def where(theta: float, theta_i: float) -> str:
    """Names the direction θo when it is a landmark."""
    if abs(theta - theta_i) <= NEAR_DEG and theta_i >= NEAR_DEG:
        return ", the mirror direction"
    if abs(theta + theta_i) <= NEAR_DEG and theta_i >= NEAR_DEG:
        return ", back toward the light"
    if abs(theta) <= NEAR_DEG:
        return ", the normal"
    return ""


def sentence(lobe: Lobe, theta_i: float, what: str = "f_r") -> str:
    """One lobe in words: peak, where it is, half width, floor (and a δ spike)."""
    s = summarise(lobe)
    parts = []
    if lobe.spike is not None:
        parts.append(
            f"a δ spike at θo {deg(theta_i)}, the mirror direction, reflectance {fmt(lobe.spike)}"
        )
    if s.peak <= 0:
        parts.append(f"{what} is 0 in this plane")
    elif s.half_width is None:
        parts.append(f"{what} {fmt(s.peak)} {UNIT} in every direction, no lobe")
    else:
        at_least = "at least " if s.wide else ""
        parts.append(
            f"peak of {what} at θo {deg(s.peak_theta)}{where(s.peak_theta, theta_i)}, "
            f"{fmt(s.peak)} {UNIT}; half width {at_least}{deg(s.half_width)}; "
            f"floor {fmt(s.floor)}"
        )
    return f"{lobe.name}, θi {deg(theta_i)}: " + "; ".join(parts) + "."


def describe(lobes: Sequence[Lobe], theta_i: float, what: str = "f_r") -> str:
    """The plot in words; with several lobes a comparison follows the sentences."""
    text = " ".join(sentence(lobe, theta_i, what) for lobe in lobes)
    if len(lobes) < 2:
        return text
    summaries = [summarise(lobe) for lobe in lobes]
    order = sorted(range(len(lobes)), key=lambda i: -summaries[i].peak)
    top = order[0]
    words = [f"Highest peak: {lobes[top].name}, {fmt(summaries[top].peak)} {UNIT}"]
    for i in order[1:]:
        if summaries[i].peak > 0:
            ratio = summaries[top].peak / summaries[i].peak
            lower = f"{fmt(ratio)} times lower" if ratio >= SAME else "the same height"
            words.append(f"{lobes[i].name} {lower}")
    lobed = [i for i in range(len(lobes)) if summaries[i].half_width is not None]
    if len(lobed) >= 2:
        narrow = min(lobed, key=lambda i: summaries[i].half_width)
        words.append(f"narrowest: {lobes[narrow].name}")
    return text + " " + "; ".join(words) + "."


def table(lobes: Sequence[Lobe], theta_i: float, step: int = TABLE_STEP) -> list[list[str]]:
    """Rows [θo, one value per lobe, mark] every `step` degrees; the header row first.
    The row nearest each lobe's peak is marked 'peak NAME' (not for a constant), θo = θi
    'mirror'."""
    header = ["θo (deg)", *[lobe.name for lobe in lobes], "mark"]
    rows = [header]
    # Only a lobe has a peak to mark (a constant's largest value is noise at its edge).
    summaries = [summarise(lobe) for lobe in lobes]
    peaks = [
        round(s.peak_theta / step) * step if s.half_width is not None else None for s in summaries
    ]
    mirror = round(theta_i / step) * step
    for theta in range(-90, 91, step):
        cells = [str(theta)]
        for lobe in lobes:
            k = int(np.argmin(np.abs(np.asarray(lobe.theta_o) - theta)))
            cells.append(fmt(max(float(np.nan_to_num(lobe.values[k], posinf=math.inf)), 0.0)))
        marks = [f"peak {lobe.name}" for lobe, p in zip(lobes, peaks, strict=True) if p == theta]
        if theta == mirror:
            marks.append("mirror")
        cells.append(", ".join(marks))
        rows.append(cells)
    return rows


def csv_text(rows: list[list[str]]) -> str:
    """The table as CSV (numbers with ASCII minus signs, names quoted when needed)."""

    def cell(text: str) -> str:
        text = text.replace("−", "-")
        return f'"{text}"' if ("," in text or '"' in text) else text

    return "\n".join(",".join(cell(c) for c in row) for row in rows) + "\n"


def cursor(lobe: Lobe, theta: float, what: str = "f_r") -> str:
    """What the keyboard cursor says at θo: 'θo −40°, f_r 0.52, 88 % of the peak'."""
    k = int(np.argmin(np.abs(np.asarray(lobe.theta_o) - theta)))
    value = max(float(np.nan_to_num(lobe.values[k])), 0.0)
    peak = summarise(lobe).peak
    share = f", {round(100 * value / peak)} % of the peak" if peak > 0 else ""
    return f"θo {deg(float(lobe.theta_o[k]))}, {what} {fmt(value)}{share}"


def reference_lobe(
    model: str, params: Mapping | None, theta_i: float, cos_weighted: bool = False
) -> Lobe:
    """A model's lobe from the numpy oracle (lab.reference), 1° steps as the plots sample."""
    from lab import reference
    from lab.geometry import plane_of_incidence

    theta_o, V = plane_of_incidence(theta_i, 0.0)
    L = np.repeat(reference.direction(np.radians(theta_i), 0.0), len(V), axis=0)
    f = reference.brdf(model, params or {}, L, V)
    values = f @ np.asarray(LUMA)
    if cos_weighted:
        values = values * np.maximum(V[:, 2], 0.0)
    spike = None
    if model in reference.DELTA_MODELS:
        spike = float(reference.delta_reflectance(model, params or {}, L[:1])[0] @ np.asarray(LUMA))
    return Lobe(model, theta_o, values, spike)

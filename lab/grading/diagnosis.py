"""What a failed check's numbers say about the mistake, in one or two plain sentences.

Everything here is numpy on the values a check already has: the solution's (`expected`)
and the student's (`got`) at the same direction pairs, plus the values of likely wrong
programs (lab.grading.mistakes). It never names a mistake the values do not show: each
test asks for the pattern on (nearly) every row, and says nothing otherwise.
"""

from __future__ import annotations

import functools
import math

import numpy as np

from lab.grading.exercise import Check
from lab.grading.words import DIAGNOSIS as WORDS
from lab.grading.words import joined

# Named factors, as a student would write them, and what their presence usually means.
CONSTANTS = (
    (math.pi, "π", "a factor 1/π is missing"),
    (1.0 / math.pi, "1/π", "there is a 1/π too many"),
    (2.0, "2", "a constant factor is off (2)"),
    (4.0, "4", "a constant factor is off (4, as in 4·N·L·N·V)"),
    (0.5, "1/2", "a constant factor is off (1/2)"),
    (0.25, "1/4", "a constant factor is off (1/4, as in 4·N·L·N·V)"),
)
CHANNELS = ("red", "green", "blue")
MATCH_SHARE = 0.98  # of the rows: a pattern must hold nearly everywhere to be named
GRAZING = 65.0  # degrees: beyond this a direction counts as near grazing


def within(check: Check, got: np.ndarray, want: np.ndarray, slack: float = 2.0) -> np.ndarray:
    """Rows where `got` is within (a little more than) the check's tolerance of `want`."""
    tol = slack * (check.atol + check.rtol * np.abs(want))
    with np.errstate(invalid="ignore"):
        close = np.abs(got - want) <= tol
    # the same infinity, or NaN where the other has NaN, agrees too (a variant that breaks)
    close |= (got == want) | (np.isnan(got) & np.isnan(want))
    return close.all(axis=-1)


def same(check: Check, got: np.ndarray, want: np.ndarray) -> bool:
    """Nearly every row agrees: two programs that behave alike on this check."""
    return bool(within(check, got, want).mean() >= MATCH_SHARE)


def nearest(
    check: Check, got: np.ndarray, candidates: dict[str, np.ndarray], wrong: np.ndarray
) -> str | None:
    """The candidate (a variant's values) the student's values agree with, if any: on
    nearly every row, and on nearly every row where the student is wrong."""
    best, best_share = None, MATCH_SHARE
    for key, values in candidates.items():
        if values.shape != got.shape:
            continue
        agree = within(check, got, values)
        if wrong.any() and agree[wrong].mean() < 0.9:
            continue
        share = float(agree.mean())
        if share >= best_share and (best is None or share > best_share):
            best, best_share = key, share
    return best


def _spread(ratio: np.ndarray) -> tuple[float, float]:
    """Median of the ratios and how far (90th percentile, relative) they stray from it."""
    med = float(np.median(ratio))
    if not math.isfinite(med) or med <= 0.0:
        return med, math.inf
    return med, float(np.percentile(np.abs(ratio / med - 1.0), 90))


def _factor_name(value: float) -> tuple[str, str] | None:
    for constant, name, cause in CONSTANTS:
        if abs(value / constant - 1.0) < 0.02:
            return name, cause
    return None


def _ratio_phrase(value: float) -> str:
    """'every value is π times too large' / '... 4 times too small' / '1.37 times ...'."""
    named = _factor_name(value)
    if named and value > 1.0:
        return WORDS["named_large"].format(name=named[0], cause=named[1])
    inverse = _factor_name(1.0 / value)
    if inverse and value < 1.0:
        cause = named[1] if named else ""
        return WORDS["named_small"].format(name=inverse[0], cause=cause).rstrip(" —")
    if value > 1.0:
        return WORDS["large"].format(times=value)
    return WORDS["small"].format(times=1.0 / value)


def cosines(angles: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    return np.cos(np.radians(angles[:, 0])), np.cos(np.radians(angles[:, 2]))


def shape(check: Check, angles: np.ndarray, expected: np.ndarray, got: np.ndarray) -> str:
    """The pattern of the error in a few words, or '' when none is clear."""
    got = np.asarray(got, dtype=np.float64)
    expected = np.asarray(expected, dtype=np.float64)
    wrong = ~within(check, got, expected, slack=1.0)
    if not wrong.any():
        return ""
    if not np.isfinite(got).all():
        return WORDS["not_finite"]
    negative = (got < 0.0).any(axis=-1)
    if negative.any():
        at_zero = (expected[negative] <= 0.0).all()
        where = WORDS["negative_at_zero" if at_zero else "negative_in_places"]
        return WORDS["negative"].format(count=int(negative.sum()), where=where)
    zero = (expected <= 0.0).all(axis=-1)
    if zero[wrong].all():
        below = np.maximum(angles[:, 0], angles[:, 2]) >= 90.0
        return WORDS["wrong_below" if below[wrong].all() else "wrong_above"]
    nothing = (np.abs(got) <= check.atol).all(axis=-1)
    if nothing[wrong].all() and not zero[wrong].any():
        # Not "grey where the solution is coloured": zero is no colour at all.
        where = WORDS["zero_everywhere" if nothing.all() else "zero_where_wrong"]
        return WORDS["zero"].format(where=where)
    for phrase in (
        _ratio(check, angles, expected, got),
        _one_channel(check, expected, got, wrong),
        _grazing(angles, wrong, zero, table=bool(check.table)),
        _seam(check, angles, wrong, zero),
    ):
        if phrase:
            return phrase
    return ""


def _ratio(check: Check, angles: np.ndarray, expected: np.ndarray, got: np.ndarray) -> str:
    """A constant factor, or one of cos θi, cos θo, their inverses, √(cos θi cos θo)."""
    floor = 20.0 * check.atol
    use = (expected > floor) & (got > 0.0)
    rows = use.all(axis=-1)
    if rows.sum() < max(8, 0.3 * len(rows)):
        return ""
    ratio = got[rows] / expected[rows]
    med, spread = _spread(ratio.ravel())
    if spread < 0.01 and abs(med - 1.0) > 3 * check.rtol:
        return _ratio_phrase(med)
    cos_i, cos_o = cosines(angles[rows])
    factors = (
        (cos_i, "factor_cos_i"),
        (cos_o, "factor_cos_o"),
        (1.0 / cos_i, "factor_over_cos_i"),
        (1.0 / cos_o, "factor_over_cos_o"),
        (np.sqrt(cos_i * cos_o), "factor_sqrt"),
        (1.0 / np.sqrt(cos_i * cos_o), "factor_over_sqrt"),
    )
    for factor, key in factors:
        if np.std(factor) < 0.05:
            continue
        med, spread = _spread((ratio / factor[:, None]).ravel())
        if spread < 0.01:
            if abs(med - 1.0) < 0.02:
                return WORDS["off_by"].format(factor=WORDS[key])
            return WORDS["off_by_scaled"].format(factor=WORDS[key], scale=med)
    return ""


def _one_channel(check: Check, expected: np.ndarray, got: np.ndarray, wrong: np.ndarray) -> str:
    """Grey where the solution is coloured, or only one channel off."""
    per_channel = np.abs(got - expected) > check.atol + check.rtol * np.abs(expected)
    coloured = np.ptp(expected, axis=-1) > 0.05 * np.max(expected, axis=-1) + check.atol
    grey = np.ptp(got, axis=-1) <= 1e-6 * (1.0 + np.max(np.abs(got), axis=-1))
    if coloured[wrong].any() and grey[wrong & coloured].all() and grey.mean() > 0.9:
        return WORDS["grey"]
    channels = per_channel.any(axis=0)
    if channels.sum() == 1:
        return WORDS["one_channel"].format(channel=CHANNELS[int(np.argmax(channels))])
    return ""


def seam_rows(check: Check, angles: np.ndarray) -> np.ndarray | None:
    """Rows whose lookup blends across the table's periodic axis (φd: its last bin's centre
    and the first's, 180° apart, are neighbours): within half a bin of either end of φd.
    None where the check reads no table. Angles in degrees (θi, φi, θo, φo), N = z."""
    specs = getattr(check, "table", ())
    dims = getattr(specs[0], "dims", None) if specs else None
    if dims is None or angles is None or np.ndim(angles) != 2 or np.shape(angles)[1] != 4:
        return None  # no table, or a check without rows of directions (a sphere's image)
    from lab import reference
    from lab.measured.merl import continuous_index, half_diff

    theta = np.radians(np.asarray(angles, dtype=np.float64))
    L = reference.direction(theta[:, 0], theta[:, 1])
    V = reference.direction(theta[:, 2], theta[:, 3])
    phi = continuous_index(*half_diff(L, V), dims)[2]
    return (phi < 0.5) | (phi > dims[2] - 0.5)


def _seam(check: Check, angles: np.ndarray, wrong: np.ndarray, zero: np.ndarray) -> str:
    """Wrong only where a table lookup blends across its periodic axis's ends (the wrap of
    φd), right everywhere else: the neighbour there is clamped (or left outside the table)
    where it should wrap around. Any code that does so shows it, however it is written."""
    seam = seam_rows(check, angles)
    if seam is None:
        return ""
    elsewhere = ~seam & ~zero
    if elsewhere.sum() >= 8 and not wrong[elsewhere].any() and wrong[seam].any():
        return WORDS["seam"]
    return ""


def _grazing(angles: np.ndarray, wrong: np.ndarray, zero: np.ndarray, table: bool) -> str:
    """Wrong only where light or view is near grazing, right everywhere else. A check that
    reads a table has no Fresnel or G term to blame: there the lookup of large angles is."""
    steep = np.maximum(angles[:, 0], angles[:, 2]) > GRAZING
    elsewhere = ~steep & ~zero
    if elsewhere.sum() >= 8 and not wrong[elsewhere].any() and wrong[steep].any():
        return WORDS["grazing_table" if table else "grazing"].format(grazing=GRAZING)
    return ""


def lobe(
    check: Check, theta: np.ndarray, expected: list, got: list, params: dict, model: str = ""
) -> str:
    """For a polar curve: the peak in the wrong place, or a lobe too wide or too narrow
    (with the exponent or roughness whose lobe is as wide, fitted with lab.reference)."""
    theta = np.asarray(theta)
    e, g = np.asarray(expected, dtype=float), np.asarray(got, dtype=float)
    side = theta >= 0.0  # the reflection side of the plane of incidence
    e, g, t = e[side], g[side], theta[side]
    if not np.isfinite(g).all() or e.max() <= 0.0 or g.max() <= 0.0:
        return ""
    e_peak, g_peak = float(t[np.argmax(e)]), float(t[np.argmax(g)])
    # A lobe must rise clearly above its ends to have a peak worth naming.
    peaked = g.max() > 1.5 * min(g[0], g[-1]) + check.atol and e.max() > 1.5 * min(e[0], e[-1])
    if not peaked:
        return ""
    if max(e_peak, g_peak) >= t.max() - 2.0:
        return ""  # the rise toward grazing (1/N·V), not a lobe: its width says nothing
    e_width, g_width = _half_width(t, e), _half_width(t, g)
    moved = abs(e_peak - g_peak) >= 3.0 and 0 < g_peak
    wider = bool(e_width and g_width) and abs(g_width / e_width - 1.0) >= 0.2
    # A wider or narrower lobe of the same model can move the peak too (an off-specular
    # peak): the width parameter is named when its fitted lobe peaks where the student's does.
    table = width_table(model, {**check.params, **params}, check, t) if wider or moved else None
    fit = fit_width(table, e_width, g_width) if wider else None
    if fit and abs(fit[3] - g_peak) > 2.0:
        fit = None
    if moved and not fit:
        # Beckmann's or Cook-Torrance's peak moves with the roughness at an equal width.
        peak = fit_peak(table, e_width, g_width, g_peak)
        if peak:
            what, value, actual, _ = peak
            return WORDS["peak_fit"].format(
                got=g_peak, want=e_peak, what=what, value=float(f"{value:.2g}"), actual=actual
            )
        return WORDS["peak"].format(got=g_peak, want=e_peak)
    if not wider:
        return ""
    key = "too_wide" if g_width > e_width else "too_narrow"
    text = WORDS[key].format(ratio=max(g_width, e_width) / min(g_width, e_width))
    if moved:
        text = WORDS["and_peaks"].format(text=text, got=g_peak, want=e_peak)
    if fit:
        what, value, actual, _ = fit
        text = WORDS["as_wide"].format(
            text=text, what=what, value=float(f"{value:.2g}"), actual=actual
        )
    return text


# Parameters that set a lobe's width, and how a hint names them.
WIDTHS = {"ke": ("an exponent", 1.0, 1000.0), "m": ("a roughness m", 0.01, 1.0)}
WIDTH_STEPS = 150  # values of the width parameter in a table, evenly spaced in log


def width_table(model: str, params: dict, check: Check, t: np.ndarray) -> dict | None:
    """The widths (full width at half height, degrees, luminance) of the model's lobe in
    lab.reference at the check's light, over θo = `t`, for WIDTH_STEPS values of its width
    parameter (ke or m), with each one's peak; None for a model without one.

    fit_width reads only this table; exercises.json carries the same table for each polar
    check, so the web page names the same value as the grader."""
    key = tuple(sorted((k, tuple(v) if isinstance(v, list) else v) for k, v in params.items()))
    angles = (float(check.theta_i), float(check.phi_i))
    return _width_table(model, key, angles, tuple(float(x) for x in t))


@functools.lru_cache(maxsize=64)
def _width_table(model: str, params: tuple, light: tuple, t: tuple) -> dict | None:
    from lab import reference
    from lab.constants import LUMA

    defaults = reference.DEFAULTS.get(model, {})
    name = next((n for n in WIDTHS if n in defaults), None)
    if name is None:
        return None
    what, low, high = WIDTHS[name]
    theta = np.array(t)
    rows = np.stack(
        [
            np.full_like(theta, light[0]),
            np.full_like(theta, light[1]),
            theta,
            np.full_like(theta, light[1] + 180.0),
        ],
        axis=1,
    )
    known = {k: v for k, v in params if k in defaults}
    try:
        actual = float(reference.resolve(model, known)[name])

        def lobe(value: float) -> np.ndarray:
            return reference.brdf_angles(model, {**known, name: value}, rows) @ np.array(LUMA)

        solution_width = _half_width(theta, lobe(actual))
        if not solution_width:
            return None  # no lobe (a diffuse term alone): fit_width would find nothing
        grid = np.geomspace(low, high, WIDTH_STEPS)
        lobes = [lobe(v) for v in grid]
    except (ValueError, KeyError, ZeroDivisionError):
        return None
    return {
        "param": name,
        "words": what,
        "actual": actual,
        "solution_width": solution_width,
        "values": [float(v) for v in grid],
        "widths": [_half_width(theta, v) for v in lobes],
        "peaks": [float(theta[np.argmax(v)]) for v in lobes],
    }


def fit_width(
    table: dict | None, e_width: float, g_width: float
) -> tuple[str, float, float, float] | None:
    """(words, value, the check's value, peak θo) of the width parameter whose lobe in the
    table is as wide as the student's, if the table reproduces the solution's width (else
    None: the reference is no model of this lobe)."""
    if not table or abs(table["solution_width"] / e_width - 1.0) > 0.15:
        return None
    widths = np.array(table["widths"])
    best = int(np.argmin(np.abs(widths - g_width)))
    if not 0 < best < len(widths) - 1 or abs(widths[best] / g_width - 1.0) > 0.1:
        return None  # beyond the parameter's range, or no value gives that width
    return table["words"], table["values"][best], table["actual"], table["peaks"][best]


def fit_peak(
    table: dict | None, e_width: float, g_width: float, g_peak: float
) -> tuple[str, float, float, float] | None:
    """As fit_width, for a lobe that peaks elsewhere: the width parameter whose lobe in the
    table peaks where the student's does (within 2°) and is as wide (within 10 %)."""
    if not table or not g_width or abs(table["solution_width"] / e_width - 1.0) > 0.15:
        return None
    widths, peaks = np.array(table["widths"]), np.array(table["peaks"])
    near = (np.abs(peaks - g_peak) <= 2.0) & (np.abs(widths / g_width - 1.0) <= 0.1)
    near[[0, -1]] = False  # the ends of the parameter's range
    if not near.any():
        return None
    best = int(np.argmin(np.where(near, np.abs(peaks - g_peak) + np.abs(widths - g_width), np.inf)))
    return table["words"], table["values"][best], table["actual"], table["peaks"][best]


def _half_width(theta: np.ndarray, values: np.ndarray) -> float:
    """Full width at half height above the curve's floor, in degrees (0 if unclear)."""
    floor = float(values.min())
    half = floor + 0.5 * (float(values.max()) - floor)
    above = np.nonzero(values >= half)[0]
    if len(above) < 2 or len(above) == len(values):
        return 0.0
    return float(theta[above[-1]] - theta[above[0]]) or 1.0


def terms_sentence(wrong: list[str], right: list[str], detail: str) -> str:
    """'the specular term is wrong (the diffuse term is right): every value ...'."""
    text = WORDS["terms_wrong" if len(wrong) > 1 else "term_wrong"].format(names=joined(wrong))
    if right:
        key = "terms_right" if len(right) > 1 else "term_right"
        text = WORDS[key].format(text=text, names=joined(right))
    return WORDS["detail"].format(text=text, detail=detail) if detail else text


def sentence(text: str) -> str:
    """'Likely: ...' with a capital-free start and one final full stop."""
    text = text.strip().rstrip(".")
    return WORDS["likely"].format(text=text) if text else ""

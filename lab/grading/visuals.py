"""What the grading report shows of a failed check: difference images and the polar plot.

Numpy and text only (no OpenGL). Every picture carries its legend: a signed difference
(red: too bright, blue: too dark) with its scale, the failing pixels and directions marked,
and the polar curves of solution and submission on one scale with radial values.
"""

from __future__ import annotations

import math

import numpy as np

from lab.constants import GRAZING_DEG

TOO_BRIGHT = np.array([0.85, 0.15, 0.1])
TOO_DARK = np.array([0.1, 0.35, 0.95])
FAIL_MARK = np.array([1.0, 0.55, 0.0])
SCALE = 8.0  # the colour saturates at this many times the threshold


def signed_difference(delta: np.ndarray, covered: np.ndarray, threshold: float) -> np.ndarray:
    """Student minus solution (tone-mapped, in 1/255): red too bright, blue too dark.

    The colour grows with |delta| up to SCALE x the threshold; differences within the
    threshold stay faint, so a few failing pixels stand out from rounding noise.
    """
    amount = np.clip(np.abs(delta) / (SCALE * threshold), 0.0, 1.0)
    amount = np.where(np.abs(delta) > threshold, 0.25 + 0.75 * amount, 0.25 * amount)
    colour = np.where((delta >= 0)[..., None], TOO_BRIGHT, TOO_DARK)
    background = np.full(delta.shape + (3,), 0.93)
    image = background * (1.0 - amount[..., None]) + colour * amount[..., None]
    image[~covered] = 1.0
    return (image * 255 + 0.5).astype(np.uint8)


def failing_overlay(reference8: np.ndarray, failing: np.ndarray) -> np.ndarray:
    """The solution's image in grey with the failing pixels in orange."""
    grey = reference8[..., :3].astype(np.float32).mean(axis=-1, keepdims=True) / 255.0
    image = np.repeat(0.25 + 0.5 * grey, 3, axis=-1)
    image[failing] = FAIL_MARK
    return (image * 255 + 0.5).astype(np.uint8)


def difference_legend(threshold: float) -> str:
    """An inline colour bar for `signed_difference`, labelled in 1/255 steps."""
    top = SCALE * threshold
    stops = ", ".join(
        [
            f"rgb{tuple(int(255 * c) for c in TOO_DARK)} 0%",
            "rgb(220,225,235) 45%",
            "rgb(237,237,237) 50%",
            "rgb(235,225,220) 55%",
            f"rgb{tuple(int(255 * c) for c in TOO_BRIGHT)} 100%",
        ]
    )
    return (
        '<div class="legend"><div class="bar" style="background: linear-gradient(to right, '
        f'{stops})"></div><div class="ticks"><span>−{top:g} too dark</span>'
        f"<span>±{threshold:g} allowed</span><span>+{top:g} too bright</span></div>"
        "<div>difference of yours − solution, per pixel, in 1/255 after tone mapping</div></div>"
    )


def _nice(value: float) -> float:
    """A round number near `value` (1, 2 or 5 times a power of ten) for the rings."""
    if value <= 0 or not math.isfinite(value):
        return 1.0
    power = 10 ** math.floor(math.log10(value))
    return min((m * power for m in (1, 2, 5, 10)), key=lambda x: abs(x - value))


SOLUTION, YOURS, FAILING = "#0072B2", "#D55E00", "#A65E00"


def _polar_title(theta: np.ndarray, expected: np.ndarray, got: np.ndarray, light: float) -> str:
    """The plot in words, for a screen reader: where each curve peaks and how high."""

    def peak(values: np.ndarray) -> str:
        i = int(np.argmax(values))
        top = float(values[i])
        if top - float(np.min(values)) <= 0.01 * abs(top):
            return f"is flat at {top:.3g} sr⁻¹"
        return f"peaks at {top:.3g} sr⁻¹ at θo {float(theta[i]):.0f}°"

    return (
        f"Polar plot of f_r, light at {light:.3g}°: the solution {peak(expected)}, "
        f"yours {peak(got)}"
    )


def polar_svg(curve: dict, failing: list[int], width: int = 420) -> str:
    """Solution and submission in the plane of incidence, one linear scale, with rings.

    The scale comes from directions up to 65 degrees from the normal (or just past the
    light), so a peak at grazing (Cook-Torrance's 1/(N.V)) cannot shrink the lobe to a dot;
    what runs past the rim is drawn on it, and the caption says so.
    """
    theta = np.asarray(curve["theta_o"], dtype=float)
    expected = np.nan_to_num(np.asarray(curve["expected"], dtype=float), nan=0.0)
    got = np.nan_to_num(np.asarray(curve["got"], dtype=float), nan=0.0, posinf=1e30)
    inner = np.abs(theta) <= min(max(65.0, curve["theta_i"] + 5.0), 80.0, GRAZING_DEG)
    peak = max(float(np.max(expected[inner], initial=0.0)), 1e-9)
    peak = max(peak, min(float(np.max(got[inner], initial=0.0)), 3.0 * peak))
    ring = _nice(peak / 3.0)
    rings = [ring * k for k in range(1, 5) if ring * k <= peak * 1.15]
    top = max(peak * 1.15, rings[-1] if rings else peak)
    cx, cy, radius = width / 2, width / 2 - 5, width / 2 - 30
    parts = [
        f'<svg class="polar" width="{width}" height="{width / 2 + 20:.0f}" '
        f'viewBox="0 0 {width} {width / 2 + 20:.0f}" role="img">',
        f"<title>{_polar_title(theta, expected, got, curve['theta_i'])}</title>",
        f'<line x1="{cx - radius}" y1="{cy}" x2="{cx + radius}" y2="{cy}" stroke="#767676"/>',
    ]
    for value in rings:
        r = value / top * radius
        parts.append(
            f'<path d="M {cx - r:.1f} {cy} A {r:.1f} {r:.1f} 0 0 1 {cx + r:.1f} {cy}" '
            'fill="none" stroke="#888"/>'
            f'<text x="{cx + r + 2:.1f}" y="{cy + 13}" font-size="10" '
            f'fill="#595959">{value:g}</text>'
        )
    clipped = False
    # Told apart by line style as well as colour (Okabe-Ito blue and vermillion, both
    # readable under colour-blindness and at 3:1 or more on white).
    for values, colour, dash in ((expected, SOLUTION, ""), (got, YOURS, ' stroke-dasharray="7 4"')):
        points = []
        for t, v in zip(theta, values, strict=True):
            r = max(v, 0.0) / top
            clipped |= r > 1.0
            r = min(r, 1.0) * radius
            a = math.radians(t)
            points.append(f"{cx + r * math.sin(a):.1f},{cy - r * math.cos(a):.1f}")
        parts.append(
            f'<polyline fill="none" stroke="{colour}" stroke-width="2.5"{dash} '
            f'points="{" ".join(points)}"/>'
        )
    for index in failing:  # a tick outside the rim in each failing direction
        a = math.radians(theta[index])
        r0, r1 = radius + 3, radius + 11
        parts.append(
            f'<line x1="{cx + r0 * math.sin(a):.1f}" y1="{cy - r0 * math.cos(a):.1f}" '
            f'x2="{cx + r1 * math.sin(a):.1f}" y2="{cy - r1 * math.cos(a):.1f}" '
            f'stroke="{FAILING}" stroke-width="2"/>'
        )
    a = math.radians(-curve["theta_i"])
    parts.append(
        f'<line x1="{cx}" y1="{cy}" x2="{cx + radius * math.sin(a):.1f}" '
        f'y2="{cy - radius * math.cos(a):.1f}" stroke="#8a6d00" stroke-dasharray="4 3"/>'
        f'<text x="{cx + 0.85 * radius * math.sin(a) + 4:.1f}" '
        f'y="{cy - 0.85 * radius * math.cos(a) + 12:.1f}" font-size="11" fill="#8a6d00">'
        "light</text>"
        "</svg>"
    )
    legend = (
        f'<div class="caption"><span style="color:{SOLUTION}">━━ solution (solid)</span> '
        f'<span style="color:{YOURS}">╍╍ yours (dashed)</span> '
        f'<span style="color:{FAILING}">▮ failing directions (ticks outside the rim)</span><br>'
        f"f_r (luminance) in the plane of incidence, light at {curve['theta_i']:.3g}° "
        f"on the left; rings at {', '.join(f'{v:g}' for v in rings)} sr⁻¹"
    )
    if clipped:
        legend += "; values beyond the outer rim are drawn on it"
    return "".join(parts) + legend + "</div>"

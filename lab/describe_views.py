"""Words for the views other than the polar plot, for readers who cannot see them (WCAG 1.1.1).

Each function takes what its view computes (an image's floats, the albedo curve, the terms,
the SH errors) and says where its largest value is, the range of its values and the one
figure the lecture reads off it. Numbers in the words of lab/describe.py (three significant
digits, whole degrees). lab/web/static/describe_views.js mirrors this module and
tests/test_a11y_views.py holds the two to one fixture.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from lab.constants import GRAZING_DEG, LUMA
from lab.describe import FLAT, NEAR_DEG, UNIT, deg, fmt

LIT = 0.01  # a pixel is lit when it has at least this share of the brightest one
GAIN = 1e-3  # an albedo above 1 + GAIN is an energy gain (the page's mark)
SH_GOOD = 0.05  # the relative error the SH description counts orders to


def _share(count: int, total: int) -> str:
    """A whole per cent, rounded half to even (as describe.js's pyRound)."""
    return f"{round(100 * count / total) if total else 0} %"


def _angle(a: np.ndarray, b: np.ndarray) -> float:
    """Degrees between two unit vectors."""
    return math.degrees(math.acos(min(max(float(np.dot(a, b)), -1.0), 1.0)))


def _light(theta_i: float, phi_i: float) -> np.ndarray:
    t, p = math.radians(theta_i), math.radians(phi_i)
    return np.array([math.sin(t) * math.cos(p), math.sin(t) * math.sin(p), math.cos(t)])


def _luminance(rgba: np.ndarray) -> np.ndarray:
    rgba = np.asarray(rgba, dtype=np.float64)
    return rgba[..., 0] * LUMA[0] + rgba[..., 1] * LUMA[1] + rgba[..., 2] * LUMA[2]


def _drawn(rgba: np.ndarray) -> np.ndarray:
    """The pixels drawn: alpha > 0 (every pixel of an RGB image)."""
    rgba = np.asarray(rgba)
    return rgba[..., 3] > 0 if rgba.shape[-1] > 3 else np.ones(rgba.shape[:2], bool)


def _nonfinite(count: int) -> str:
    return f" {count} pixels are not finite (NaN or ∞)." if count else ""


def sphere(
    name: str,
    rgba: np.ndarray,
    theta_i: float,
    phi_i: float,
    more: Sequence[tuple[float, float]] = (),
) -> str:
    """A lit sphere (H x W x 4 floats, row 0 at the top, alpha 0 off the disc): its brightest
    point, how far that point's normal is from the halfway vector and from the light, and the
    share of the disc that is lit. `more`: (θi, φi) of further lights; the angles are then
    those of the light whose halfway vector is nearest that normal."""
    lum = _luminance(rgba)
    disc = _drawn(rgba)
    height, width = lum.shape
    ok = disc & np.isfinite(lum)
    lights = [(theta_i, phi_i), *more]
    where = "light" if not more else f"{len(lights)} lights, light 1"
    head = f"{name} on a sphere, {where} at θi {deg(theta_i)}, φi {deg(phi_i)}: "
    bad = _nonfinite(int((disc & ~np.isfinite(lum)).sum()))
    values = np.where(ok, lum, -math.inf)
    k = int(np.argmax(values))
    peak = float(values.flat[k])
    if not disc.any() or peak <= 0:
        return head + "black everywhere." + bad
    row, col = divmod(k, width)
    x = (col + 0.5) / width * 2 - 1
    y = 1 - (row + 0.5) / height * 2
    normal = np.array([x, y, math.sqrt(max(1 - x * x - y * y, 0.0))])
    best = None  # (angle to the halfway vector, light number, angle to the light)
    for j, (t, p) in enumerate(lights):
        light = _light(t, p)
        half = light + np.array([0.0, 0.0, 1.0])
        half /= np.linalg.norm(half)
        if best is None or _angle(normal, half) < best[0]:
            best = (_angle(normal, half), j + 1, _angle(normal, light))
    to_half, j, to_light = best
    which = (
        ("the halfway vector", "the light")
        if not more
        else (f"the halfway vector of light {j}", "that light")
    )
    lit = int((ok & (lum >= LIT * peak)).sum())
    return (
        head + f"brightest {fmt(peak)} where the normal is {deg(to_half)} from {which[0]} "
        f"and {deg(to_light)} from {which[1]}; "
        f"{_share(lit, int(disc.sum()))} of the disc lit." + bad
    )


def _where(row: int, col: int, height: int, width: int) -> str:
    """The third of a picture a pixel is in: 'top left', 'centre', 'bottom'..."""
    v = ("top", "middle", "bottom")[min(3 * row // height, 2)]
    h = ("left", "centre", "right")[min(3 * col // width, 2)]
    if v == "middle":
        return "centre" if h == "centre" else h
    return v if h == "centre" else f"{v} {h}"


def picture(name: str, what: str, rgba: np.ndarray) -> str:
    """A rendered picture (the lit object, the IBL sphere): its brightest point and where
    it is, the mean over the pixels drawn (alpha > 0) and the share of them lit."""
    lum = _luminance(rgba)
    drawn = _drawn(rgba)
    ok = drawn & np.isfinite(lum)
    bad = _nonfinite(int((drawn & ~np.isfinite(lum)).sum()))
    head = f"{what} of {name}: "
    values = np.where(ok, lum, -math.inf)
    k = int(np.argmax(values))
    peak = float(values.flat[k])
    if not ok.any() or peak <= 0:
        return head + "black everywhere." + bad
    height, width = lum.shape
    row, col = divmod(k, width)
    mean = float(lum[ok].sum() / ok.sum())
    lit = int((ok & (lum >= LIT * peak)).sum())
    return (
        head + f"brightest {fmt(peak)} at the {_where(row, col, height, width)}; "
        f"mean {fmt(mean)}; {_share(lit, int(drawn.sum()))} of it lit." + bad
    )


def albedo(name: str, thetas: Sequence[float], values: Sequence[float]) -> str:
    """The directional albedo against θi: its ends, its largest value and any energy gain."""
    t = [float(x) for x in thetas]
    a = [float(x) for x in values]
    head = f"{name}: directional albedo "
    if not t:
        return head + "not computed yet."
    finite = [k for k in range(len(a)) if math.isfinite(a[k])]
    if not finite:
        return head + "not finite at any θi."
    top = max(finite, key=lambda k: (a[k], -k))
    text = (
        head + f"{fmt(a[0])} at θi {deg(t[0])} to {fmt(a[-1])} at θi {deg(t[-1])}; "
        f"largest {fmt(a[top])} at θi {deg(t[top])}; "
    )
    gain = [k for k in range(len(a)) if not a[k] <= 1 + GAIN]
    if not gain:
        return text + "above 1 nowhere."
    return text + (
        f"above 1 (energy gain, not physical) at {len(gain)} of {len(a)} angles, "
        f"θi {deg(t[gain[0]])} to {deg(t[gain[-1]])}."
    )


def image_slice(name: str, rgba: np.ndarray, phi_d: float) -> str:
    """The (θh, θd) slice (row 0 at the top = θd 90°, θh growing to the right): its range,
    median and largest value, and θh where f_r falls to half along the bottom row."""
    lum = _luminance(rgba)
    height, width = lum.shape
    ok = np.isfinite(lum)
    head = f"{name}, image slice at φd {deg(phi_d)}: "
    bad = _nonfinite(int((~ok).sum()))
    if not ok.any():
        return head + "no finite value." + bad
    values = np.where(ok, lum, -math.inf)
    k = int(np.argmax(values))
    row, col = divmod(k, width)
    theta_h = (col + 0.5) / width * 90
    theta_d = (height - 1 - row + 0.5) / height * 90
    finite = np.sort(lum[ok])
    if finite[0] >= FLAT * finite[-1]:
        return head + f"f_r {fmt(float(finite[-1]))} {UNIT} over the whole slice, no peak." + bad
    grazing = " (near grazing)" if theta_d > GRAZING_DEG else ""
    text = (
        head + f"f_r from {fmt(float(finite[0]))} to {fmt(float(values.flat[k]))} {UNIT}, "
        f"median {fmt(float(finite[len(finite) // 2]))}; largest at θh {deg(theta_h)}, "
        f"θd {deg(theta_d)}{grazing}; "
    )
    bottom = lum[height - 1]
    start = float(bottom[0])
    if not (math.isfinite(start) and start > 0):
        return text + "at θh 0°, θd 0° it is 0." + bad
    for c in range(1, width):
        if bottom[c] < start / 2:
            where = deg((c + 0.5) / width * 90)
            return text + f"along θd 0° it falls to half its θh 0° value by θh {where}." + bad
    return text + "along θd 0° it stays above half its θh 0° value." + bad


def lobe3d(
    name: str,
    values: Sequence[float],
    angles: Sequence[float],
    theta_i: float,
    phi_i: float,
    what: str = "f_r",
    spike: float = 0.0,
) -> str:
    """The 3D lobe from its grid (values at vertices whose (θo, φo) in radians are the pairs
    of `angles`): the peak's direction and value, away from grazing, and f_r at the normal."""
    v = [float(x) for x in values]
    head = f"{name}, 3D lobe, light at θi {deg(theta_i)}, φi {deg(phi_i)}: "
    grazing = math.radians(GRAZING_DEG)
    k = -1
    for j in range(len(v)):
        if angles[2 * j] <= grazing and math.isfinite(v[j]) and (k < 0 or v[j] > v[k]):
            k = j
    spiked = f"a δ spike in the mirror direction, reflectance {fmt(spike)}; " if spike else ""
    if k < 0 or v[k] <= 0:
        return head + spiked + f"{what} is 0 everywhere."
    theta, phi = float(angles[2 * k]), float(angles[2 * k + 1])
    d = np.array(
        [math.sin(theta) * math.cos(phi), math.sin(theta) * math.sin(phi), math.cos(theta)]
    )
    mirror = _light(theta_i, phi_i + 180)
    toward = ""
    if _angle(d, mirror) <= NEAR_DEG and theta_i >= NEAR_DEG:
        toward = ", the mirror direction"
    elif _angle(d, _light(theta_i, phi_i)) <= NEAR_DEG and theta_i >= NEAR_DEG:
        toward = ", back toward the light"
    elif math.degrees(theta) <= NEAR_DEG:
        toward = ", the normal"
    phi_deg = int(round(math.degrees(phi))) % 360
    normal = v[0] if math.isfinite(v[0]) else 0.0  # the grid's first row is θo = 0
    return (
        head
        + spiked
        + (
            f"peak of {what} {fmt(v[k])} {UNIT} toward θo {deg(math.degrees(theta))}, "
            f"φo {phi_deg}°{toward}; at the normal {fmt(max(normal, 0.0))}."
        )
    )


def terms(
    name: str,
    theta: Sequence[float],
    D: Sequence[float],
    theta_o: Sequence[float],
    G: Sequence[float],
    F: Sequence[Sequence[float]],
) -> str:
    """D against θh (its value at 0° and where it halves), G against θo (at the normal and
    its lowest away from grazing), F's luminance against θd (at both ends)."""
    if not len(theta):
        return f"{name}: no D, G, F terms."
    d = [float(x) for x in D]
    parts = [f"D {fmt(d[0])} {UNIT} at θh 0°"]
    for k in range(1, len(d)):
        if d[k] < d[0] / 2:
            parts[0] += f", half of that at θh {deg(float(theta[k]))}"
            break
    else:
        parts[0] += ", above half of that to θh 90°"
    inside = [k for k in range(len(theta_o)) if abs(theta_o[k]) <= GRAZING_DEG]
    g = [float(x) for x in G]
    normal = min(inside, key=lambda k: (abs(theta_o[k]), k))
    low = min((k for k in inside if math.isfinite(g[k])), key=lambda k: (g[k], k), default=normal)
    parts.append(
        f"G {fmt(g[normal])} at the normal, lowest {fmt(g[low])} at θo {deg(float(theta_o[low]))}"
    )
    f = [float(LUMA[0] * c[0] + LUMA[1] * c[1] + LUMA[2] * c[2]) for c in F]
    parts.append(f"F {fmt(f[0])} at θd 0° to {fmt(f[-1])} at θd {deg(float(theta[-1]))}")
    return f"{name}: " + "; ".join(parts) + "."


def sh(name: str, errors: Sequence[float], order: int) -> str:
    """The SH fit: its relative error at the chosen order, and from which order it is below
    SH_GOOD."""
    if not len(errors):
        return f"{name}: no spherical harmonics (a δ model, or not computed yet)."
    e = [float(x) for x in errors]
    order = min(max(int(order), 0), len(e) - 1)
    good = next((n for n in range(len(e)) if e[n] < SH_GOOD), None)
    limit = f"{fmt(100 * SH_GOOD)} %"
    reach = (
        f"below {limit} from order {good}"
        if good is not None
        else f"above {limit} up to order {len(e) - 1}"
    )
    return (
        f"{name}: spherical harmonics to order {order}, relative error {fmt(100 * e[order])} %; "
        f"order 0: {fmt(100 * e[0])} %; {reach}."
    )

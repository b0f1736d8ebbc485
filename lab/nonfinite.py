"""Say where a render went NaN or Inf: a BRDF that divides by zero otherwise shows only as
black pixels and empty plots, with no message at all."""

from __future__ import annotations

import numpy as np


def _span(values: np.ndarray) -> str:
    lo, hi = float(values.min()), float(values.max())
    return f"{lo:.2f}" if hi - lo < 0.005 else f"{lo:.2f}–{hi:.2f}"


def sphere_report(image: np.ndarray, light: np.ndarray | None = None) -> str:
    """'' when every pixel of the sphere (alpha > 0) is finite; else one line with the share
    of NaN/Inf pixels and where they are: N·V (1 at the centre, 0 at the rim), N·L for the
    light direction `light` (camera space, as the sphere view's), and the side of the disc.
    """
    on = image[..., 3] > 0
    rgb = image[..., :3]
    bad = on & ~np.isfinite(rgb).all(axis=-1)
    count = int(bad.sum())
    if not count:
        return ""
    n = image.shape[0]
    rows, cols = np.mgrid[0:n, 0:n]
    x = (cols + 0.5) / n * 2.0 - 1.0
    y = 1.0 - (rows + 0.5) / n * 2.0  # row 0 is the top
    z = np.sqrt(np.clip(1.0 - x * x - y * y, 0.0, 1.0))
    nan = int((on & np.isnan(rgb).any(axis=-1)).sum())
    kinds = "NaN" if nan == count else ("Inf" if nan == 0 else f"NaN or Inf ({nan} of them NaN)")
    parts = [f"N·V {_span(z[bad])}"]
    if light is not None:
        nl = x * light[0] + y * light[1] + z * light[2]
        parts.append(f"N·L {_span(nl[bad])}")
    cx, cy = float(x[bad].mean()), float(y[bad].mean())
    if np.hypot(cx, cy) < 0.25:
        central = bad[np.hypot(x, y) < 0.15].any()
        side = "around the centre" if central else "in a ring around the centre"
    else:
        side = ("upper " if cy > 0.25 else "lower " if cy < -0.25 else "") + (
            "right" if cx > 0.25 else "left" if cx < -0.25 else ""
        )
        side = f"mostly {side.strip()}"
    share = count / max(int(on.sum()), 1)
    return (
        f"{share:.1%} of the sphere ({count} pixels) is {kinds}, {side}, where "
        f"{' and '.join(parts)}: "
        "look for a division by zero, or sqrt, log or pow of a negative number, there"
    )

"""The one scaling rule of every plot of f_r (CLI, gallery, figures, app, watch, web page).

The scale's top comes from the values with |theta_o| <= GRAZING_DEG only: toward the horizon
some models diverge for real (Ward's 1 / sqrt(cos theta_i cos theta_o), Phong illumination's
1 / cos theta_i), and scaling to them would flatten every lobe to a line. What lies above the
top is drawn at the rim and reported (`Scale.clipped`, `Scale.note`), never hidden.
Ticks are round numbers in sr^-1 (f_r and f_r cos theta_o both have that unit).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from lab.constants import GRAZING_DEG, PLOT_DECADES

UNIT = "sr⁻¹"
SUPERSCRIPT = str.maketrans("-0123456789", "⁻⁰¹²³⁴⁵⁶⁷⁸⁹")
STEPS = (1.0, 2.0, 2.5, 5.0)  # tick steps per decade: 0.25 0.5 0.75 or 1 2 3 read easily


def peak_value(theta_o: np.ndarray, values: np.ndarray) -> float:
    """The largest finite value with |theta_o| <= GRAZING_DEG (0 when there is none)."""
    v = np.asarray(values, dtype=np.float64)
    inside = v[(np.abs(np.asarray(theta_o)) <= GRAZING_DEG) & np.isfinite(v)]
    return float(inside.max()) if inside.size else 0.0


def nice_step(peak: float, ticks: int = 3) -> float:
    """The smallest round step (1, 2, 2.5, 5 x 10^k) with at most `ticks` steps up to peak."""
    raw = peak / ticks
    base = 10.0 ** math.floor(math.log10(raw))
    for s in (*STEPS, 10.0):
        if s * base >= raw * (1 - 1e-9):
            return s * base
    return 10.0 * base


@dataclass
class Scale:
    """Maps values to radii in [0, 1] (1 = the rim) and names its ticks."""

    top: float
    log: bool = False
    decades: float = PLOT_DECADES
    ticks: list[float] = field(default_factory=list)
    clipped_max: float = 0.0  # the largest value drawn at the rim instead (inf: a divergence)
    clipped_at: float | None = None  # its theta_o in degrees

    def radius(self, values) -> np.ndarray:
        v = np.nan_to_num(np.asarray(values, dtype=np.float64), nan=0.0, posinf=np.inf)
        if self.log:
            floor = self.top * 10.0**-self.decades
            r = np.log10(np.maximum(v, floor) / floor) / self.decades
        else:
            r = v / self.top
        return np.clip(r, 0.0, 1.0)

    def label(self, value: float) -> str:
        """A tick's number: plain where short (0.25, 100), a power of ten otherwise."""
        if value == 0 or 1e-3 <= abs(value) < 1e4:
            return f"{value:.4g}"
        exponent = math.floor(math.log10(abs(value)) + 1e-9)
        mantissa = value / 10.0**exponent
        power = "10" + str(exponent).translate(SUPERSCRIPT)
        return power if abs(mantissa - 1) < 1e-6 else f"{mantissa:.3g}·{power}"

    @property
    def clipped(self) -> bool:
        return self.clipped_max > self.top * (1 + 1e-6)

    def note(self) -> str:
        """One line saying what lies beyond the rim, or ''."""
        if not self.clipped:
            return ""
        size = "→ ∞" if not math.isfinite(self.clipped_max) else f"{self.clipped_max:.3g} {UNIT}"
        where = f" at θo = {self.clipped_at:g}°" if self.clipped_at is not None else ""
        return f"clipped at the rim: up to {size}{where}\n(grazing, left out of the scale)"


def polar_scale(
    theta_o: np.ndarray,
    curves: list[np.ndarray],
    spikes: tuple[float, ...] = (),
    log: bool = False,
    decades: float = PLOT_DECADES,
) -> Scale:
    """The shared scale of lobes sampled at theta_o (deg): curves (n,) and delta spikes."""
    theta_o = np.asarray(theta_o, dtype=np.float64)
    peaks = [peak_value(theta_o, c) for c in curves] + [s for s in spikes if math.isfinite(s)]
    peak = max(peaks, default=0.0)
    peak = peak if peak > 0 else 1.0
    if log:
        top = 10.0 ** math.ceil(math.log10(peak) - 1e-9)
        ticks = [top * 10.0**-k for k in range(int(decades) - 1, -1, -1)]
    else:
        step = nice_step(peak)
        top = step * math.ceil(peak / step - 1e-9)
        ticks = [step * k for k in range(1, int(round(top / step)) + 1)]
    scale = Scale(top, log, decades, ticks)
    for c in curves:
        v = np.asarray(c, dtype=np.float64)
        v = np.where(np.isnan(v), 0.0, v)
        if v.size and v.max() > scale.clipped_max:
            i = int(np.argmax(v))
            scale.clipped_max, scale.clipped_at = float(v[i]), float(theta_o[i])
    return scale

"""The (θh, θd) image slice of BRDF Explorer (shaders/views/slice.glsl), and the colour
scale its values need: they span decades, and near grazing (θd → 90°) a microfacet model's
f_r diverges (GGX reaches 10⁴ sr⁻¹), so a scale to the maximum paints the specular peak
black. The scale's top is a high percentile instead, and the view says so."""

from __future__ import annotations

import math

import numpy as np

from lab import plots
from lab.constants import LUMA
from lab.plotscale import SUPERSCRIPT, UNIT
from lab.views import PlotJob, Setting, ViewSpec

SCALES = ("log", "linear", "exposure")  # the app's menu; the first two map colours
TOP_PERCENTILE = 95.0  # the top: a grazing divergence (a few % of the pixels) cannot move it
DECADES = 4.0  # the log scale's range below its top
# A dark-to-light ramp (black, violet, red, orange, pale yellow): brightness rises
# monotonically, so it reads in grey too; anchors at 0, 1/4, 1/2, 3/4, 1.
RAMP = np.array(
    [
        [0.00, 0.00, 0.02],
        [0.29, 0.07, 0.47],
        [0.72, 0.21, 0.38],
        [0.98, 0.55, 0.15],
        [0.99, 0.98, 0.75],
    ]
)


def luminance(rgb: np.ndarray) -> np.ndarray:
    return np.asarray(rgb, dtype=np.float64)[..., :3] @ np.array(LUMA)


def colour_range(images: list[np.ndarray], log: bool = True) -> tuple[float, float]:
    """(low, high) of a scale shared by `images` (f_r RGB): high the TOP_PERCENTILE of
    their finite positive luminances, low DECADES below it (log) or 0 (linear)."""
    values = [luminance(im) for im in images]
    finite = np.concatenate([v[np.isfinite(v) & (v > 0)] for v in values] or [np.zeros(0)])
    high = float(np.percentile(finite, TOP_PERCENTILE)) if finite.size else 1.0
    high = high if high > 0 else 1.0
    return (high * 10.0**-DECADES if log else 0.0), high


def position(values: np.ndarray, low: float, high: float, log: bool = True) -> np.ndarray:
    """Where values fall on the scale, 0..1 (clipped at both ends; NaN at 0)."""
    v = np.nan_to_num(np.asarray(values, dtype=np.float64), nan=0.0, posinf=high)
    if log:
        t = np.log10(np.maximum(v, low) / low) / math.log10(high / low)
    else:
        t = v / high
    return np.clip(t, 0.0, 1.0)


def ramp(t: np.ndarray) -> np.ndarray:
    """The colours (..., 3) in 0..1 of scale positions t in 0..1."""
    stops = np.linspace(0.0, 1.0, len(RAMP))
    return np.stack([np.interp(t, stops, RAMP[:, c]) for c in range(3)], axis=-1)


def coloured(rgb: np.ndarray, low: float, high: float, log: bool = True) -> np.ndarray:
    """f_r RGB (h, w, 3) as the ramp's colours of its luminance."""
    return ramp(position(luminance(rgb), low, high, log)).astype(np.float32)


def tick_label(value: float) -> str:
    """A scale end's number: plain where short, else a power of ten."""
    if 1e-2 <= value < 1e4:
        return f"{value:.3g}"
    exponent = math.floor(math.log10(value))
    mantissa = value / 10.0**exponent
    power = "10" + str(exponent).translate(SUPERSCRIPT)
    return power if round(mantissa, 1) == 1 else f"{mantissa:.1f}·{power}"


def scale_note(log: bool) -> str:
    """What the colours mean, in a line."""
    kind = f"log scale ({DECADES:g} decades)" if log else "linear scale"
    return f"f_r in {UNIT}, {kind} to its {TOP_PERCENTILE:g}th percentile; above: clipped"


def plot(job: PlotJob) -> None:
    """log10 f_r over (θh, θd) at φd = the light's φ (90° when it is 0), on the scale
    above (the grazing divergence clipped, as the colour bar says)."""
    phi_d = job.phi_i if job.phi_i else 90.0
    fig, ax = plots.figure()
    rgb = job.renderer.slice(job.model, job.values, phi_d=phi_d, size=min(job.size, 512))
    low, high = colour_range([rgb])
    image = np.maximum(plots.luminance(rgb.astype(np.float64)), low)
    shown = ax.imshow(
        np.log10(image),
        extent=(0, 90, 0, 90),
        cmap="magma",
        aspect="equal",
        vmin=math.log10(low),
        vmax=math.log10(high),
    )
    fig.colorbar(shown, label=f"log10 f_r (top: {TOP_PERCENTILE:g}th percentile)")
    ax.set_xlabel("θh (degrees)")
    ax.set_ylabel("θd (degrees)")
    ax.set_title(f"{job.model.name}: image slice at φd = {phi_d:g}°", fontsize=10)
    plots.save_figure(fig, job.out, job.size)


VIEW = ViewSpec(
    name="slice",
    title="Image slice (θh, θd)",
    settings={
        "phi_d": Setting(
            90.0,
            0.0,
            180.0,
            "φd",
            1.0,
            unit="°",
            doc="φd: the difference azimuth of the (θh, θd) slice",
        ),
        "slice_scale": Setting(0, 0, len(SCALES) - 1, "colours", choices=SCALES),
    },
    dock=("bottom", 0),
    size=(0.34, 0.3),
    short_title="Slice θh θd",
    widget="lab.app.views.slice:SliceView",
    plot=plot,
    order=50,
)

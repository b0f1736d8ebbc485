"""What the views' PNG plots share: tone-mapped images, luminance, a matplotlib figure
(imported only when one is drawn), the polar half-disc and saving at a given width.

Each view's own plot lives in its module in lab/views/."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from lab import plotscale
from lab.constants import LUMA


def to_srgb8(rgb: np.ndarray, exposure: float = 0.0, gamma: float | None = None) -> np.ndarray:
    """Linear radiance -> 8-bit: scale by 2^exposure, clamp, sRGB curve (or 1/gamma power)."""
    x = np.clip(np.nan_to_num(rgb, nan=0.0) * 2.0**exposure, 0.0, 1.0)
    if gamma:
        encoded = x ** (1.0 / gamma)
    else:
        encoded = np.where(x <= 0.0031308, 12.92 * x, 1.055 * np.power(x, 1 / 2.4) - 0.055)
    return (encoded * 255.0 + 0.5).astype(np.uint8)


def save_image(image: np.ndarray, path: str | Path, exposure: float = 0.0) -> None:
    """Save an RGBA float render (alpha 0 = background) as PNG."""
    from PIL import Image

    rgb = to_srgb8(image[..., :3], exposure)
    if image.shape[-1] == 4:
        alpha = (np.clip(image[..., 3], 0, 1) * 255 + 0.5).astype(np.uint8)
        Image.fromarray(np.dstack([rgb, alpha]), "RGBA").save(path)
    else:
        Image.fromarray(rgb, "RGB").save(path)


def luminance(rgb: np.ndarray) -> np.ndarray:
    return rgb @ np.array(LUMA, dtype=rgb.dtype)


def figure(polar: bool = False, three_d: bool = False):
    """A 6 x 4.5 inch matplotlib figure and its axes (matplotlib is imported here, when used)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig = plt.figure(figsize=(6, 4.5), dpi=110)
    projection = "polar" if polar else ("3d" if three_d else None)
    return fig, fig.add_subplot(projection=projection)


def draw_polar(
    ax,
    lobes: list[tuple[object, str, object]],
    theta_i: float,
    what: str,
    log: bool = False,
    normalize: bool = False,
    fontsize: float = 11,
) -> plotscale.Scale:
    """Lobes (Polar, label, colour) on a half-disc with the shared scale (lab.plotscale).

    The light is on the right, as on the spheres and the 3D lobe; radial ticks are values in
    sr^-1 (or fractions of each lobe's peak with `normalize`); what the scale clips at the rim
    is marked and named in the legend; the direction labels are moved until none overlaps.
    """
    curves = [luminance(p.values.astype(np.float64)) for p, _, _ in lobes]
    spikes = tuple(
        float(luminance(np.asarray(p.spike, np.float64)))
        for p, _, _ in lobes
        if p.spike is not None
    )
    theta_o = lobes[0][0].theta_o if lobes else np.zeros(1)
    if normalize:
        peaks = [
            max(plotscale.peak_value(p.theta_o, c), 1e-30)
            for (p, _, _), c in zip(lobes, curves, strict=True)
        ]
        curves = [c / k for c, k in zip(curves, peaks, strict=True)]
    scale = plotscale.polar_scale(theta_o, curves, () if normalize else spikes, log=log)
    for (polar, label, color), r in zip(lobes, curves, strict=True):
        theta = np.radians(polar.theta_o)
        (line,) = ax.plot(theta, scale.radius(r), label=label, color=color, lw=2)
        over = r > scale.top * (1 + 1e-6)
        if over.any():
            ax.plot(theta[over], np.ones(over.sum()), "v", color="crimson", ms=6, clip_on=False)
        if polar.spike is not None and not normalize:
            height = float(luminance(np.asarray(polar.spike, np.float64)))
            mirror = np.radians(polar.theta_i)
            ax.plot(
                [mirror] * 2,
                [0, float(scale.radius([height])[0])],
                lw=4,
                color=line.get_color(),
                label=f"{label}: delta spike, reflectance {height:.3g}",
            )
    if scale.clipped:
        ax.plot([], [], "v", color="crimson", ms=6, label=scale.note())
    _style_polar(ax, theta_i, what, scale, normalize, fontsize)
    return scale


def _style_polar(ax, theta_i: float, what: str, scale, normalize: bool, fontsize: float) -> None:
    ax.set_theta_zero_location("N")
    ax.set_theta_direction(1)  # positive theta_o (the mirror side) on the left, the light right
    ax.set_thetamin(-90)
    ax.set_thetamax(90)
    ax.set_ylim(0, 1)
    radii = scale.radius(scale.ticks)
    ax.set_yticks(radii)
    unit = plotscale.UNIT
    ax.set_yticklabels([scale.label(t) for t in scale.ticks])  # the unit is in the title
    ax.set_xticks(np.radians([-90, -60, -30, 0, 30, 60, 90]))
    ax.set_xticklabels(["90°", "60°", "30°", "0°", "30°", "60°", "90°"])
    ax.tick_params(labelsize=fontsize * 0.9)
    marks = [(0.0, "normal", ":"), (-theta_i, "incident", "--"), (theta_i, "mirror", "-.")]
    if theta_i < 8:  # the three directions (nearly) coincide: one label says so
        merged = "normal = incident\n= mirror" if theta_i == 0 else "normal"
        marks = [(0.0, merged, ":")]
    for angle, _, style in marks:
        ax.plot([np.radians(angle)] * 2, [0, 1], style, color="grey", lw=1)
    texts = []
    for angle, name, _ in marks:
        # Away from the normal while the line is steep, toward the centre once it is flat,
        # so that a label neither covers the normal's nor leaves the disc.
        outward = abs(angle) < 50
        side = "center" if abs(angle) < 8 else ("right" if (angle > 0) == outward else "left")
        texts.append(
            ax.text(
                np.radians(angle),
                0.8,
                name,
                ha=side,
                va="bottom" if abs(angle) > 60 else "center",
                fontsize=fontsize,
                color="dimgrey",
                bbox={"facecolor": "white", "edgecolor": "none", "pad": 1, "alpha": 0.8},
                zorder=1.5,  # below the lobes: a label never hides the lobe's tip
            )
        )
    log = ", log scale" if scale.log else ""
    ax.set_title(
        f"{what}{'' if normalize else ' in ' + unit}{log}, θi = {theta_i:g}°\n(light on the right)",
        fontsize=fontsize * 1.1,
    )
    ax.legend(
        loc="upper center",
        bbox_to_anchor=(0.5, 0.02),
        fontsize=fontsize * 0.9,
        ncol=1 if scale.clipped or len(ax.get_legend_handles_labels()[0]) > 3 else 2,
        frameon=False,
    )
    separate_labels(ax, texts)


def separate_labels(ax, texts: list) -> None:
    """Move direction labels toward the centre until none overlaps another or the angle
    labels at the rim (and none leaves the axes)."""
    fig = ax.figure
    fig.tight_layout()  # the final layout first: it moves the rim's labels relative to ours
    fig.draw_without_rendering()  # places the rim's labels
    renderer = fig.canvas.get_renderer()
    rim = [t.get_window_extent(renderer) for t in ax.get_xticklabels() if t.get_text()]
    for index, text in enumerate(texts):
        radius = 0.8
        while radius > 0.2:
            # A margin: tight_layout may still shrink the axes a little after this.
            box = text.get_window_extent(renderer).expanded(1.25, 1.3)
            others = rim + [t.get_window_extent(renderer) for t in texts[:index]]
            if not any(box.overlaps(o) for o in others):
                break
            radius -= 0.12
            angle = text.get_position()[0]
            text.set_position((angle, radius))


def save_figure(fig, out: str | Path, size: int = 512) -> None:
    """Save `fig` `size` pixels wide (320 at least, to stay legible) and free it."""
    import matplotlib.pyplot as plt

    fig.tight_layout()
    fig.savefig(out, dpi=max(size, 320) / fig.get_size_inches()[0])
    plt.close(fig)

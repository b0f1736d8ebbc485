"""The lecture's diagrams, drawn from the lab's own numbers (matplotlib).

- The gonioreflectometer: light and detector arms over a sample, and the readings the
  detector would take, which are the model's f_r computed by its GLSL.
- V-groove shadowing and masking: the lit and visible part of a facet is the Torrance-Sparrow
  G of lab.reference (the same formula as shaders/terms/geometry.glsl).
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np

from lab import plots, reference

# The slides show a figure at its own size (one PNG pixel = one CSS pixel of the 1280x800
# deck), which a 1280x720 screen draws at 0.874: text of 21 pt at 100 dpi (29 px) is 25 px
# there, readable from the back row (tests/test_slides.py measures it).
DPI = 100
FONT = 21


def text_sizes(fig, dpi: float = DPI) -> list[tuple[str, float]]:
    """Every text the figure draws, with its font size in the PNG's pixels."""
    import matplotlib.text

    hidden = set()  # tick labels of axes drawn without their axis ("off")
    for ax in fig.axes:
        if not ax.axison:
            for axis in (ax.xaxis, ax.yaxis):
                hidden.update(map(id, axis.get_ticklabels(which="both")))
    return [
        (t.get_text(), round(t.get_fontsize() * dpi / 72.0, 2))
        for t in fig.findobj(matplotlib.text.Text)
        if t.get_visible() and t.get_text().strip() and id(t) not in hidden
    ]


def record_text(out: Path, texts: list[tuple[str, float]]) -> None:
    """Write what a figure says and how large beside it (NAME.text.json): the deck's test
    reads it to measure the text on the slide; [] for a picture without text."""
    data = [{"text": text, "px": px} for text, px in texts]
    out.with_suffix(".text.json").write_text(json.dumps(data, ensure_ascii=False, indent=0))


def save(fig, out: Path, dpi: float = DPI) -> Path:
    """Save a slide figure (and its text sizes) and free it."""
    import matplotlib.pyplot as plt

    fig.savefig(out, dpi=dpi, bbox_inches="tight", facecolor="white")
    record_text(out, text_sizes(fig, dpi))
    plt.close(fig)
    trim(out)
    return out


def trim(path: Path, margin: int = 8) -> None:
    """Cut the white border off a PNG (a polar half disc leaves its empty half), keeping
    `margin` pixels: the slide shows the drawing, not the paper. Text sizes do not change."""
    from PIL import Image

    with Image.open(path) as image:
        rgb = np.asarray(image.convert("RGB"))
    ink = np.argwhere((rgb < 245).any(axis=2))
    if ink.size == 0:
        return
    (top, left), (bottom, right) = ink.min(axis=0), ink.max(axis=0)
    height, width = rgb.shape[:2]
    box = (
        max(int(left) - margin, 0),
        max(int(top) - margin, 0),
        min(int(right) + margin + 1, width),
        min(int(bottom) + margin + 1, height),
    )
    Image.fromarray(rgb[box[1] : box[3], box[0] : box[2]]).save(path)


def gonioreflectometer(renderer, out: str | Path, theta_i: float = 45.0) -> Path:
    """A sample, a light arm at theta_i and a detector on an arc; the detector's readings
    every 10 degrees are the model's f_r (Cook-Torrance, m = 0.3) computed by the renderer."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(11.0, 5.6))
    ax.set_aspect("equal")
    ax.axis("off")
    ax.add_patch(plt.Rectangle((-0.55, -0.08), 1.1, 0.08, color="0.55"))
    ax.text(0.0, -0.16, "sample", ha="center", va="top", fontsize=FONT)
    arc = np.radians(np.linspace(-90, 90, 181))
    ax.plot(1.2 * np.sin(arc), 1.2 * np.cos(arc), ":", color="0.6")
    ax.plot([0, 0], [0, 1.3], "--", color="0.5", lw=1)
    ax.text(0.0, 1.33, "N", ha="center", va="bottom", fontsize=FONT)
    # The light on the right, as in every view of the lab.
    li = math.radians(theta_i)
    lx, ly = 1.2 * math.sin(li), 1.2 * math.cos(li)
    ax.annotate("", (0.05 * lx, 0.05 * ly), (lx, ly), arrowprops={"arrowstyle": "->", "lw": 2})
    ax.add_patch(plt.Circle((lx, ly), 0.07, color="orange"))
    ax.text(lx + 0.1, ly + 0.05, f"light\nθi = {theta_i:g}°", fontsize=FONT, va="bottom")
    # The detector's readings: f_r at theta_o every 10 degrees on the mirror side.
    values = {"kd": (0.1, 0.1, 0.1), "m": 0.3}
    angles = np.arange(0.0, 90.0, 10.0)
    L = np.repeat(reference.direction(li, 0.0), len(angles), axis=0)
    V = reference.direction(np.radians(angles), np.full(len(angles), math.pi))
    f = plots.luminance(renderer.probe("cook_torrance", values, L, V).astype(np.float64))
    scale = 0.9 / f.max()
    for a, value in zip(angles, f, strict=True):
        t = math.radians(a)
        ax.plot(
            [0, -scale * value * math.sin(t)], [0, scale * value * math.cos(t)], color="tab:blue"
        )
        ax.plot(-1.2 * math.sin(t), 1.2 * math.cos(t), "s", color="tab:blue", ms=6)
    detector = math.radians(theta_i + 15.0)
    dx, dy = -1.2 * math.sin(detector), 1.2 * math.cos(detector)
    ax.add_patch(plt.Rectangle((dx - 0.07, dy - 0.05), 0.14, 0.1, color="black"))
    ax.text(dx - 0.12, dy + 0.02, "detector\nat θo, φo", ha="right", fontsize=FONT)
    ax.text(
        0.0,
        -0.3,
        "reading = reflected radiance / irradiance = fᵣ (sr⁻¹)\n"
        "blue: every 10°, Cook-Torrance (m = 0.3) from its GLSL",
        ha="center",
        va="top",
        fontsize=FONT,
    )
    ax.set_xlim(-2.1, 2.1)
    ax.set_ylim(-0.75, 1.5)
    return save(fig, Path(out))


def _groove(ax, slope_deg: float, x0: float, lit: float, color: str, side: int) -> None:
    """One V-groove at x0 (its two facets); on facet `side` (+1 right, -1 left) the part
    nearest the groove's bottom, 1 - `lit` of it, is drawn dark."""
    a = math.radians(slope_deg)
    w, h = 1.0, math.tan(a)
    bottom = (x0, -h)
    for s in (-1, 1):
        top = (x0 + s * w, 0.0)
        ax.plot([bottom[0], top[0]], [bottom[1], top[1]], color="0.2", lw=1.5)
        if s == side:
            # Points along the facet from the bottom (t = 0) to the top (t = 1).
            cut = 1.0 - lit
            mid = (bottom[0] + cut * (top[0] - bottom[0]), bottom[1] + cut * (top[1] - bottom[1]))
            ax.plot([bottom[0], mid[0]], [bottom[1], mid[1]], color="0.15", lw=6)
            ax.plot([mid[0], top[0]], [mid[1], top[1]], color=color, lw=6)


def vgroove(out: str | Path, slope_deg: float = 30.0, grazing_deg: float = 80.0) -> Path:
    """V-grooves in cross-section, facets at +-slope_deg. Shadowing: the light at grazing_deg
    on the right and the eye where the right-facing facets mirror it into; masking: the same
    with light and eye swapped. The lit (visible) share of a facet is the V-groove G of
    lab.reference for that pair (the facet normal is their half vector)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    h = math.radians(slope_deg)
    far = math.radians(grazing_deg)
    near = 2.0 * h - far  # the mirror partner of `far` about the facet normal (negative: left)
    cos = [np.array([math.cos(x)]) for x in (h, far, abs(near), far - h)]
    g = float(reference.g_vgroove(*cos)[0])  # symmetric in L and V: one value for both panels
    fig, axes = plt.subplots(1, 2, figsize=(12.0, 3.6))
    for ax, what in zip(axes, ("shadowing", "masking"), strict=True):
        ax.set_aspect("equal")
        ax.axis("off")
        color = "gold" if what == "shadowing" else "tab:green"
        for k in range(3):
            _groove(ax, slope_deg, 2.0 * k - 2.0, g, color, -1)
        d = (math.sin(far), math.cos(far))
        for k in range(3):
            x = 2.0 * k - 3.0
            start, end = (x + 0.9 * d[0], 0.9 * d[1]), (x, 0.0)
            if what == "masking":
                start, end = end, start
            style = {"arrowstyle": "->", "color": "orange" if what == "shadowing" else "0.3"}
            ax.annotate("", end, start, arrowprops=style)
        who, other = ("light", "eye") if what == "shadowing" else ("eye", "light")
        hidden = "in shadow" if what == "shadowing" else "hidden"
        ax.set_title(
            f"{what}: {who} at {grazing_deg:g}°,\n{other} at {abs(math.degrees(near)):g}°;"
            f" dark: {hidden}",
            fontsize=FONT,
        )
        ax.set_xlim(-3.3, 3.3)
        ax.set_ylim(-math.tan(h) - 0.1, 0.3)
    fig.text(
        0.5,
        0.14,
        f"G = {g:.2f}: the lit and seen share of each facet ({1 - g:.0%} dark)",
        ha="center",
        va="top",
        fontsize=FONT,
    )
    fig.tight_layout()
    return save(fig, Path(out))

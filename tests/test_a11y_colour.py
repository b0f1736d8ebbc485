"""Colour on the page: the model colours stay apart for colour-blind readers and stand out
from the panel (3:1, WCAG 1.4.11); the polar plot's rings too. Measured in the page as drawn."""

from __future__ import annotations

import itertools

import numpy as np
import pytest

from lab.web.browser import chromium_path

pytestmark = pytest.mark.skipif(chromium_path() is None, reason="needs Chromium")

# Machado, Oliveira & Fernandes 2009, "A physiologically-based model for simulation of color
# vision deficiency", severity 1.0, applied to linear RGB.
DEFICIENCIES = {
    "protanopia": [
        [0.152286, 1.052583, -0.204868],
        [0.114503, 0.786281, 0.099216],
        [-0.003882, -0.048116, 1.051998],
    ],
    "deuteranopia": [
        [0.367322, 0.860646, -0.227968],
        [0.280085, 0.672501, 0.047413],
        [-0.011820, 0.042940, 0.968881],
    ],
    "tritanopia": [
        [1.255528, -0.076749, -0.178779],
        [-0.078411, 0.930809, 0.147602],
        [0.004733, 0.691367, 0.303900],
    ],
}
MIN_DELTA_E = (
    15.0  # CIE76 in CIELAB: the old palette had pairs at 7.9 (protanopia), 8.9 (deuteranopia)
)
SRGB_TO_XYZ = np.array(
    [[0.4124, 0.3576, 0.1805], [0.2126, 0.7152, 0.0722], [0.0193, 0.1192, 0.9505]]
)
WHITE = np.array([0.95047, 1.0, 1.08883])


def linear(rgb8) -> np.ndarray:
    c = np.asarray(rgb8, dtype=np.float64) / 255
    return np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)


def lab(linear_rgb) -> np.ndarray:
    t = SRGB_TO_XYZ @ np.clip(linear_rgb, 0, 1) / WHITE
    f = np.where(t > (6 / 29) ** 3, np.cbrt(t), t / (3 * (6 / 29) ** 2) + 4 / 29)
    return np.array([116 * f[1] - 16, 500 * (f[0] - f[1]), 200 * (f[1] - f[2])])


def contrast(a8, b8) -> float:
    la, lb = (float(linear(c) @ [0.2126, 0.7152, 0.0722]) for c in (a8, b8))
    return (max(la, lb) + 0.05) / (min(la, lb) + 0.05)


def hex_rgb(text: str) -> list[int]:
    return [int(text[i : i + 2], 16) for i in (1, 3, 5)]


def test_old_palette_fails_the_measure():
    """The measure finds the fault the issue reports (deuteranopia merges the old red and green)."""
    old = [hex_rgb(c) for c in ("#e6194b", "#3cb44b", "#ffe119")]
    m = np.array(DEFICIENCIES["deuteranopia"])
    seen = [lab(m @ linear(c)) for c in old]
    assert np.linalg.norm(seen[0] - seen[1]) < MIN_DELTA_E


@pytest.fixture(scope="module")
def page(tmp_path_factory):
    from tests.webpage import open_page

    models = "&".join(
        f"model={m}" for m in ("phong", "blinn_phong", "cook_torrance", "ggx", "lambert", "ward")
    )
    with open_page(tmp_path_factory, models) as tab:
        yield tab


def test_model_colours_apart_under_colour_blindness_and_against_the_panel(page):
    from lab.app.state import PALETTE
    from lab.app.views.base import BACKGROUND
    from lab.constants import MODEL_COLORS

    shown = page.evaluate("brdfLab.state.panels.map(p => p.color)")
    assert shown == list(MODEL_COLORS) == PALETTE[:6]  # the page and the desktop: one set
    colours = [hex_rgb(c) for c in shown]
    assert min(contrast(c, BACKGROUND) for c in colours) >= 3.0  # the desktop's plots
    panel = page.evaluate("getComputedStyle(document.querySelector('.panel')).backgroundColor")
    background = [int(x) for x in panel[panel.index("(") + 1 : panel.index(")")].split(",")[:3]]
    ratios = [contrast(c, background) for c in colours]
    assert min(ratios) >= 3.0, ratios
    for name, matrix in {"normal": np.eye(3), **DEFICIENCIES}.items():
        seen = [lab(np.array(matrix) @ linear(c)) for c in colours]
        worst = min(np.linalg.norm(a - b) for a, b in itertools.combinations(seen, 2))
        assert worst >= MIN_DELTA_E, (name, worst)


def test_polar_rings_at_three_to_one(page):
    """Pixels of the rings as drawn (a mirror: no lobe in the way), over the panel's colour."""
    page.evaluate("brdfLab.setModel(0, 'mirror')")
    ring = page.evaluate(
        """() => { const p = brdfLab.panel(0); const g = p.polarGeometry; const c = p.polar;
          const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
          const bg = getComputedStyle(p.root).backgroundColor.match(/\\d+/g).map(Number);
          const out = [];
          for (const r of [0.25, 0.5, 0.75, 1]) {
            // the most opaque pixel across the ring at 70° from the normal, toward the light
            let best = null;
            for (let dr = -2; dr <= 2; dr++) {
              const a = -70 * Math.PI / 180, rr = g.radius * r + dr;
              const x = Math.round(g.centre[0] - rr * Math.sin(a));
              const y = Math.round(g.centre[1] - rr * Math.cos(a));
              const k = 4 * (y * c.width + x);
              if (!best || d[k + 3] > best[3]) best = [d[k], d[k + 1], d[k + 2], d[k + 3]];
            }
            const al = best[3] / 255;
            out.push([best.slice(0, 3).map((v, i) => v * al + bg[i] * (1 - al)), bg]);
          }
          return out; }"""
    )
    ratios = [contrast(c, bg) for c, bg in ring]
    assert min(ratios) >= 3.0, ratios

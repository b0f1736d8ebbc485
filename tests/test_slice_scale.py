"""The (θh, θd) slice's colour scale: GGX's f_r diverges toward grazing (θd -> 90°), and a
scale to the maximum paints the specular peak black; the 95th-percentile scale shows it."""

from __future__ import annotations

import os

import numpy as np
import pytest

from lab.views import slice as scale

SIZE = 128
SPECULAR = {"alpha": 0.2, "kd": (0.0, 0.0, 0.0)}  # the peak alone, no diffuse floor


def peak_region(image: np.ndarray) -> np.ndarray:
    """f_r luminance near the specular peak: θh < 6°, 20° < θd < 60° (rows run 90..0°)."""
    n = image.shape[0]
    rows = slice(int(n * (1 - 60 / 90)), int(n * (1 - 20 / 90)))
    return scale.luminance(image[rows, : max(int(n * 6 / 90), 1)])


def test_percentile_top_shows_the_ggx_peak(renderer):
    image = renderer.slice("ggx", SPECULAR, phi_d=90.0, size=SIZE)
    values = scale.luminance(image)
    low, high = scale.colour_range([image])
    assert high == pytest.approx(np.percentile(values[values > 0], 95))
    assert low == pytest.approx(high * 1e-4)
    # The grazing divergence is far above the top: a scale to it would flatten the rest.
    assert np.nanmax(values) > 20 * high
    peak = np.median(peak_region(image))
    assert scale.position(peak, low, high).item() > 0.6  # bright on the new scale
    top = float(np.nanmax(values))  # the old scale: log, 4 decades below the maximum
    assert scale.position(peak, top * 1e-4, top).item() < 0.1  # black
    assert scale.position(peak, 0.0, top, log=False).item() < 0.01  # linear: black


def test_ramp_brightens_monotonically():
    colours = scale.ramp(np.linspace(0, 1, 50))
    luma = colours @ np.array([0.2126, 0.7152, 0.0722])
    assert np.all(np.diff(luma) > 0)  # readable in grey: colour is not the only cue
    assert scale.tick_label(70.57) == "70.6" and scale.tick_label(7.1e-3) == "7.1·10⁻³"


@pytest.mark.skipif(not os.environ.get("DISPLAY"), reason="needs a display (xvfb-run)")
def test_app_slice_says_its_scale_and_paints_the_peak(qtbot, window, output_dir):
    from qtapp import floating_view, settle

    from lab.models import load_model

    window.lab.add(load_model("ggx"), dict(SPECULAR))
    view = floating_view(qtbot, window, "slice", (640, 420))
    settle(qtbot, window)
    assert view.canvas.bar is not None and view.canvas.bar[2]
    assert "95th percentile" in view.note.text() and "log" in view.note.text()
    rect = view.canvas.plot_rects()[0]
    picture = view.canvas.grab().toImage()

    # The peak's pixel (θh = 2°, θd = 40°) is bright; far from it (θh = 60°) dark.
    def grey(theta_h: float, theta_d: float) -> float:
        x = rect.left() + round(theta_h / 90 * (rect.width() - 1))
        y = rect.bottom() - round(theta_d / 90 * (rect.height() - 1))
        colour = picture.pixelColor(x, y)
        return 0.2126 * colour.red() + 0.7152 * colour.green() + 0.0722 * colour.blue()

    assert grey(2, 40) > 100 and grey(2, 40) > 3 * grey(60, 40)
    view.grab().save(str(output_dir / "app_slice_scale.png"))
    window.lab.settings.set("slice_scale", scale.SCALES.index("exposure"))
    settle(qtbot, window)
    assert view.canvas.bar is None and "exposure" in view.note.text()

"""The shared plot scale (lab.plotscale) and the polar figures drawn with it (lab.plots)."""

from __future__ import annotations

import itertools

import numpy as np
import pytest

from lab import plots, plotscale
from lab.constants import GRAZING_DEG
from lab.models import load_model, model_names


def lum(polar) -> np.ndarray:
    return plots.luminance(polar.values.astype(np.float64))


def test_scale_leaves_out_ward_divergence_and_names_it(renderer):
    """Ward at theta_i = 75 deg rises without bound toward theta_o = 90: the scale stops at
    the last value inside GRAZING_DEG and says what it clipped."""
    polar = renderer.polar("ward", load_model("ward").defaults(), 75.0)
    values = lum(polar)
    scale = plotscale.polar_scale(polar.theta_o, [values])
    inside = values[np.abs(polar.theta_o) <= GRAZING_DEG].max()
    assert inside <= scale.top < 1.5 * inside
    assert scale.clipped and scale.clipped_max == values.max() > scale.top
    assert abs(scale.clipped_at) > GRAZING_DEG
    assert "clipped" in scale.note() and f"{scale.clipped_max:.3g}" in scale.note()
    assert scale.radius(values).max() == 1.0


@pytest.mark.parametrize("name", [n for n in model_names() if not load_model(n).delta])
@pytest.mark.parametrize("theta_i", [0.0, 30.0, 45.0, 75.0])
def test_every_lobe_fills_its_plot(renderer, name, theta_i):
    """No empty plot and no flat line: the largest drawn radius is at least 0.5 of the rim,
    and the values left out of the scale all lie beyond GRAZING_DEG."""
    polar = renderer.polar(name, load_model(name).defaults(), theta_i)
    values = lum(polar)
    scale = plotscale.polar_scale(polar.theta_o, [values])
    r = scale.radius(values)
    assert r.max() >= 0.5
    inside = np.abs(polar.theta_o) <= GRAZING_DEG
    assert r[inside].max() >= 0.5  # the lobe itself, not only its grazing tail
    assert (values[inside] <= scale.top).all()


def test_ticks_are_round_and_reach_the_top():
    for peak in (0.0123, 0.171, 0.9, 1.0, 1.2, 7.3, 420.0):
        scale = plotscale.polar_scale(np.array([0.0]), [np.array([peak])])
        assert 2 <= len(scale.ticks) <= 4 and scale.ticks[-1] == pytest.approx(scale.top)
        assert peak <= scale.top <= 2.0 * peak
        step = scale.ticks[0]
        mantissa = step / 10 ** np.floor(np.log10(step))
        assert any(np.isclose(mantissa, m) for m in plotscale.STEPS)
    log = plotscale.polar_scale(np.array([0.0]), [np.array([420.0])], log=True, decades=3)
    assert log.ticks == pytest.approx([10.0, 100.0, 1000.0])
    assert [log.label(t) for t in (1e-4, 0.25, 1000.0, 1e5)] == ["10⁻⁴", "0.25", "1000", "10⁵"]


def _figure_texts(theta_i: float):
    import matplotlib.pyplot as plt

    from lab.render import Renderer

    renderer = Renderer()
    fig, ax = plots.figure(polar=True)
    lobe = renderer.polar("cook_torrance", load_model("cook_torrance").defaults(), theta_i)
    plots.draw_polar(ax, [(lobe, "cook_torrance", None)], theta_i, "f_r")
    fig.tight_layout()
    fig.canvas.draw()
    names = {"normal", "incident", "mirror"}
    texts = [t for t in ax.texts if t.get_text().split("\n")[0].split(" ")[0] in names]
    return fig, ax, texts, plt


@pytest.mark.parametrize(
    "theta_i", [0.0, 5.0, 8.0, 10.0, 15.0, 30.0, 40.0, 45.0, 50.0, 60.0, 75.0, 85.0, 89.0]
)
def test_direction_labels_never_collide_or_clip(theta_i):
    fig, ax, texts, plt = _figure_texts(theta_i)
    renderer = fig.canvas.get_renderer()
    boxes = [t.get_window_extent(renderer) for t in texts]
    page = fig.bbox
    try:
        for box, text in zip(boxes, texts, strict=True):
            inside = box.x0 >= page.x0 and box.x1 <= page.x1 and box.y0 >= page.y0
            assert inside and box.y1 <= page.y1, f"{text.get_text()!r} leaves the figure"
        for a, b in itertools.combinations(range(len(boxes)), 2):
            assert not boxes[a].overlaps(boxes[b]), (texts[a].get_text(), texts[b].get_text())
        # Nor the angles at the rim (at 45° 'incident' ran into '60°' once the layout moved).
        for tick in ax.get_xticklabels():
            rim = tick.get_window_extent(renderer)
            for box, text in zip(boxes, texts, strict=True):
                assert not box.overlaps(rim), (text.get_text(), tick.get_text())
        # The light is on the right, as on the spheres: the incident line ends right of centre.
        if theta_i >= 8:
            incident = next(t for t in texts if t.get_text() == "incident")
            centre = ax.transData.transform((0.0, 0.0))[0]
            assert incident.get_window_extent(renderer).x1 > centre
            mirror = next(t for t in texts if t.get_text() == "mirror")
            assert mirror.get_window_extent(renderer).x0 < centre
        # Radial ticks: numbers; the unit in the title.
        labels = [t.get_text() for t in ax.get_yticklabels()]
        assert len(labels) >= 2 and all(float(x) > 0 for x in labels)
        assert plotscale.UNIT in ax.get_title()
    finally:
        plt.close(fig)

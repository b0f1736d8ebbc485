"""The desktop lab's 3D lobe view through the real window and real OpenGL (xvfb-run)."""

from __future__ import annotations

import os
import sys

import numpy as np
import pytest

pytest.importorskip("pytestqt")
if sys.platform.startswith("linux") and not os.environ.get("DISPLAY"):
    pytest.skip("needs a display: run under xvfb-run -a", allow_module_level=True)

from PyQt6.QtCore import QPoint, QPointF, Qt  # noqa: E402
from PyQt6.QtGui import QWheelEvent  # noqa: E402
from PyQt6.QtTest import QTest  # noqa: E402
from PyQt6.QtWidgets import QApplication, QCheckBox  # noqa: E402
from qtapp import settle  # noqa: E402

from lab.models import load_model  # noqa: E402


def check_box(widget, text: str) -> QCheckBox:
    return next(c for c in widget.findChildren(QCheckBox) if c.text() == text)


def lit(image: np.ndarray) -> np.ndarray:
    """Pixels that are not the background (the lobes, coloured)."""
    rgb = image[..., :3].astype(int)
    return rgb.max(axis=-1) - rgb.min(axis=-1) > 40


def test_lobe_view_draws_every_model_and_follows_the_mouse(qtbot, window, output_dir):
    window.lab.add(load_model("phong"), {"ke": 20.0})  # red
    window.lab.add(load_model("lambert"))  # green
    window.lab.settings.set("theta_i", 40.0)
    settle(qtbot, window)
    view = window.view("lobe3d")
    assert [s.model.name for s, _ in view.data] == ["phong", "lambert"]
    image = view.image
    canvas = view.canvas
    assert image.shape == (canvas.height(), canvas.width(), 4)  # drawn at its size on screen
    red = lit(image) & (image[..., 0] > image[..., 1])
    green = lit(image) & (image[..., 1] > image[..., 0])
    assert red.sum() > 200 and green.sum() > 200
    assert not view.coarse  # refined to the full grid
    view.export_png(output_dir / "app_view_lobe3d_two.png")

    # Dragging rotates the camera: yaw and pitch change, and so does the picture.
    s = window.lab.settings
    yaw, pitch = s["lobe_yaw"], s["lobe_pitch"]
    centre = QPoint(canvas.width() // 2, canvas.height() // 2)
    QTest.mousePress(canvas, Qt.MouseButton.LeftButton, pos=centre)
    QTest.mouseMove(canvas, centre + QPoint(40, 20))
    QTest.mouseRelease(canvas, Qt.MouseButton.LeftButton, pos=centre + QPoint(40, 20))
    settle(qtbot, window)
    assert s["lobe_yaw"] == pytest.approx(yaw + 0.4) and s["lobe_pitch"] == pytest.approx(
        pitch + 0.2
    )
    assert not np.array_equal(view.image, image)

    # The wheel zooms in: the lobes cover more of the picture.
    before = lit(view.image).sum()
    for _ in range(3):
        event = QWheelEvent(
            QPointF(centre),
            QPointF(canvas.mapToGlobal(centre)),
            QPoint(),
            QPoint(0, 120),
            Qt.MouseButton.NoButton,
            Qt.KeyboardModifier.NoModifier,
            Qt.ScrollPhase.NoScrollPhase,
            False,
        )
        QApplication.sendEvent(canvas, event)
    settle(qtbot, window)
    assert s["lobe_zoom"] == pytest.approx(1.1**3)
    assert lit(view.image).sum() > 1.15 * before

    # Wire: only the grid lines are drawn, far fewer pixels.
    solid = lit(view.image).sum()
    view.wire.setChecked(True)
    settle(qtbot, window)
    assert lit(view.image).sum() < 0.6 * solid
    view.export_png(output_dir / "app_view_lobe3d_wire.png")


def test_lobe_view_shares_log_and_cosine_with_the_polar_plot(qtbot, window, output_dir):
    window.lab.add(load_model("phong"), {"ke": 200.0})
    settle(qtbot, window)
    view = window.view("lobe3d")
    linear = lit(view.image).sum()
    # The log scale lifts the diffuse floor (3 decades below the peak) toward the peak.
    check_box(window.view("polar"), "log scale").setChecked(True)
    assert window.lab.settings["polar_log"] and check_box(view, "log scale").isChecked()
    settle(qtbot, window)
    assert lit(view.image).sum() > 2 * linear
    view.export_png(output_dir / "app_view_lobe3d_log.png")
    # f_r cos theta_o: the same setting in both views; the scale is f_r cos's peak.
    check_box(view, "f_r · cos θo").setChecked(True)
    assert (
        window.lab.settings["polar_cos"]
        and check_box(window.view("polar"), "f_r · cos θo").isChecked()
    )
    settle(qtbot, window)
    theta_i = window.lab.settings["theta_i"]
    expected = window.renderer.lobe_peak(load_model("phong"), {"ke": 200.0}, theta_i, 0.0, True)
    assert view.data[0][1] == pytest.approx(expected)
    without = window.renderer.lobe_peak(load_model("phong"), {"ke": 200.0}, theta_i, 0.0)
    assert expected[0] == pytest.approx(without[0] * np.cos(np.radians(theta_i)), rel=1e-3)


def test_delta_model_spike_in_the_app(qtbot, window):
    window.lab.add(load_model("mirror"))
    settle(qtbot, window)
    view = window.view("lobe3d")
    ((state, (peak, spike)),) = view.data
    assert peak == 0.0 and spike > 0.5
    assert lit(view.image).sum() > 50  # the spike, in the model's colour

"""Presenter mode on a projector's screen: 1024x768 and 1280x800, every preset, nothing cut.

Without a window manager (Xvfb) full screen is not applied, so the window is given the
screen's size; it must accept it (its minimum fits) and lay every text out in full.
"""

from __future__ import annotations

import os
import sys

import pytest

pytest.importorskip("pytestqt")
pg = pytest.importorskip("pyqtgraph")
if sys.platform.startswith("linux") and not os.environ.get("DISPLAY"):
    pytest.skip("needs a display: run under xvfb-run -a", allow_module_level=True)

from PyQt6.QtCore import Qt  # noqa: E402
from PyQt6.QtWidgets import (  # noqa: E402
    QAbstractButton,
    QComboBox,
    QLabel,
    QLineEdit,
    QTabBar,
    QWidget,
)
from qtapp import settle  # noqa: E402

from lab.app.state import shipped_presets  # noqa: E402
from lab.app.views.polar import glyph_box  # noqa: E402
from lab.app.widgets import LiveText  # noqa: E402
from lab.models import load_model  # noqa: E402


def cut_texts(window) -> list[str]:
    """Visible labels, buttons and menus whose one-line text is wider than their room."""
    cut = []
    for widget in window.findChildren(QWidget):
        if not widget.isVisible() or widget.visibleRegion().isEmpty():
            continue
        if isinstance(widget, QLabel) and (widget.wordWrap() or "<" in widget.text()):
            continue
        if isinstance(widget, (QLabel, QAbstractButton)):
            text, room = widget.text().replace("&", ""), widget.contentsRect().width()
            if isinstance(widget, QAbstractButton) and not isinstance(widget, QLabel):
                room -= 6  # the button's own margins
        elif isinstance(widget, QComboBox):
            text, room = widget.currentText(), widget.contentsRect().width() - 24
        elif isinstance(widget, QLineEdit):  # a value box that scrolls its text
            text, room = widget.text(), widget.contentsRect().width() - 8
        elif isinstance(widget, LiveText):  # a short form or nothing is fine, "…" is not
            if widget.painted() not in (widget.text(), widget.short, ""):
                cut.append(f"LiveText {widget.text()!r} shows {widget.painted()!r}")
            continue
        elif isinstance(widget, QTabBar):  # the docks' tabs: elided, or scrolled out of view
            cut += cut_tabs(widget)
            continue
        else:
            continue
        for line in text.splitlines():
            need = widget.fontMetrics().horizontalAdvance(line)
            if line and need > room + 1:
                cut.append(f"{type(widget).__name__} {line!r}: {need} px > {room} px")
    for view in window.findChildren(QWidget):  # captions a view paints itself
        if view.isVisible() and getattr(view, "elided", None):
            cut += [f"{type(view).__name__} caption {c!r} elided" for c in view.elided]
    cut += cut_plot_texts(window)
    for dock in window.docks.values():
        if dock.isVisible() and not dock.visibleRegion().isEmpty():
            need = dock.fontMetrics().horizontalAdvance(dock.windowTitle())
            if need > dock.width() - 50:  # the float and close buttons
                cut.append(f"dock title {dock.windowTitle()!r}")
    return cut


def cut_plot_texts(window) -> list[str]:
    """Labels inside the plots (pyqtgraph text items: the polar plot's directions and ring
    values, axis notes) that reach past their plot's edge, where they are cut off."""
    cut = []
    for widget in window.findChildren(pg.PlotWidget):
        if not widget.isVisible() or widget.viewport().visibleRegion().isEmpty():
            continue
        box = widget.getViewBox().sceneBoundingRect()
        texts = [
            item
            for item in widget.getViewBox().addedItems
            if isinstance(item, pg.TextItem) and item.isVisible() and item.toPlainText()
        ]

        for k, item in enumerate(texts):
            r = item.sceneBoundingRect()
            if r.left() < box.left() - 1 or r.right() > box.right() + 1:
                cut.append(f"plot text {item.toPlainText()!r} reaches past its plot")
            for other in texts[k + 1 :]:
                if glyph_box(item).intersects(glyph_box(other)):
                    cut.append(
                        f"plot texts {item.toPlainText()!r}, {other.toPlainText()!r} overlap"
                    )
    return cut


def cut_tabs(bar: QTabBar) -> list[str]:
    """Tabs whose title is elided or that lie (partly) outside the bar (scroll buttons)."""
    cut = []
    metrics = bar.fontMetrics()
    for i in range(bar.count()):
        if not bar.isTabVisible(i):
            continue
        rect, text = bar.tabRect(i), bar.tabText(i).replace("&", "")
        need = metrics.horizontalAdvance(text)
        room = (
            rect.width()
            - 2 * bar.style().pixelMetric(bar.style().PixelMetric.PM_TabBarTabHSpace) // 2
        )
        outside = rect.left() < 0 or rect.right() > bar.width()
        elided = bar.elideMode() != Qt.TextElideMode.ElideNone and need > room + 1
        if outside or elided:
            cut.append(
                f"tab {text!r}: {need} px in {room} px{', scrolled away' if outside else ''}"
            )
    return cut


@pytest.mark.parametrize("size", [(1024, 768), (1280, 800)], ids=["1024x768", "1280x800"])
def test_presenter_fits_the_projector(qtbot, window, output_dir, size):
    window.lab.add(load_model("phong"))
    window.lab.add(load_model("cook_torrance"))
    window.toggle_presenter()
    try:
        qtbot.wait(100)
        for preset in [None, *shipped_presets()]:
            if preset is not None:
                window.load_preset(preset)
            window.setGeometry(0, 0, *size)
            qtbot.wait(60)
            settle(qtbot, window)
            name = preset.stem[:2] if preset else "all"
            window.grab().save(str(output_dir / f"presenter_{size[0]}x{size[1]}_{name}.png"))
            assert (window.width(), window.height()) == size, f"{name}: needs {window.size()}"
            cut = cut_texts(window)
            assert cut == [], f"{name}: {cut}"
            # The views get the room: the controls column stays a narrow one.
            assert window.controls_dock.width() <= 0.34 * size[0], name
    finally:
        window.toggle_presenter()


def test_polar_direction_labels_become_letters_where_words_collide(qtbot, window):
    """In a small polar plot with the presenter's large text, 'normal', 'incident' and
    'mirror' would run into each other: N, L and R show instead, the legend says what they
    are; in a large plot the words show."""
    from qtapp import floating_view

    window.lab.add(load_model("phong"))
    window.toggle_presenter()
    try:
        for size, letters in (((300, 260), True), ((1000, 700), False)):
            view = floating_view(qtbot, window, "polar", size)
            qtbot.wait(60)
            settle(qtbot, window)
            words = [text.toPlainText() for _, text in view.marks]
            assert words == (["N", "L", "R"] if letters else ["normal", "incident", "mirror"])
            assert ("N normal" in view.legend.text()) == letters
            assert cut_plot_texts(window) == [], size
    finally:
        window.toggle_presenter()

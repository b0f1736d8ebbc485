"""What the layout tests measure in the desktop lab's window: texts cut short or lying on
each other, the size of text and of each plot, and whether the window lies on its screen."""

from __future__ import annotations

import pyqtgraph as pg
from PyQt6.QtCore import QRectF, Qt
from PyQt6.QtGui import QFont, QFontInfo, QImage, QPainter
from PyQt6.QtWidgets import (
    QAbstractButton,
    QApplication,
    QComboBox,
    QLabel,
    QLineEdit,
    QTabBar,
    QWidget,
)

from lab.app.views.polar import glyph_box
from lab.app.widgets import LiveText


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


def off_screen(window) -> str:
    """'' when the window, its frame included, lies inside its screen's free area."""
    room = (window.screen() or QApplication.primaryScreen()).availableGeometry()
    frame = window.frameGeometry()
    if room.contains(frame):
        return ""
    return f"window {frame.getRect()} outside the screen's {room.getRect()}"


def shown_views(window) -> list:
    """The view widgets on screen now (a dock shown and in front of its tabs)."""
    return [
        v
        for v in window.views
        if window.docks[v.name].isVisible() and v.isVisible() and not v.visibleRegion().isEmpty()
    ]


def view_fonts(view) -> list[tuple[str, object]]:
    """(what, font) of every text drawn inside a view's pictures and plots: pyqtgraph's
    text items, axes and legends, and the widgets that paint captions (plot_text)."""
    fonts = []
    for widget in view.findChildren(pg.PlotWidget):
        if not widget.isVisible():
            continue
        item = widget.getPlotItem()
        for text in item.getViewBox().addedItems:
            if isinstance(text, pg.TextItem) and text.isVisible() and text.toPlainText():
                fonts.append((f"text {text.toPlainText()!r}", text.textItem.font()))
        for name in ("left", "bottom"):
            axis = item.getAxis(name)
            if axis.isVisible():
                fonts.append((f"{name} ticks", axis.style["tickFont"] or axis.font()))
                if axis.label.isVisible() and axis.labelText:
                    fonts.append((f"{name} label {axis.labelText!r}", axis.label.font()))
        if item.legend is not None and item.legend.isVisible():
            for _, label in item.legend.items:  # drawn as HTML at the size in its options
                font, size = QFont(label.item.font()), str(label.opts.get("size") or "")
                if size.endswith("pt"):
                    font.setPointSizeF(float(size[:-2]))
                elif size.endswith("px"):
                    font.setPixelSize(round(float(size[:-2])))
                fonts.append((f"legend {label.text!r}", font))
    for widget in view.findChildren(QWidget):
        if getattr(widget, "plot_text", False) and widget.isVisible():
            fonts.append((type(widget).__name__, widget.font()))
    return fonts


def small_texts(window, px: int) -> list[str]:
    """Texts inside the shown views smaller than `px` pixels (the font's pixel size)."""
    small = []
    for view in shown_views(window):
        for what, font in view_fonts(view):
            size = QFontInfo(font).pixelSize()
            if size < px:
                small.append(f"{view.name}: {what} is {size} px")
    return small


def axis_overlaps(window) -> list[str]:
    """Tick labels of a plot's axes whose letters lie on each other, as pyqtgraph draws
    them (the boxes of the glyphs, not of the lines)."""
    found = []
    image = QImage(8, 8, QImage.Format.Format_RGB32)
    for view in shown_views(window):
        for widget in view.findChildren(pg.PlotWidget):
            if not widget.isVisible():
                continue
            for name in ("left", "bottom"):
                axis = widget.getPlotItem().getAxis(name)
                if not axis.isVisible():
                    continue
                painter = QPainter(image)
                painter.setFont(axis.style["tickFont"] or axis.font())
                metrics = painter.fontMetrics()
                specs = axis.generateDrawSpecs(painter)
                painter.end()
                boxes = []
                for rect, _, text in specs[2] if specs else []:
                    ink = metrics.tightBoundingRect(text)
                    box = QRectF(0, 0, ink.width(), ink.height())
                    box.moveCenter(rect.center())
                    if name == "left":
                        box.moveRight(rect.right())
                    boxes.append((box, text))
                for i, (a, ta) in enumerate(boxes):
                    for b, tb in boxes[i + 1 :]:
                        if a.intersects(b):
                            found.append(f"{view.name} {name} ticks {ta!r} and {tb!r} overlap")
    return found


def tick_texts(view, name: str) -> list[str]:
    """The tick labels an axis of the view's (first) plot draws now."""
    image = QImage(8, 8, QImage.Format.Format_RGB32)
    axis = view.findChildren(pg.PlotWidget)[0].getPlotItem().getAxis(name)
    painter = QPainter(image)
    specs = axis.generateDrawSpecs(painter)
    painter.end()
    return [text for _, _, text in specs[2]] if specs else []


def plot_sizes(window) -> dict[str, int]:
    """The size in pixels of each shown view's picture or plot: the polar plot's disc
    diameter, a sphere's or object's side, the 3D lobe's square, a slice's side, the IBL
    picture's side and its error plot's height."""
    sizes = {}
    for view in shown_views(window):
        if view.name == "polar":
            sizes["polar"] = round(2.0 / view.plot.getViewBox().viewPixelSize()[0])
        elif view.name in ("sphere", "object", "ibl"):
            sizes[view.name] = view.canvas.cell()[1]
            if view.name == "ibl":
                sizes["ibl plot"] = view.plot.getPlotItem().getViewBox().height()
        elif view.name == "lobe3d":
            sizes["lobe3d"] = min(view.canvas.width(), view.canvas.height())
        elif view.name == "slice":
            rects = view.canvas.plot_rects(max(len(view.canvas.images), 1))
            sizes["slice"] = rects[0].width()
    return {k: int(v) for k, v in sizes.items()}

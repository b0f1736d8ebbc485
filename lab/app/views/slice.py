"""The (θh, θd) slice's widget: an image of f_r over the half and difference angles."""

from __future__ import annotations

import numpy as np
from PyQt6.QtCore import QRect, Qt
from PyQt6.QtGui import QColor, QFont, QFontInfo, QFontMetrics, QImage, QPainter, QPen
from PyQt6.QtWidgets import QWidget

from lab.app.state import ModelState
from lab.app.views.base import BACKGROUND, PLOT_TEXT_PX, View, opaque, state_key, tonemap
from lab.app.widgets import LiveText, SettingCombo, SettingSlider
from lab.views import slice as scale


class SliceCanvas(QWidget):
    """One square image per model over theta_h (x) and theta_d (y), both axes 0..90 deg.

    Drawn by hand so the axes can never drift or stretch: every plot is a square at the
    same scale, whatever the widget's shape.
    """

    plot_text = True  # in the plot font (View.apply_font)

    def __init__(self):
        super().__init__()
        self.images: list[tuple[QImage, str, str]] = []
        self.bar: tuple[float, float, bool] | None = None  # the colour scale (low, high, log)
        self.setMinimumSize(160, 120)
        opaque(self)

    def axis_font(self) -> QFont:
        """Tick and axis labels a little smaller than the titles, but never below the
        presenter's PLOT_TEXT_PX once the titles are that large."""
        font = QFont(self.font())
        if QFontInfo(font).pixelSize() < PLOT_TEXT_PX:
            font.setPointSizeF(max(self.font().pointSizeF() * 0.85, 6.0))
        return font

    def margins(self) -> tuple[int, int, int, int]:
        """Left, top, right and bottom room around each plot for titles, ticks, labels."""
        fm = QFontMetrics(self.axis_font())
        line = fm.height()
        title = QFontMetrics(self.font()).height()
        return (fm.horizontalAdvance("90°") + line + 10, title + 4, 12, 2 * line + 6)

    BAR_MIN_SIDE = 64  # plots smaller than this with the bar beside them go without it

    def bar_width(self, count: int | None = None) -> int:
        """Room on the right for the colour bar and its numbers: 0 without a bar, or where
        it would shrink the plots below BAR_MIN_SIDE (a small dock; the view's note then
        names the scale and its top)."""
        if self.bar is None:
            return 0
        room = 18 + QFontMetrics(self.axis_font()).horizontalAdvance("8.8·10⁻⁸ ") + 8
        n = max(count if count is not None else len(self.images), 1)
        return room if self.grid(self.width() - room, n)[0] >= self.BAR_MIN_SIDE else 0

    def grid(self, width: int, n: int) -> tuple[int, int, int]:
        """(side, columns, rows) of the grid of n squares in `width` that makes them largest."""
        left, top, right, bottom = self.margins()
        best = (0, 1, 1)
        for cols in range(1, n + 1):
            rows = -(-n // cols)
            side = min(width // cols - left - right, self.height() // rows - top - bottom)
            if side > best[0]:
                best = (side, cols, rows)
        return best

    def plot_rects(self, count: int | None = None) -> list[QRect]:
        """Where each image goes: squares of one size in the grid (columns x rows) that
        makes them largest, centred."""
        n = max(count if count is not None else len(self.images), 1)
        left, top, right, bottom = self.margins()
        width = self.width() - self.bar_width(n)
        side, cols, rows = self.grid(width, n)
        side = max(side, 16)
        cell_w, cell_h = left + side + right, top + side + bottom
        x0 = (width - cols * cell_w) // 2
        y0 = (self.height() - rows * cell_h) // 2
        return [
            QRect(x0 + (i % cols) * cell_w + left, y0 + (i // cols) * cell_h + top, side, side)
            for i in range(n)
        ]

    def paintEvent(self, event) -> None:
        painter = QPainter(self)
        painter.fillRect(self.rect(), QColor(*BACKGROUND))
        title_metrics = QFontMetrics(self.font())
        self.elided: list[str] = []  # captions cut short in this paint
        font = self.axis_font()
        fm = QFontMetrics(font)
        line = fm.height()
        axis = QColor(170, 170, 170)
        for rect, (image, caption, color) in zip(self.plot_rects(), self.images, strict=False):
            if image.width() == rect.width() and image.height() == rect.height():
                painter.drawImage(rect.topLeft(), image)
            else:
                painter.drawImage(rect, image)
            painter.setPen(QColor(color))
            # The caption over its image, else over the whole cell (axis margins too), in a
            # font down to 3/4 of the view's; elided only past that (and noted for the tests).
            left, _, right, _ = self.margins()
            caption_font = QFont(self.font())
            room, x = rect.width() + 40, rect.left() - 20
            if title_metrics.horizontalAdvance(caption) > room:
                room, x = left + rect.width() + right - 4, rect.left() - left + 2
                size = caption_font.pointSizeF()
                while (
                    size > 0
                    and QFontMetrics(caption_font).horizontalAdvance(caption) > room
                    and caption_font.pointSizeF() > 0.76 * size
                ):
                    caption_font.setPointSizeF(caption_font.pointSizeF() - 0.05 * size)
            metrics = QFontMetrics(caption_font)
            text = metrics.elidedText(caption, Qt.TextElideMode.ElideRight, room)
            if text != caption:
                self.elided.append(caption)
            painter.setFont(caption_font)
            painter.drawText(
                QRect(
                    x,
                    rect.top() - title_metrics.height() - 3,
                    room,
                    title_metrics.height() + 2,
                ),
                Qt.AlignmentFlag.AlignCenter,
                text,
            )
            painter.setFont(font)
            painter.setPen(QPen(axis, 1))
            painter.drawRect(rect.adjusted(0, 0, -1, -1))
            room = rect.width() / fm.horizontalAdvance("90° ")
            ticks = (0, 30, 60, 90) if room >= 4.5 else (0, 45, 90) if room >= 3 else (0, 90)
            for tick in ticks:
                x = rect.left() + round(tick / 90 * (rect.width() - 1))
                y = rect.bottom() - round(tick / 90 * (rect.height() - 1))
                painter.drawLine(x, rect.bottom(), x, rect.bottom() + 3)
                painter.drawLine(rect.left() - 3, y, rect.left(), y)
                painter.drawText(
                    QRect(x - 30, rect.bottom() + 4, 60, line),
                    Qt.AlignmentFlag.AlignHCenter,
                    f"{tick}°",
                )
                painter.drawText(
                    QRect(rect.left() - 64, y - line // 2, 60, line),
                    Qt.AlignmentFlag.AlignRight | Qt.AlignmentFlag.AlignVCenter,
                    f"{tick}°",
                )
            painter.drawText(
                QRect(rect.left(), rect.bottom() + 4 + line, rect.width(), line),
                Qt.AlignmentFlag.AlignHCenter,
                "θh",
            )
            painter.save()
            painter.translate(rect.left() - fm.horizontalAdvance("90°") - 8, rect.center().y())
            painter.rotate(-90)
            painter.drawText(
                QRect(-rect.height() // 2, -line, rect.height(), line),
                Qt.AlignmentFlag.AlignCenter,
                "θd",
            )
            painter.restore()
        if self.bar is not None and self.images and self.bar_width():
            self.paint_bar(painter, self.plot_rects()[0], font)
        painter.end()

    def paint_bar(self, painter: QPainter, rect: QRect, font: QFont) -> None:
        """The colour scale beside the images: the ramp, its ends' values (and the middle
        of a log scale) in sr^-1."""
        low, high, log = self.bar
        x = self.width() - self.bar_width() + 4
        steps = np.linspace(1.0, 0.0, max(rect.height(), 2))
        colours = (scale.ramp(steps) * 255 + 0.5).astype(np.uint8)
        for row, (r, g, b) in enumerate(colours):
            painter.setPen(QColor(int(r), int(g), int(b)))
            painter.drawLine(x, rect.top() + row, x + 12, rect.top() + row)
        painter.setPen(QColor(170, 170, 170))
        painter.setFont(font)
        line = QFontMetrics(font).height()
        marks = [(0.0, high), (1.0, low)]
        if log:
            marks.append((0.5, float(np.sqrt(low * high))))
        for where, value in marks:
            y = rect.top() + round(where * (rect.height() - 1))
            painter.drawLine(x + 12, y, x + 15, y)
            painter.drawText(
                QRect(x + 17, y - line // 2, self.width() - x - 17, line),
                Qt.AlignmentFlag.AlignLeft | Qt.AlignmentFlag.AlignVCenter,
                scale.tick_label(value),
            )


class SliceView(View):
    """f_r over (theta_h, theta_d) at a chosen phi_d, one image per visible model."""

    title = "Image slice (θh, θd)"
    name = "slice"
    FAST_SIZE = 96

    def __init__(self, lab, renderer):
        super().__init__(lab, renderer)
        s = lab.settings
        phi_d = SettingSlider.of(s, "phi_d")
        phi_d.setToolTip(
            "the slice's difference azimuth; the images use the spheres' exposure and gamma"
        )
        self.tools.addWidget(phi_d, 1)
        colours = SettingCombo(s, "slice_scale", scale.SCALES)
        colours.setToolTip(
            "colours: log or linear scale to the 95th percentile (a grazing divergence "
            "would take a scale to the maximum), or the spheres' exposure and gamma"
        )
        self.tools.addWidget(colours)
        self.note = LiveText(optional=True)  # which scale, beside the menu where it fits
        self.tools.addWidget(self.note, 2)
        self.canvas = SliceCanvas()
        self.layout_.addWidget(self.canvas, 1)
        self.data: list[tuple[ModelState, np.ndarray]] = []

    def axes(self) -> list[tuple[tuple[float, float], tuple[float, float], QRect]]:
        """Each plot's (theta_h range, theta_d range, rectangle on screen)."""
        return [
            ((0.0, 90.0), (0.0, 90.0), rect)
            for rect in self.canvas.plot_rects(len(self.canvas.images))
        ][: len(self.canvas.images)]

    def side(self) -> int:
        rects = self.canvas.plot_rects(len(self.lab.visible_models()))
        return min(max(rects[0].width(), 32), 256)

    settings_used = ("phi_d", "exposure", "gamma", "slice_scale")

    def own_inputs(self) -> tuple:
        return (self.side(),)

    def draw(self, fast: bool) -> bool:
        s = self.lab.settings
        full = self.side()
        small = min(full, self.FAST_SIZE)
        self.data, images = [], []
        coarse = False
        tone = (s["exposure"], s["gamma"])
        for state in self.lab.visible_models():
            key = state_key(state, s["phi_d"])
            image, rough = self.best(
                state,
                fast,
                (*key, small),
                (*key, full),
                lambda use_full, st=state: self.renderer.slice(
                    st.model, st.values, s["phi_d"], full if use_full else small
                ),
            )
            coarse = coarse or rough
            if image is None:
                continue
            self.data.append((state, image))
        mapped = scale.SCALES[s["slice_scale"]] != "exposure"
        if mapped and self.data:  # one scale for every model: their colours compare
            log = scale.SCALES[s["slice_scale"]] == "log"
            low, high = scale.colour_range([im for _, im in self.data], log)
            self.canvas.bar = (low, high, log)
            for state, image in self.data:
                shown = tonemap(scale.coloured(image, low, high, log), 0.0, 1.0)
                images.append((shown, state.label, state.color))
            top = f"top {scale.tick_label(high)} = {scale.TOP_PERCENTILE:g}th pct"
            self.note.short = f"{'log' if log else 'linear'}, {top}"
            self.note.setText(f"{scale.scale_note(log)} ({scale.tick_label(high)} {scale.UNIT})")
        else:
            self.canvas.bar = None
            for state, image in self.data:
                images.append((self.toned_image(state, image, tone), state.label, state.color))
            self.note.short = "exposure"
            self.note.setText("f_r with the spheres' exposure and gamma" if self.data else "")
        self.note.setToolTip(self.note.text())
        self.canvas.images = images
        self.canvas.update()
        return coarse

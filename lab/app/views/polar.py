"""The polar plot's widget: f_r in the plane of incidence for every visible model."""

from __future__ import annotations

import csv
import html
import math
from collections.abc import Callable
from pathlib import Path

import numpy as np
import pyqtgraph as pg
from PyQt6.QtCore import Qt
from PyQt6.QtGui import QColor, QFontMetrics
from PyQt6.QtWidgets import QBoxLayout, QLabel, QPushButton

from lab import constants, describe, plotscale
from lab.app.state import ModelState
from lab.app.views.base import LUMA, QWIDGETSIZE_MAX, View, opaque, pen, state_key
from lab.app.widgets import SettingCheck


def glyph_box(text: pg.TextItem):
    """The scene box of a text item's letters (its document margin left out)."""
    margin = text.textItem.document().documentMargin()
    return text.sceneBoundingRect().adjusted(margin, margin, -margin, -margin)


class PolarView(View):
    """The lobe in the plane of incidence, with normal, incident and mirror directions."""

    title = "Polar plot"
    name = "polar"
    DECADES = constants.PLOT_DECADES

    def __init__(self, lab, renderer):
        super().__init__(lab, renderer)
        s = lab.settings
        self.tools.addWidget(SettingCheck(s, "polar_log", "log scale"))
        self.tools.addWidget(SettingCheck(s, "polar_cos", "f_r · cos θo"))
        export = QPushButton("CSV…")
        export.setToolTip("save the plotted lobes as CSV")
        export.clicked.connect(self._ask_csv)
        self.tools.addWidget(export)
        self.tools.addStretch(1)
        self.plot = pg.PlotWidget()
        opaque(self.plot.viewport())
        self.plot.setAspectLocked(True)
        self.plot.hideAxis("left")
        self.plot.hideAxis("bottom")
        self.plot.setMouseEnabled(False, False)
        # Plot and legend: side by side in a wide view, stacked in a tall one (resizeEvent).
        self.body = QBoxLayout(QBoxLayout.Direction.TopToBottom)
        self.body.addWidget(self.plot, 1)
        self.layout_.addLayout(self.body, 1)
        self.data: list[tuple[ModelState, object]] = []
        # Fixed items are made once; curves, rings and tick labels are reused (re-creating
        # items costs milliseconds). x = -r sin(theta_o): the light on the right, as on the
        # spheres and the 3D lobe.
        self.plot.plot([-1.05, 1.05], [0, 0], pen=pg.mkPen((150, 150, 150)))
        self.rings: list[tuple[pg.PlotDataItem, pg.TextItem]] = []
        self.marks = []
        self.texts: list[pg.TextItem] = []
        for label, color in (
            ("normal", (200, 200, 200)),
            ("incident", (255, 210, 0)),
            ("mirror", (120, 200, 255)),
        ):
            line = self.plot.plot(pen=pg.mkPen(color, width=1, style=Qt.PenStyle.DashLine))
            text = pg.TextItem(label, color=color, anchor=(0.5, 1.0))
            self.plot.addItem(text)
            self.texts.append(text)
            self.marks.append((line, text))
        self.curves: list[tuple[pg.PlotDataItem, pg.PlotDataItem]] = []
        self.clip_marks = self.plot.plot(
            pen=None, symbol="t", symbolBrush=(220, 40, 60), symbolPen=None, symbolSize=9
        )
        # The legend is a label below the plot: it wraps instead of running out of the view.
        self.legend = QLabel()
        self.legend.plot_text = True  # in the plot font (View.apply_font)
        self.legend.setWordWrap(True)
        self.legend.setTextFormat(Qt.TextFormat.RichText)
        self.legend.setAlignment(Qt.AlignmentFlag.AlignLeft | Qt.AlignmentFlag.AlignVCenter)
        self.body.addWidget(self.legend)
        self.scale: plotscale.Scale | None = None
        self.marked: float | None = None
        self.short_marks = False  # N, L, R instead of the words (place_marks)
        self.plot.setRange(xRange=(-1.15, 1.15), yRange=(-0.2, 1.3), padding=0)

    def resizeEvent(self, event) -> None:
        wide = self.width() > 1.6 * self.height()
        self.body.setDirection(
            QBoxLayout.Direction.LeftToRight if wide else QBoxLayout.Direction.TopToBottom
        )
        self.legend.setMaximumWidth(int(0.4 * self.width()) if wide else QWIDGETSIZE_MAX)
        super().resizeEvent(event)

    def draw_rings(self, scale: plotscale.Scale) -> None:
        """Rings at the scale's ticks (and the rim), labelled in sr^-1 along the baseline."""
        angle = np.radians(np.linspace(-90, 90, 91))
        grid = pg.mkPen((90, 90, 90), style=Qt.PenStyle.DotLine)
        while len(self.rings) < len(scale.ticks) + 1:
            text = pg.TextItem("", color=(190, 190, 190), anchor=(0.5, 0.0))
            self.plot.addItem(text)
            self.texts.append(text)
            self.rings.append((self.plot.plot(pen=grid), text))
        radii = list(scale.radius(scale.ticks))
        labels = [scale.label(t) for t in scale.ticks]  # the unit is named in the legend
        # Labels that would run into the next one (large fonts, a small view) are left out,
        # from the centre outward; the rim's always stays.
        unit_px = 1.0 / max(self.plot.getViewBox().viewPixelSize()[0], 1e-9)
        metrics = QFontMetrics(self.rings[0][1].textItem.font()) if self.rings else None
        right = math.inf
        for index in range(len(labels) - 1, -1, -1):
            if metrics is None:
                break
            width = metrics.horizontalAdvance(labels[index]) + 6
            centre = radii[index] * unit_px - (width / 2 if index < len(labels) - 1 else width)
            if centre + width > right:
                labels[index] = ""
            else:
                right = centre
        for index, (ring, text) in enumerate(self.rings):
            if index < len(scale.ticks):
                r = radii[index]
                ring.setData(r * np.sin(angle), r * np.cos(angle))
                text.setText(labels[index])
                text.setPos(r, 0.0)
                # The rim's label ends at the rim, so that it stays inside the view.
                text.setAnchor((1.0, 0.0) if index == len(scale.ticks) - 1 else (0.5, 0.0))
            else:
                ring.setData(np.sin(angle), np.cos(angle))  # the rim
                text.setText("")

    settings_used = ("theta_i", "phi_i", "polar_cos", "polar_log")

    def own_inputs(self) -> tuple:
        # The plot's size and font: which ring labels fit.
        return (self.plot.width(), self.plot.height(), self.font().pointSizeF())

    def draw(self, fast: bool) -> bool:
        s = self.lab.settings
        theta_i, phi_i, cos = s["theta_i"], s["phi_i"], s["polar_cos"]
        self.data = []
        for state in self.lab.visible_models():
            key = state_key(state, theta_i, phi_i, cos)
            polar = self.cached(
                state,
                key,
                lambda st=state: self.renderer.polar(
                    st.model, st.values, theta_i, phi_i, cos_weighted=cos
                ),
            )
            if polar is not None:
                self.data.append((state, polar))
        lum = [(st, p, p.values.astype(np.float64) @ LUMA) for st, p in self.data]
        spikes = tuple(float(np.asarray(p.spike) @ LUMA) for _, p, _ in lum if p.spike is not None)
        theta_o = lum[0][1].theta_o if lum else np.zeros(1)
        scale = plotscale.polar_scale(
            theta_o, [v for _, _, v in lum], spikes, log=s["polar_log"], decades=self.DECADES
        )
        self.scale = scale
        self.fit_range()
        self.draw_rings(scale)
        ti = math.radians(theta_i)
        if self.marked != theta_i:  # the marks move with the light only
            self.marked = theta_i
            for (line, text), a in zip(self.marks, (0.0, ti, -ti), strict=True):
                line.setData([0, 1.05 * math.sin(a)], [0, 1.05 * math.cos(a)])
                text.setPos(1.1 * math.sin(a), 1.1 * math.cos(a))
        self.place_marks(theta_i)  # every draw: the room for them changes with size and font
        while len(self.curves) < len(lum):
            self.curves.append((self.plot.plot(), self.plot.plot()))
        clipped_x: list[float] = []
        clipped_y: list[float] = []
        for index, (curve, spike) in enumerate(self.curves):
            if index >= len(lum):
                if curve.xData is not None and len(curve.xData):
                    curve.setData([], [])
                    spike.setData([], [])
                continue
            state, polar, values = lum[index]
            r = scale.radius(values)
            a = np.radians(polar.theta_o)
            curve.setData(-r * np.sin(a), r * np.cos(a), pen=pen(state.color))
            over = np.nan_to_num(values, nan=0.0) > scale.top * (1 + 1e-6)
            clipped_x += list(-np.sin(a[over]))
            clipped_y += list(np.cos(a[over]))
            if polar.spike is not None:
                h = float(scale.radius([float(np.asarray(polar.spike) @ LUMA)])[0])
                spike.setData(
                    [0, -h * math.sin(ti)], [0, h * math.cos(ti)], pen=pen(state.color, 4)
                )
            elif spike.xData is not None and len(spike.xData):
                spike.setData([], [])
        self.clip_marks.setData(clipped_x, clipped_y)
        self.draw_legend(lum, scale)
        self.describe(lum, theta_i, cos)
        return False

    def describe(self, lum, theta_i: float, cos: bool) -> None:
        """The plot in words for screen readers (lab/describe.py, as the web page says it)."""
        lobes = []
        for st, p, v in lum:
            spike = None if p.spike is None else float(np.asarray(p.spike) @ LUMA)
            lobes.append(describe.Lobe(st.label, p.theta_o, v, spike))
        what = "f_r cos θo" if cos else "f_r"
        text = describe.describe(lobes, theta_i, what) if lobes else "no model is visible"
        self.plot.setAccessibleName("polar plot of the visible models")
        self.plot.setAccessibleDescription(text)

    def fit_range(self) -> None:
        """The half disc and room for a line of text above the rim (the direction labels)
        and below the baseline (the ring values), in pixels: large fonts are never cut."""
        text = QFontMetrics(self.marks[0][1].textItem.font()).height() + 2
        height, width = max(self.plot.height(), 40), max(self.plot.width(), 40)
        unit = max(min((height - 2 * text) / 1.2, width / 2.3), 4.0)  # pixels per unit
        self.plot.setRange(
            xRange=(-1.15, 1.15), yRange=(-0.02 - text / unit, 1.12 + text / unit), padding=0
        )

    def place_marks(self, theta_i: float) -> None:
        """Direction labels that never sit on each other: one label when they coincide; the
        light's grows to the right and the mirror's to the left while the lines are steep,
        inward once they are flat (past 50 degrees), so all stay inside the view."""
        normal, incident, mirror = (text for _, text in self.marks)
        normal.setVisible(True)
        merged = theta_i < 8
        for text in (incident, mirror):
            text.setVisible(not merged)
        steep = theta_i < 50
        # The words, or where they would run into each other (large text in a small plot)
        # the letters N, L, R, which the legend then explains.
        for words in (("normal", "incident", "mirror"), ("N", "L", "R")):
            normal.setText(" = ".join(words) if theta_i == 0 else words[0])
            incident.setText(words[1])
            mirror.setText(words[2])
            self.anchor_inside(normal, 0.5)
            self.anchor_inside(incident, 0.0 if steep else 1.0)
            self.anchor_inside(mirror, 1.0 if steep else 0.0)
            shown = [t for t in (normal, incident, mirror) if t.isVisible()]
            boxes = [glyph_box(t) for t in shown]
            if not any(a.intersects(b) for i, a in enumerate(boxes) for b in boxes[i + 1 :]):
                break
        else:  # letters collide too (a small plot, projector text): the normal's goes
            normal.setVisible(theta_i == 0)
        self.short_marks = words[0] == "N"

    def anchor_inside(self, text: pg.TextItem, preferred: float) -> None:
        """Anchors `text` at `preferred` (0: it starts at its point, 1: it ends there), or
        as near to that as keeps the whole text inside the view's width (a large font in a
        narrow view would otherwise cut it off at the edge)."""
        # The text's box in pixels (its margins included), in the view's units.
        width = text.textItem.boundingRect().width() * self.plot.getViewBox().viewPixelSize()[0]
        (left, right), x = self.plot.getViewBox().viewRange()[0], text.pos().x()
        anchor = preferred
        if 0 < width < right - left:
            anchor = min(max(preferred, (x + width - right) / width), (x - left) / width)
        text.setAnchor((anchor, 1.0))

    def draw_legend(self, lum: list, scale: plotscale.Scale) -> None:
        """Which colour is which model, the quantity and its unit, and what was clipped."""
        quantity = "f_r · cos θo" if self.lab.settings["polar_cos"] else "f_r"
        log = ", log scale" if scale.log else ""
        rows = [f"{quantity} in {plotscale.UNIT} (luminance){log}; light on the right"]
        if self.short_marks:
            rows[0] += "; N normal, L toward the light, R mirror direction"
        for state, polar, _ in lum:
            extra = ""
            if polar.spike is not None:
                extra = f" + delta spike {float(np.asarray(polar.spike) @ LUMA):.3g}"
            colour = QColor(state.color).name()
            # The colour's dash and the name on one line (a narrow legend breaks elsewhere).
            rows.append(
                f"<span style='color:{colour}'>━━</span>&nbsp;{html.escape(state.label)}{extra}"
            )
        if scale.clipped:
            note = html.escape(scale.note()).replace("\n", " ")
            rows.append(f"<span style='color:#dc283c'>▼</span> {note}")
        self.legend.setText("<br>".join(rows))

    def curve(self, state: ModelState) -> tuple[np.ndarray, np.ndarray] | None:
        """(theta_o, luminance of the plotted quantity) of one model's lobe."""
        for st, polar in self.data:
            if st is state:
                return polar.theta_o, polar.values.astype(np.float64) @ LUMA
        return None

    def file_actions(self) -> list[tuple[str, Callable[[], None]]]:
        return [("Export polar data as CSV…", self._ask_csv)]

    def _ask_csv(self) -> None:
        from PyQt6.QtWidgets import QFileDialog

        path, _ = QFileDialog.getSaveFileName(self, "Save polar data", "polar.csv", "CSV (*.csv)")
        if path:
            self.export_csv(path)

    def export_csv(self, path: str | Path) -> None:
        """theta_o and f_r (r, g, b) of every plotted model, one column set per model."""
        self.up_to_date()
        with open(path, "w", newline="", encoding="utf-8") as handle:
            writer = csv.writer(handle)
            quantity = "fr_cos" if self.lab.settings["polar_cos"] else "fr"
            header = ["theta_o_deg"]
            for state, _ in self.data:
                header += [f"{state.label}:{quantity}_{c}" for c in "rgb"]
            writer.writerow(header)
            if not self.data:
                return
            theta = self.data[0][1].theta_o
            for row, t in enumerate(theta):
                cells = [f"{t:g}"]
                for _, polar in self.data:
                    cells += [repr(float(v)) for v in polar.values[row]]
                writer.writerow(cells)

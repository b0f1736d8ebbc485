"""The views. Each reads the LabState, asks the GLSL (through the renderer) for data and
draws it; `redraw(fast)` returns True when a slower, finer pass would look better.

Results are cached per model, so moving one model's slider recomputes only that model.
"""

from __future__ import annotations

import csv
import html
import math
from functools import lru_cache
from pathlib import Path

import numpy as np
import pyqtgraph as pg
from PyQt6.QtCore import QPointF, QRect, Qt
from PyQt6.QtGui import QColor, QFont, QFontMetrics, QImage, QPainter, QPen
from PyQt6.QtWidgets import (
    QBoxLayout,
    QCheckBox,
    QComboBox,
    QHBoxLayout,
    QLabel,
    QPushButton,
    QVBoxLayout,
    QWidget,
)

from lab import constants, plotscale
from lab.app.renderer import MODES, SHAPES, AppRenderer
from lab.app.state import LabState, ModelState
from lab.app.widgets import LiveText, SettingCheck, SettingCombo, SettingSlider
from lab.glsl import ShaderCompileError
from lab.models import ModelError
from lab.nonfinite import sphere_report
from lab.render import (
    LOBE_FAST_GRID,
    LOBE_GRID,
    LOBE_MARK_RGB,
    Light,
    LobeCamera,
    direction,
)

LUMA = np.array(constants.LUMA)
QWIDGETSIZE_MAX = (1 << 24) - 1
BACKGROUND = (40, 40, 44)
_BACKGROUND_BGR = np.array(BACKGROUND[::-1], np.float32) / 255.0


def tonemap(image: np.ndarray, exposure: float, gamma: float) -> QImage:
    """Float RGB(A) -> QImage: 2^exposure, clamp, 1/gamma, background where alpha is 0.

    Float32 in place throughout (it runs for every image of every frame), built in the
    BGRA byte order of a 32-bit RGB QImage, which the raster engine draws unconverted.
    """
    bgr = image[..., 2::-1] * np.float32(2.0**exposure)
    np.fmax(bgr, np.float32(0.0), out=bgr)  # fmax also turns NaN into 0
    np.fmin(bgr, np.float32(1.0), out=bgr)
    np.power(bgr, np.float32(1.0 / max(gamma, 0.1)), out=bgr)
    if image.shape[-1] == 4:  # (c - bg) * alpha + bg
        bgr -= _BACKGROUND_BGR
        bgr *= image[..., 3:4]
        bgr += _BACKGROUND_BGR
    bgr *= np.float32(255.0)
    bgr += np.float32(0.5)
    height, width = bgr.shape[:2]
    data = np.full((height, width, 4), 255, np.uint8)
    data[..., :3] = bgr
    return QImage(data.data, width, height, 4 * width, QImage.Format.Format_RGB32).copy()


def finite_max(values: np.ndarray) -> float:
    finite = values[np.isfinite(values)]
    return float(finite.max()) if finite.size else 0.0


def state_key(state: ModelState, *extra) -> tuple:
    return (state.model.code, str(state.model.path), tuple(sorted(state.values.items())), *extra)


def look_key(state: ModelState) -> tuple:
    """What a view shows of a model besides its values: identity, label and colour."""
    return (id(state), state_key(state), state.label, state.color)


@lru_cache(maxsize=64)
def pen(color, width: float = 2.0, style: Qt.PenStyle = Qt.PenStyle.SolidLine) -> QPen:
    """Pens made once per colour (pyqtgraph copies them)."""
    made = pg.mkPen(color, width=width, style=style)
    made.setCosmetic(True)
    return made


def opaque(widget: QWidget) -> QWidget:
    """A widget that paints every pixel: Qt need not paint its parents below it first."""
    widget.setAttribute(Qt.WidgetAttribute.WA_OpaquePaintEvent, True)
    return widget


class View(QWidget):
    """Base: a tool row above the content, a per-model cache and PNG export.

    `redraw(fast)` does nothing when the view's `inputs()` are those it last drew (a light
    change leaves the slice alone, a model's change leaves views of other models alone).
    Subclasses implement `inputs()` and `draw(fast) -> needs a finer pass`.
    """

    title = "view"
    name = "view"

    def __init__(self, lab: LabState, renderer: AppRenderer):
        super().__init__()
        self.lab, self.renderer = lab, renderer
        self.cache: dict[int, tuple[tuple, object]] = {}
        self.toned: dict[int, tuple] = {}  # (image, (exposure, gamma), QImage): tone-map once
        self.layout_ = QVBoxLayout(self)
        self.layout_.setContentsMargins(2, 2, 2, 2)
        self.tools = QHBoxLayout()
        self.layout_.addLayout(self.tools)
        self.errors: list[str] = []
        self.drawn: tuple | None = None  # the inputs of the last draw
        self.coarse = False  # the last draw asked for a finer pass
        self.draws = 0  # how many times the view really drew (tests count them)
        self.budget = 0  # full-quality computations left in this refinement step

    def is_shown(self) -> bool:
        return self.isVisible() and not self.visibleRegion().isEmpty()

    def inputs(self) -> tuple:
        """Everything the view's picture depends on."""
        raise NotImplementedError

    def draw(self, fast: bool) -> bool:
        raise NotImplementedError

    def redraw(self, fast: bool = False) -> bool:
        """Draw if the inputs changed (or a finer pass is due); True: refine me later."""
        inputs = self.inputs()
        if inputs == self.drawn and (fast or not self.coarse):
            return self.coarse
        # One full-quality computation per refinement step: a step never holds input back.
        self.budget = 0 if fast else 1
        self.coarse = bool(self.draw(fast))
        self.drawn = inputs
        self.draws += 1
        return self.coarse

    def invalidate(self) -> None:
        self.drawn = None

    def plot_items(self) -> list[pg.PlotItem]:
        """The pyqtgraph plots in the view (their fonts follow presenter mode)."""
        items = []
        for widget in self.findChildren(pg.GraphicsView):
            items += [item for item in widget.items() if isinstance(item, pg.PlotItem)]
        return items

    def apply_font(self, font: QFont) -> None:
        """Presenter mode: pyqtgraph draws its text with its own fonts; give them ours."""
        small = QFont(font)
        small.setPointSizeF(font.pointSizeF() * 0.9)
        for plot in self.plot_items():
            for name in ("left", "bottom"):
                axis = plot.getAxis(name)
                axis.setStyle(tickFont=small)
                axis.label.setFont(small)
                axis.setLabel(axis.labelText, axis.labelUnits)
                if name == "left" and axis.fixedWidth is not None:
                    axis.setWidth(QFontMetrics(small).horizontalAdvance("0.00") * 2 + 8)
        for item in self.findChildren(QWidget):
            item.update()
        for text in getattr(self, "texts", []):
            text.setFont(small)
        self.invalidate()

    def resizeEvent(self, event) -> None:
        super().resizeEvent(event)
        request = getattr(self.window(), "request", None)
        if request is not None:
            request()  # views drawn at their size on screen check their inputs again

    def toned_image(self, state: ModelState, image: np.ndarray, tone: tuple) -> QImage:
        """`image` tone-mapped for display, computed again only when it or the tone changes."""
        known = self.toned.get(id(state))
        if known is None or known[0] is not image or known[1] != tone:
            known = (image, tone, tonemap(image, *tone))
            self.toned[id(state)] = known
        return known[2]

    def cached(self, state: ModelState, key: tuple, compute):
        """compute() unless the model's inputs are the same as last time."""
        hit = self.cache.get(id(state))
        if hit is not None and hit[0] == key:
            return hit[1]
        try:
            value = compute()
        except (ShaderCompileError, ModelError) as err:
            state.error = state.error or str(err)
            value = None
        self.cache[id(state)] = (key, value)
        return value

    def best(
        self, state: ModelState, fast: bool, fast_key: tuple, full_key: tuple, compute
    ) -> tuple[object, bool]:
        """(result, coarse): the full-quality result when at hand or within this step's
        budget, else the interactive one. `compute(full)` makes either."""
        hit = self.cache.get(id(state))
        if hit is not None and hit[0] == full_key:
            return hit[1], False
        if not fast and self.budget > 0 or fast_key == full_key:
            self.budget -= not fast
            return self.cached(state, full_key, lambda: compute(True)), False
        return self.cached(state, fast_key, lambda: compute(False)), True

    def climb(
        self, state: ModelState, fast: bool, key: tuple, sizes: list[int], compute
    ) -> tuple[object, bool]:
        """(result, coarse) for resolutions `sizes` (ascending): while sliding the smallest
        (or whatever is at hand), then one size up per refinement step, so no single
        step is long. `compute(size)` makes one."""
        hit = self.cache.get(id(state))
        have = hit[0][-1] if hit is not None and hit[0][:-1] == key else None
        if have in sizes and (fast or have == sizes[-1]):
            return hit[1], have != sizes[-1]
        size = sizes[0] if fast or have not in sizes else sizes[sizes.index(have) + 1]
        return self.cached(state, (*key, size), lambda: compute(size)), size != sizes[-1]

    def up_to_date(self) -> None:
        """Draw at full quality now: a hidden view is not redrawn, and exports must not
        save what it showed before the last change."""
        for _ in range(8):  # the refinement steps of the finest view
            if not self.redraw(fast=False):
                break

    def export_png(self, path: str | Path) -> None:
        self.up_to_date()
        self.grab().save(str(path))


class ImageRow(QWidget):
    """Images side by side, each with a coloured caption; emits drags as unit-disc points.

    An image as large as its cell is drawn at its own size (no scaling); a coarse one
    (while a slider moves) is scaled up without smoothing.
    """

    CAPTION = 20

    def __init__(self, on_drag=None):
        super().__init__()
        self.images: list[tuple[QImage, str, str]] = []
        self.on_drag = on_drag
        self.setMinimumSize(160, 120)
        opaque(self)

    def caption_height(self) -> int:
        """Lines enough for every caption across its column (captions wrap, never elide,
        never run into the next one): up to three."""
        metrics = self.fontMetrics()
        column = self.width() // max(len(self.images), 1)
        widths = [metrics.horizontalAdvance(c) + 8 for _, c, _ in self.images]
        lines = min(max([math.ceil(w / max(column, 1)) for w in widths] + [1]), 3)
        return max(self.CAPTION, metrics.height() * lines + 4)

    def cell(self) -> tuple[int, int]:
        n = max(len(self.images), 1)
        side = max(min(self.width() // n, self.height() - self.caption_height()), 16)
        return n, side

    def image_left(self, index: int) -> int:
        """Each image centred in its own column, so a caption may use the column's width."""
        n, side = self.cell()
        column = self.width() // n
        return index * column + (column - side) // 2

    def paintEvent(self, event) -> None:
        painter = QPainter(self)
        painter.fillRect(self.rect(), QColor(*BACKGROUND))
        n, side = self.cell()
        column = self.width() // n
        for index, (image, caption, color) in enumerate(self.images):
            left = self.image_left(index)
            if image.width() == side and image.height() == side:
                painter.drawImage(left, 0, image)
            else:
                painter.drawImage(QRect(left, 0, side, side), image)
            painter.setPen(QColor(color))
            painter.drawText(
                QRect(index * column + 4, side, column - 8, self.caption_height()),
                Qt.AlignmentFlag.AlignHCenter
                | Qt.AlignmentFlag.AlignTop
                | Qt.TextFlag.TextWordWrap,
                caption,
            )
        painter.end()

    def _drag(self, event) -> None:
        if self.on_drag is None or not self.images:
            return
        n, side = self.cell()
        x = event.position().x()
        index = min(max(int(x // max(self.width() // n, 1)), 0), n - 1)
        px, py = x - self.image_left(index), event.position().y()
        self.on_drag(2.0 * px / side - 1.0, 1.0 - 2.0 * py / side)

    def mousePressEvent(self, event) -> None:
        self._drag(event)

    def mouseMoveEvent(self, event) -> None:
        if event.buttons():
            self._drag(event)


class SphereView(View):
    """A lit sphere per visible model; drag on a sphere to move the light there."""

    title = "Lit spheres"
    name = "sphere"
    FAST_SIZE = 192

    def __init__(self, lab, renderer):
        super().__init__(lab, renderer)
        s = lab.settings
        self.tools.addWidget(SettingSlider.of(s, "exposure"), 2)
        self.tools.addWidget(SettingSlider.of(s, "gamma"), 1)
        self.tools.addWidget(SettingCheck(s, "multiply_cos", "× N·L"))
        # NaN or Inf pixels show as black: a banner says how many and where.
        self.banner = QLabel()
        self.banner.setWordWrap(True)
        self.banner.setStyleSheet("background:#8b1a1a; color:white; padding:4px;")
        self.banner.hide()
        self.layout_.addWidget(self.banner)
        self.canvas = ImageRow(self.drag_light)
        self.layout_.addWidget(self.canvas, 1)
        self.floats: list[tuple[ModelState, np.ndarray]] = []

    def drag_light(self, x: float, y: float) -> None:
        r = math.hypot(x, y)
        if r > 1.0:
            x, y, r = x / r, y / r, 1.0
        theta = math.degrees(math.asin(min(r, 1.0)))
        phi = math.degrees(math.atan2(y, x)) % 360.0
        self.lab.settings.set("theta_i", round(theta * 2) / 2)
        self.lab.settings.set("phi_i", round(phi * 2) / 2)

    def side(self) -> int:
        """The spheres' size on screen: they are rendered at exactly that size."""
        n = max(len(self.lab.visible_models()), 1)
        side = max(
            min(self.canvas.width() // n, self.canvas.height() - self.canvas.caption_height()), 32
        )
        return min(side, 512)

    def inputs(self) -> tuple:
        s = self.lab.settings
        return (
            tuple(look_key(m) for m in self.lab.visible_models()),
            s["theta_i"],
            s["phi_i"],
            s["multiply_cos"],
            s["exposure"],
            s["gamma"],
            self.side(),
        )

    def draw(self, fast: bool) -> bool:
        s = self.lab.settings
        full = self.side()
        small = min(full, self.FAST_SIZE)
        light = (s["theta_i"], s["phi_i"])
        self.floats, images = [], []
        coarse = False
        tone = (s["exposure"], s["gamma"])
        for state in self.lab.visible_models():
            image, rough = self.best(
                state,
                fast,
                (light, small, s["multiply_cos"], state_key(state)),
                (light, full, s["multiply_cos"], state_key(state)),
                lambda use_full, st=state: self.renderer.sphere(
                    st.model,
                    st.values,
                    light,
                    size=full if use_full else small,
                    multiply_cos=s["multiply_cos"],
                ),
            )
            coarse = coarse or rough
            if image is None:
                continue
            self.floats.append((state, image))
            images.append((self.toned_image(state, image, tone), state.label, state.color))
        self.canvas.images = images
        self.canvas.update()
        self.show_nonfinite(direction(*light))
        return coarse

    def show_nonfinite(self, light: np.ndarray) -> None:
        """The banner: each model whose sphere has NaN or Inf pixels, with share and place."""
        reports = [(st.label, sphere_report(image, light)) for st, image in self.floats]
        lines = [f"⚠ {label}: {text}" for label, text in reports if text]
        self.banner.setText("\n".join(lines))
        self.banner.setVisible(bool(lines))


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
        self.legend.setWordWrap(True)
        self.legend.setTextFormat(Qt.TextFormat.RichText)
        self.legend.setAlignment(Qt.AlignmentFlag.AlignLeft | Qt.AlignmentFlag.AlignVCenter)
        self.body.addWidget(self.legend)
        self.scale: plotscale.Scale | None = None
        self.marked: float | None = None
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

    def inputs(self) -> tuple:
        s = self.lab.settings
        return (
            tuple(look_key(m) for m in self.lab.visible_models()),
            s["theta_i"],
            s["phi_i"],
            s["polar_cos"],
            s["polar_log"],
            self.plot.width(),  # which ring labels fit
            self.plot.height(),
            self.font().pointSizeF(),
        )

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
        self.draw_rings(scale)
        ti = math.radians(theta_i)
        if self.marked != theta_i:  # the marks move with the light only
            self.marked = theta_i
            for (line, text), a in zip(self.marks, (0.0, ti, -ti), strict=True):
                line.setData([0, 1.05 * math.sin(a)], [0, 1.05 * math.cos(a)])
                text.setPos(1.1 * math.sin(a), 1.1 * math.cos(a))
            self.place_marks(theta_i)
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
        return False

    def place_marks(self, theta_i: float) -> None:
        """Direction labels that never sit on each other: one label when they coincide; the
        light's grows to the right and the mirror's to the left while the lines are steep,
        inward once they are flat (past 50 degrees), so all stay inside the view."""
        normal, incident, mirror = (text for _, text in self.marks)
        merged = theta_i < 8
        normal.setText("normal = incident = mirror" if theta_i == 0 else "normal")
        for text in (incident, mirror):
            text.setVisible(not merged)
        steep = theta_i < 50
        incident.setAnchor((0.0, 1.0) if steep else (1.0, 1.0))
        mirror.setAnchor((1.0, 1.0) if steep else (0.0, 1.0))

    def draw_legend(self, lum: list, scale: plotscale.Scale) -> None:
        """Which colour is which model, the quantity and its unit, and what was clipped."""
        quantity = "f_r · cos θo" if self.lab.settings["polar_cos"] else "f_r"
        log = ", log scale" if scale.log else ""
        rows = [f"{quantity} in {plotscale.UNIT} (luminance){log}; light on the right"]
        for state, polar, _ in lum:
            extra = ""
            if polar.spike is not None:
                extra = f" + delta spike {float(np.asarray(polar.spike) @ LUMA):.3g}"
            colour = QColor(state.color).name()
            rows.append(f"<span style='color:{colour}'>━━</span> {html.escape(state.label)}{extra}")
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


class LobeCanvas(QWidget):
    """The lobe image drawn by the models' GLSL, with the marks' names; drag rotates, the
    wheel zooms."""

    def __init__(self, view: LobeView):
        super().__init__()
        self.view = view
        self.image: QImage | None = None
        self.labels: list[tuple[QPointF, str, tuple]] = []
        self.last = None
        self.setMinimumSize(160, 160)
        opaque(self)

    def paintEvent(self, event) -> None:
        painter = QPainter(self)
        image = self.image
        if image is None:
            painter.fillRect(self.rect(), QColor(*BACKGROUND))
        elif image.width() == self.width() and image.height() == self.height():
            painter.drawImage(0, 0, image)
        else:  # a coarse image while sliding, or the widget was just resized
            painter.drawImage(self.rect(), image)
        for point, text, color in self.labels:
            painter.setPen(QColor(*color))
            painter.drawText(point, text)
        painter.end()

    def mousePressEvent(self, event) -> None:
        self.last = event.position()

    def mouseReleaseEvent(self, event) -> None:
        self.last = None

    def mouseMoveEvent(self, event) -> None:
        if self.last is None:
            return
        delta = event.position() - self.last
        self.last = event.position()
        s = self.view.lab.settings
        s.set("lobe_yaw", s["lobe_yaw"] + delta.x() * 0.01)
        s.set("lobe_pitch", min(max(s["lobe_pitch"] + delta.y() * 0.01, -1.5), 1.5))

    def wheelEvent(self, event) -> None:
        s = self.view.lab.settings
        factor = 1.1 if event.angleDelta().y() > 0 else 1 / 1.1
        s.set("lobe_zoom", min(max(s["lobe_zoom"] * factor, 0.2), 8.0))


class LobeView(View):
    """The 3D lobe over the hemisphere, drawn on the GPU by each model's own GLSL (its BRDF
    in the vertex stage of shaders/views/lobe_mesh.glsl); f_r or f_r cos, linear or log,
    as the polar plot. All visible models in one picture, each in its colour."""

    title = "3D lobe"
    name = "lobe3d"
    # llvmpipe sets triangles up on one core: the full grid shares a triangle budget among
    # the models (the mirror direction is a grid vertex, so sharp lobes keep their tips).
    TRIANGLES = 20000
    GRIDS = [(61, 121), (49, 97), (41, 81), (33, 65), (25, 49)]
    MAX_SIDE = 1024
    MARKS = (("N", "normal"), ("L", "incident"), ("R", "mirror"))

    def __init__(self, lab, renderer):
        super().__init__(lab, renderer)
        s = lab.settings
        self.tools.addWidget(SettingCheck(s, "polar_log", "log scale"))
        self.tools.addWidget(SettingCheck(s, "polar_cos", "f_r · cos θo"))
        self.wire = QCheckBox("wire")
        self.wire.setToolTip("grid lines only: overlapping lobes show through each other")
        self.wire.toggled.connect(lambda _: self.window().request())
        self.tools.addWidget(self.wire)
        hint = LiveText("drag: rotate, wheel: zoom")
        self.tools.addWidget(hint, 1)
        self.canvas = LobeCanvas(self)
        for widget in (hint, self.canvas):
            widget.setToolTip("drag to rotate the lobe, turn the wheel to zoom")
        self.layout_.addWidget(self.canvas, 1)
        self.data: list[tuple[ModelState, tuple[float, float]]] = []
        self.image: np.ndarray | None = None  # the last picture, RGBA bytes

    def size_(self) -> tuple[int, int]:
        return (
            min(max(self.canvas.width(), 16), self.MAX_SIDE),
            min(max(self.canvas.height(), 16), self.MAX_SIDE),
        )

    def camera(self) -> LobeCamera:
        s = self.lab.settings
        return LobeCamera(s["lobe_yaw"], s["lobe_pitch"], s["lobe_zoom"])

    def full_grid(self, count: int) -> tuple[int, int]:
        return next(
            (
                g
                for g in self.GRIDS
                if (g[0] - 1) * (g[1] - 1) * 2 * max(count, 1) <= self.TRIANGLES
            ),
            self.GRIDS[-1],
        )

    def inputs(self) -> tuple:
        s = self.lab.settings
        return (
            tuple(look_key(m) for m in self.lab.visible_models()),
            s["theta_i"],
            s["phi_i"],
            s["polar_cos"],
            s["polar_log"],
            s["lobe_yaw"],
            s["lobe_pitch"],
            s["lobe_zoom"],
            self.wire.isChecked(),
            self.size_(),
        )

    def draw(self, fast: bool) -> bool:
        s = self.lab.settings
        theta_i, phi_i, cos = s["theta_i"], s["phi_i"], s["polar_cos"]
        self.data = []
        for state in self.lab.visible_models():
            # The scale comes from the finest grid, whatever grid draws: no jump on refining.
            key = state_key(state, theta_i, phi_i, cos)
            peak = self.cached(
                state,
                key,
                lambda st=state: self.renderer.lobe_peak(
                    st.model, st.values, theta_i, phi_i, cos, LOBE_GRID
                ),
            )
            if peak is not None:
                self.data.append((state, peak))
        full = self.full_grid(len(self.data))
        grid = LOBE_FAST_GRID if fast else full
        layers = [(st.model, st.values, QColor(st.color).getRgbF()[:3]) for st, _ in self.data]
        size, camera = self.size_(), self.camera()
        try:
            image = self.renderer.lobe_mesh(
                layers,
                theta_i,
                phi_i,
                size,
                camera,
                cos,
                s["polar_log"],
                grid,
                "wire" if self.wire.isChecked() else "solid",
                peaks=[p for _, p in self.data],
                background=(*(np.array(BACKGROUND) / 255.0), 1.0),
                dtype="u1",
            )
        except (ShaderCompileError, ModelError) as err:  # lobe_peak compiled them already
            for state, _ in self.data:
                state.error = state.error or str(err)
            image = None
        self.image = image
        if image is not None:
            self.canvas.image = QImage(
                image.data, size[0], size[1], 4 * size[0], QImage.Format.Format_RGBA8888
            ).copy()
        ends = [direction(0.0, 0.0), direction(theta_i, phi_i), direction(theta_i, phi_i + 180.0)]
        points = camera.project(1.2 * np.array(ends), size)
        sx, sy = self.canvas.width() / size[0], self.canvas.height() / size[1]
        half = self.canvas.fontMetrics().height() / 3
        self.canvas.labels = [
            (
                QPointF(x * sx - half, y * sy + half),
                letter,
                tuple(round(255 * c) for c in LOBE_MARK_RGB[name]),
            )
            for (x, y), (letter, name) in zip(points, self.MARKS, strict=True)
        ]
        self.canvas.update()
        return grid != full


class SliceCanvas(QWidget):
    """One square image per model over theta_h (x) and theta_d (y), both axes 0..90 deg.

    Drawn by hand so the axes can never drift or stretch: every plot is a square at the
    same scale, whatever the widget's shape.
    """

    def __init__(self):
        super().__init__()
        self.images: list[tuple[QImage, str, str]] = []
        self.setMinimumSize(160, 120)
        opaque(self)

    def axis_font(self) -> QFont:
        """Tick and axis labels a little smaller than the titles (presenter fonts too)."""
        font = QFont(self.font())
        font.setPointSizeF(max(self.font().pointSizeF() * 0.85, 6.0))
        return font

    def margins(self) -> tuple[int, int, int, int]:
        """Left, top, right and bottom room around each plot for titles, ticks, labels."""
        fm = QFontMetrics(self.axis_font())
        line = fm.height()
        title = QFontMetrics(self.font()).height()
        return (fm.horizontalAdvance("90°") + line + 10, title + 4, 12, 2 * line + 6)

    def plot_rects(self, count: int | None = None) -> list[QRect]:
        """Where each image goes: squares of one size in the grid (columns x rows) that
        makes them largest, centred."""
        n = max(count if count is not None else len(self.images), 1)
        left, top, right, bottom = self.margins()
        best = (0, 1, 1)
        for cols in range(1, n + 1):
            rows = -(-n // cols)
            side = min(self.width() // cols - left - right, self.height() // rows - top - bottom)
            if side > best[0]:
                best = (side, cols, rows)
        side, cols, rows = best
        side = max(side, 16)
        cell_w, cell_h = left + side + right, top + side + bottom
        x0 = (self.width() - cols * cell_w) // 2
        y0 = (self.height() - rows * cell_h) // 2
        return [
            QRect(x0 + (i % cols) * cell_w + left, y0 + (i // cols) * cell_h + top, side, side)
            for i in range(n)
        ]

    def paintEvent(self, event) -> None:
        painter = QPainter(self)
        painter.fillRect(self.rect(), QColor(*BACKGROUND))
        title_metrics = QFontMetrics(self.font())
        font = self.axis_font()
        fm = QFontMetrics(font)
        line = fm.height()
        axis = QColor(170, 170, 170)
        for rect, (image, caption, color) in zip(self.plot_rects(), self.images, strict=False):
            if image.width() == rect.width() and image.height() == rect.height():
                painter.drawImage(rect.topLeft(), image)
            else:
                painter.drawImage(rect, image)
            painter.setFont(self.font())
            painter.setPen(QColor(color))
            room = rect.width() + 40
            painter.drawText(
                QRect(
                    rect.left() - 20,
                    rect.top() - title_metrics.height() - 3,
                    room,
                    title_metrics.height() + 2,
                ),
                Qt.AlignmentFlag.AlignCenter,
                title_metrics.elidedText(caption, Qt.TextElideMode.ElideRight, room),
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
        painter.end()


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

    def inputs(self) -> tuple:
        s = self.lab.settings
        return (
            tuple(look_key(m) for m in self.lab.visible_models()),
            s["phi_d"],
            s["exposure"],
            s["gamma"],
            self.side(),
        )

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
            images.append((self.toned_image(state, image, tone), state.label, state.color))
        self.canvas.images = images
        self.canvas.update()
        return coarse


class AlbedoView(View):
    """Directional albedo vs theta_i; values above the albedo = 1 line are energy gain."""

    title = "Directional albedo"
    name = "albedo"
    NOTE = "albedo = ∫ f_r cos θo dω (largest colour channel)"
    FAST = (np.linspace(0, 85, 9), 32, 16)
    FULL = (np.arange(0, 90, 2.5), 192, 48)

    def __init__(self, lab, renderer):
        super().__init__(lab, renderer)
        self.note = LiveText(self.NOTE)
        self.tools.addWidget(self.note, 1)
        self.plot = pg.PlotWidget()
        opaque(self.plot.viewport())
        self.plot.setLabel("bottom", "θi (deg)")
        self.plot.setLabel("left", "albedo")
        self.plot.getAxis("left").setWidth(52)  # fixed: new tick labels never relayout
        self.plot.setMouseEnabled(False, False)
        self.plot.hideButtons()
        self.layout_.addWidget(self.plot, 1)
        self.data: list[tuple[ModelState, np.ndarray, np.ndarray]] = []
        unit = pg.InfiniteLine(
            pos=1.0,
            angle=0,
            pen=pg.mkPen((220, 220, 220), style=Qt.PenStyle.DashLine),
            label="albedo = 1",
        )
        self.plot.addItem(unit)
        self.texts = [unit.label]
        self.curves: list[tuple[pg.PlotDataItem, pg.PlotDataItem]] = []
        self.top = 0.0
        self.set_top(1.0)

    def set_top(self, top: float, grow_only: bool = False) -> None:
        """The y range: the smallest of 1.1, 1.5, 2, 3, 5, 10, ... above the data. While a
        slider moves it only grows (new ticks cost more than the curves); it may shrink
        again when the slider stops."""
        wanted = next(
            t for t in (1.1, 1.5, 2.0, 3.0, 5.0, 10.0, 20.0, 50.0, math.inf) if t >= top * 1.05
        )
        if not math.isfinite(wanted):
            wanted = 10.0 ** math.ceil(math.log10(top * 1.05))
        if wanted > self.top or wanted < self.top and not grow_only:
            self.top = wanted
            self.plot.setRange(xRange=(0, 90), yRange=(0, wanted), padding=0.02)

    def inputs(self) -> tuple:
        # Albedo is integrated over every outgoing direction: it does not depend on theta_i.
        return (tuple(look_key(m) for m in self.lab.visible_models()), self.lab.settings["phi_i"])

    def draw(self, fast: bool) -> bool:
        phi_i = self.lab.settings["phi_i"]
        self.data = []
        coarse = False
        for state in self.lab.visible_models():
            key = state_key(state, phi_i)

            def compute(full: bool, st=state):
                thetas, samples, wedges = self.FULL if full else self.FAST
                return thetas, self.renderer.albedo(
                    st.model, st.values, thetas, phi_i, samples=samples, wedges=wedges
                )

            result, rough = self.best(state, fast, (*key, "fast"), (*key, "full"), compute)
            coarse = coarse or rough
            if result is not None:
                self.data.append((state, result[0], result[1].max(axis=1)))
        while len(self.curves) < len(self.data):
            gain_marks = self.plot.plot(
                pen=None, symbol="x", symbolBrush=None, symbolPen=pg.mkPen((255, 60, 60), width=2)
            )
            self.curves.append((self.plot.plot(), gain_marks))
        gain = []
        for index, (curve, marks) in enumerate(self.curves):
            if index >= len(self.data):
                curve.setData([], [])
                marks.setData([], [])
                continue
            state, thetas_, albedo = self.data[index]
            curve.setData(thetas_, albedo, pen=pen(state.color))
            over = albedo > 1.0 + 1e-3
            marks.setData(thetas_[over], albedo[over])
            if over.any():
                gain.append(state.label)
        self.set_top(max([finite_max(a) for _, _, a in self.data] + [1.0]), grow_only=fast)
        if gain:
            self.note.setText("energy gain (albedo > 1): " + ", ".join(gain), "#ff5050")
        else:
            self.note.setText(self.NOTE)
        return coarse


class ObjectView(View):
    """The selected model on a procedural object with several lights and ambient light."""

    title = "Lit object / spatially varying"
    name = "object"
    FAST_SIZE = 96
    FILL_LIGHTS = [
        Light(60.0, 200.0, (0.35, 0.4, 0.55)),
        Light(75.0, 100.0, (0.5, 0.4, 0.3)),
        Light(50.0, 300.0, (0.3, 0.3, 0.3)),
    ]

    def __init__(self, lab, renderer):
        super().__init__(lab, renderer)
        s = lab.settings
        for name, items in (("shape", SHAPES), ("mode", MODES)):
            combo = SettingCombo(s, name, items)
            # Long choices must not set the view's width: the menu shows them in full.
            combo.setSizeAdjustPolicy(
                QComboBox.SizeAdjustPolicy.AdjustToMinimumContentsLengthWithIcon
            )
            combo.setMinimumContentsLength(6)
            self.tools.addWidget(combo, 1)
        more = QHBoxLayout()  # a second row: the view stays narrow enough to share a row
        more.addWidget(SettingSlider.of(s, "lights"), 1)
        more.addWidget(SettingSlider.of(s, "ambient"), 1)
        self.layout_.addLayout(more)
        self.canvas = ImageRow(self.drag)
        self.layout_.addWidget(self.canvas, 1)
        self.image: np.ndarray | None = None
        self.start: tuple[float, float] | None = None

    def drag(self, x: float, y: float) -> None:
        s = self.lab.settings
        if self.start is not None:
            s.set("yaw", s["yaw"] + (x - self.start[0]) * 2.0)
            s.set("pitch", min(max(s["pitch"] - (y - self.start[1]) * 2.0, -1.5), 1.5))
        self.start = (x, y)

    def mouseReleaseEvent(self, event) -> None:
        self.start = None

    def subject(self) -> ModelState | None:
        visible = self.lab.visible_models()
        if self.lab.selected in visible:
            return self.lab.selected
        return visible[0] if visible else None

    def side(self) -> int:
        return max(
            min(self.canvas.width(), self.canvas.height() - self.canvas.caption_height(), 512), 32
        )

    def inputs(self) -> tuple:
        s = self.lab.settings
        state = self.subject()
        return (
            look_key(state) if state else None,
            self.side(),
            *(
                s[k]
                for k in (
                    "theta_i",
                    "phi_i",
                    "lights",
                    "ambient",
                    "shape",
                    "mode",
                    "yaw",
                    "pitch",
                    "exposure",
                    "gamma",
                )
            ),
        )

    def draw(self, fast: bool) -> bool:
        s = self.lab.settings
        state = self.subject()
        if state is None:
            self.canvas.images = []
            self.canvas.update()
            return False
        full = self.side()
        small = min(full, self.FAST_SIZE)
        lights = [Light(s["theta_i"], s["phi_i"])] + self.FILL_LIGHTS[: s["lights"] - 1]
        ambient = (s["ambient"],) * 3
        key = state_key(
            state,
            s["theta_i"],
            s["phi_i"],
            s["lights"],
            s["ambient"],
            s["shape"],
            s["mode"],
            s["yaw"],
            s["pitch"],
        )
        self.cache = {k: v for k, v in self.cache.items() if k == id(state)}
        # The object's full size costs several milliseconds: refine through a middle size.
        sizes = sorted({small, min(full, 2 * small), full})
        image, coarse = self.climb(
            state,
            fast,
            key,
            sizes,
            lambda size: self.renderer.object(
                state.model,
                state.values,
                lights,
                ambient,
                s["shape"],
                s["mode"],
                s["yaw"],
                s["pitch"],
                size,
            ),
        )
        self.image = image
        if image is not None:
            caption = f"{state.label}: {MODES[s['mode']]}"
            self.canvas.images = [(tonemap(image, s["exposure"], s["gamma"]), caption, state.color)]
        self.canvas.update()
        return coarse


VIEW_CLASSES = [SphereView, PolarView, LobeView, SliceView, AlbedoView, ObjectView]


def big_font(widget: QWidget, scale: float) -> None:
    font = QFont(widget.font())
    font.setPointSizeF(font.pointSizeF() * scale)
    widget.setFont(font)

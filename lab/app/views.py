"""The views. Each reads the LabState, asks the GLSL (through the renderer) for data and
draws it; `redraw(fast)` returns True when a slower, finer pass would look better.

Results are cached per model, so moving one model's slider recomputes only that model.
"""

from __future__ import annotations

import csv
import math
from pathlib import Path

import numpy as np
import pyqtgraph as pg
from PyQt6.QtCore import QPointF, QRectF, Qt
from PyQt6.QtGui import QColor, QFont, QImage, QPainter, QPen
from PyQt6.QtWidgets import QHBoxLayout, QLabel, QPushButton, QVBoxLayout, QWidget

from lab.app.renderer import MODES, SHAPES, AppRenderer
from lab.app.state import LabState, ModelState
from lab.app.widgets import SettingCheck, SettingCombo, SettingSlider
from lab.glsl import ShaderCompileError
from lab.models import ModelError
from lab.render import Light

LUMA = np.array([0.2126, 0.7152, 0.0722])
BACKGROUND = (40, 40, 44)


def tonemap(image: np.ndarray, exposure: float, gamma: float) -> QImage:
    """Float RGB(A) -> QImage: 2^exposure, clamp, 1/gamma, background where alpha is 0."""
    rgb = np.clip(np.nan_to_num(image[..., :3], nan=0.0) * (2.0 ** exposure), 0.0, 1.0)
    rgb = rgb ** (1.0 / max(gamma, 0.1))
    if image.shape[-1] == 4:
        alpha = image[..., 3:4]
        rgb = rgb * alpha + (np.array(BACKGROUND) / 255.0) * (1.0 - alpha)
    data = np.ascontiguousarray((rgb * 255.0 + 0.5).astype(np.uint8))
    height, width = data.shape[:2]
    return QImage(data.data, width, height, 3 * width, QImage.Format.Format_RGB888).copy()


def finite_max(values: np.ndarray) -> float:
    finite = values[np.isfinite(values)]
    return float(finite.max()) if finite.size else 0.0


def state_key(state: ModelState, *extra) -> tuple:
    return (state.model.code, str(state.model.path), tuple(sorted(state.values.items())), *extra)


class View(QWidget):
    """Base: a tool row above the content, a per-model cache and PNG export."""

    title = "view"
    name = "view"

    def __init__(self, lab: LabState, renderer: AppRenderer):
        super().__init__()
        self.lab, self.renderer = lab, renderer
        self.cache: dict[int, tuple[tuple, object]] = {}
        self.layout_ = QVBoxLayout(self)
        self.layout_.setContentsMargins(2, 2, 2, 2)
        self.tools = QHBoxLayout()
        self.layout_.addLayout(self.tools)
        self.errors: list[str] = []

    def is_shown(self) -> bool:
        return self.isVisible() and not self.visibleRegion().isEmpty()

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

    def redraw(self, fast: bool = False) -> bool:
        raise NotImplementedError

    def export_png(self, path: str | Path) -> None:
        self.grab().save(str(path))


class ImageRow(QWidget):
    """Images side by side, each with a coloured caption; emits drags as unit-disc points."""

    def __init__(self, on_drag=None):
        super().__init__()
        self.images: list[tuple[QImage, str, str]] = []
        self.on_drag = on_drag
        self.setMinimumSize(160, 120)

    def cell(self) -> tuple[int, int]:
        n = max(len(self.images), 1)
        side = max(min(self.width() // n, self.height() - 20), 16)
        return n, side

    def paintEvent(self, event) -> None:
        painter = QPainter(self)
        painter.fillRect(self.rect(), QColor(*BACKGROUND))
        n, side = self.cell()
        x0 = (self.width() - n * side) // 2
        for index, (image, caption, color) in enumerate(self.images):
            target = QRectF(x0 + index * side, 0, side, side)
            painter.drawImage(target, image)
            painter.setPen(QColor(color))
            painter.drawText(QRectF(target.left(), side, side, 20),
                             Qt.AlignmentFlag.AlignCenter, caption)
        painter.end()

    def _drag(self, event) -> None:
        if self.on_drag is None or not self.images:
            return
        n, side = self.cell()
        x0 = (self.width() - n * side) // 2
        px, py = event.position().x() - x0, event.position().y()
        px = px % side
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

    def __init__(self, lab, renderer):
        super().__init__(lab, renderer)
        s = lab.settings
        self.tools.addWidget(SettingSlider(s, "exposure", "exposure", -8.0, 8.0, 0.1), 2)
        self.tools.addWidget(SettingSlider(s, "gamma", "gamma", 1.0, 3.0, 0.1), 1)
        self.tools.addWidget(SettingCheck(s, "multiply_cos", "× N·L"))
        self.canvas = ImageRow(self.drag_light)
        self.layout_.addWidget(self.canvas, 1)
        self.floats: list[tuple[ModelState, np.ndarray]] = []
        self.toned: dict[int, tuple] = {}  # (image, (exposure, gamma), QImage): tone-map once

    def drag_light(self, x: float, y: float) -> None:
        r = math.hypot(x, y)
        if r > 1.0:
            x, y, r = x / r, y / r, 1.0
        theta = math.degrees(math.asin(min(r, 1.0)))
        phi = math.degrees(math.atan2(y, x)) % 360.0
        self.lab.settings.set("theta_i", round(theta * 2) / 2)
        self.lab.settings.set("phi_i", round(phi * 2) / 2)

    def size_for(self, fast: bool) -> int:
        n = max(len(self.lab.visible_models()), 1)
        side = max(min(self.canvas.width() // n, self.canvas.height() - 20), 32)
        side = min(side, 512)
        return min(side, 192) if fast else side

    def redraw(self, fast: bool = False) -> bool:
        s = self.lab.settings
        size = self.size_for(fast)
        light = (s["theta_i"], s["phi_i"])
        self.floats, images = [], []
        for state in self.lab.visible_models():
            key = state_key(state, light, size, s["multiply_cos"])
            image = self.cached(state, key, lambda st=state: self.renderer.sphere(
                st.model, st.values, light, size=size, multiply_cos=s["multiply_cos"]))
            if image is None:
                continue
            self.floats.append((state, image))
            known = self.toned.get(id(state))
            tone = (s["exposure"], s["gamma"])
            if known is None or known[0] is not image or known[1] != tone:
                known = (image, tone, tonemap(image, *tone))
                self.toned[id(state)] = known
            images.append((known[2], state.label, state.color))
        self.canvas.images = images
        self.canvas.update()
        return size < self.size_for(False)


class PolarView(View):
    """The lobe in the plane of incidence, with normal, incident and mirror directions."""

    title = "Polar plot"
    name = "polar"
    DECADES = 3.0

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
        self.plot.setAspectLocked(True)
        self.plot.hideAxis("left")
        self.plot.hideAxis("bottom")
        self.plot.setMouseEnabled(False, False)
        self.layout_.addWidget(self.plot, 1)
        self.data: list[tuple[ModelState, object]] = []
        # Fixed items are made once; curves are reused (re-creating items costs milliseconds).
        angle = np.radians(np.linspace(-90, 90, 91))
        grid = pg.mkPen((90, 90, 90), style=Qt.PenStyle.DotLine)
        for r in (0.25, 0.5, 0.75, 1.0):
            self.plot.plot(r * np.sin(angle), r * np.cos(angle), pen=grid)
        self.plot.plot([-1.05, 1.05], [0, 0], pen=pg.mkPen((150, 150, 150)))
        self.marks = []
        for label, color in (("normal", (200, 200, 200)), ("incident", (255, 210, 0)),
                             ("mirror", (120, 200, 255))):
            line = self.plot.plot(pen=pg.mkPen(color, width=1, style=Qt.PenStyle.DashLine))
            text = pg.TextItem(label, color=color, anchor=(0.5, 1.0))
            self.plot.addItem(text)
            self.marks.append((line, text))
        self.curves: list[tuple[pg.PlotDataItem, pg.PlotDataItem]] = []
        self.plot.setRange(xRange=(-1.15, 1.15), yRange=(-0.1, 1.2), padding=0)

    def radius(self, values: np.ndarray, peak: float) -> np.ndarray:
        if self.lab.settings["polar_log"]:
            floor = peak * 10.0 ** -self.DECADES
            return np.maximum(np.log10(np.maximum(values, floor) / floor), 0.0) / self.DECADES
        return values / peak

    def redraw(self, fast: bool = False) -> bool:
        s = self.lab.settings
        theta_i, phi_i, cos = s["theta_i"], s["phi_i"], s["polar_cos"]
        self.data = []
        for state in self.lab.visible_models():
            key = state_key(state, theta_i, phi_i, cos)
            polar = self.cached(state, key, lambda st=state: self.renderer.polar(
                st.model, st.values, theta_i, phi_i, cos_weighted=cos))
            if polar is not None:
                self.data.append((state, polar))
        lum = [(st, p, p.values.astype(np.float64) @ LUMA) for st, p in self.data]
        # Grazing directions are left out of the scale: some models (Ward) diverge there.
        peaks = [finite_max(v[np.abs(p.theta_o) <= 87.0]) for _, p, v in lum]
        peaks += [float(np.asarray(p.spike) @ LUMA) for _, p, _ in lum if p.spike is not None]
        peak = max([x for x in peaks if np.isfinite(x)] + [1e-12])
        ti = math.radians(theta_i)
        for (line, text), a in zip(self.marks, (0.0, -ti, ti), strict=True):
            line.setData([0, 1.05 * math.sin(a)], [0, 1.05 * math.cos(a)])
            text.setPos(1.1 * math.sin(a), 1.1 * math.cos(a))
        while len(self.curves) < len(lum):
            self.curves.append((self.plot.plot(), self.plot.plot()))
        for index, (curve, spike) in enumerate(self.curves):
            if index >= len(lum):
                curve.setData([], [])
                spike.setData([], [])
                continue
            state, polar, values = lum[index]
            r = np.minimum(np.nan_to_num(self.radius(values, peak), posinf=1.3), 1.3)
            a = np.radians(polar.theta_o)
            curve.setData(r * np.sin(a), r * np.cos(a), pen=pg.mkPen(state.color, width=2))
            if polar.spike is not None:
                h = float(self.radius(np.array([float(np.asarray(polar.spike) @ LUMA)]), peak)[0])
                spike.setData([0, h * math.sin(ti)], [0, h * math.cos(ti)],
                              pen=pg.mkPen(state.color, width=4))
            else:
                spike.setData([], [])
        return False

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
    """Wireframe lobes projected by hand; drag rotates, the wheel zooms."""

    def __init__(self, view: LobeView):
        super().__init__()
        self.view = view
        self.lines: list[tuple[list, str]] = []
        self.paths: list[tuple[object, str]] = []
        self.marks: list[tuple[np.ndarray, tuple]] = []
        self.last = None
        self.setMinimumSize(160, 160)

    def project(self, points: np.ndarray) -> np.ndarray:
        s = self.view.lab.settings
        yaw, pitch = s["lobe_yaw"], s["lobe_pitch"]
        x, y, z = points[..., 0], points[..., 1], points[..., 2]
        xr = x * math.cos(yaw) - y * math.sin(yaw)
        yr = x * math.sin(yaw) + y * math.cos(yaw)
        up = z * math.cos(pitch) - yr * math.sin(pitch)
        scale = 0.45 * min(self.width(), self.height()) * s["lobe_zoom"]
        cx, cy = self.width() / 2, self.height() * 0.62
        return np.stack([cx + scale * xr, cy - scale * up], axis=-1)

    def paintEvent(self, event) -> None:
        painter = QPainter(self)
        painter.fillRect(self.rect(), QColor(*BACKGROUND))
        painter.setRenderHint(QPainter.RenderHint.Antialiasing, not self.view.fast)
        # One path per model from numpy arrays: building QPointF lists would cost milliseconds.
        self.paths = []
        for polylines, color in self.lines:
            screen = [self.project(line) for line in polylines]
            xy = np.concatenate(screen)
            connect = np.concatenate([np.r_[np.ones(len(p) - 1, bool), False] for p in screen])
            self.paths.append((pg.arrayToQPath(xy[:, 0], xy[:, 1], connect=connect), color))
        ring = np.radians(np.linspace(0, 360, 73))
        disc = np.stack([np.cos(ring), np.sin(ring), 0 * ring], axis=-1)
        painter.setPen(QPen(QColor(110, 110, 110), 1))
        painter.drawPolyline([QPointF(*p) for p in self.project(disc)])
        for direction, color in self.marks:
            ends = self.project(np.array([[0.0, 0.0, 0.0], direction * 1.1]))
            painter.setPen(QPen(QColor(*color), 1.5, Qt.PenStyle.DashLine))
            painter.drawLine(QPointF(*ends[0]), QPointF(*ends[1]))
        for path, color in self.paths:
            qcolor = QColor(color)
            qcolor.setAlpha(170)
            painter.setPen(QPen(qcolor, 1))
            painter.drawPath(path)
        painter.end()

    def mousePressEvent(self, event) -> None:
        self.last = event.position()

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
    """The 3D lobe over the hemisphere (f_r or f_r cos, linear or log as the polar plot)."""

    title = "3D lobe"
    name = "lobe3d"

    def __init__(self, lab, renderer):
        super().__init__(lab, renderer)
        self.tools.addWidget(QLabel("drag to rotate, wheel to zoom; scale as the polar plot"))
        self.fast = False
        self.canvas = LobeCanvas(self)
        self.layout_.addWidget(self.canvas, 1)
        self.data: list[tuple[ModelState, tuple]] = []

    def redraw(self, fast: bool = False) -> bool:
        from lab.render import direction

        s = self.lab.settings
        theta_i, phi_i = s["theta_i"], s["phi_i"]
        grid = (16, 37) if fast else (31, 73)
        self.fast = fast
        self.data = []
        for state in self.lab.visible_models():
            key = state_key(state, theta_i, phi_i, grid)
            lobe = self.cached(state, key, lambda st=state: self.renderer.lobe3d(
                st.model, st.values, theta_i, phi_i, n_theta=grid[0], n_phi=grid[1]))
            if lobe is not None:
                self.data.append((state, lobe))
        values = []
        for _, (theta, _phi, f) in self.data:
            lum = f.astype(np.float64) @ LUMA
            if s["polar_cos"]:
                lum = lum * np.cos(np.radians(theta))[:, None]
            values.append(lum)
        peak = max([finite_max(v[theta <= 87.0]) for (_, (theta, _, _)), v
                    in zip(self.data, values, strict=True)] + [1e-12])
        self.canvas.lines = []
        for (state, (theta, phi, _)), lum in zip(self.data, values, strict=True):
            if s["polar_log"]:
                floor = peak * 1e-3
                r = np.log10(np.maximum(lum, floor) / floor) / 3.0
            else:
                r = lum / peak
            tt, pp = np.meshgrid(theta, phi, indexing="ij")
            dirs = direction(tt, pp)
            points = dirs * np.nan_to_num(np.minimum(r, 1.5))[..., None]
            lines = [points[i] for i in range(0, len(theta), 2)]
            lines += [points[:, j] for j in range(0, len(phi), 3)]
            self.canvas.lines.append((lines, state.color))
        light = direction(theta_i, phi_i)
        self.canvas.marks = [
            (np.array([0.0, 0.0, 1.0]), (200, 200, 200)),
            (light, (255, 210, 0)),
            (np.array([-light[0], -light[1], light[2]]), (120, 200, 255)),
        ]
        self.canvas.update()
        return fast


class SliceView(View):
    """f_r over (theta_h, theta_d) at a chosen phi_d, one image per visible model."""

    title = "Image slice (θh, θd)"
    name = "slice"

    def __init__(self, lab, renderer):
        super().__init__(lab, renderer)
        s = lab.settings
        self.tools.addWidget(SettingSlider(s, "phi_d", "φd", 0.0, 180.0, 1.0), 1)
        self.tools.addWidget(QLabel("tone as the spheres"))
        self.graphics = pg.GraphicsLayoutWidget()
        self.layout_.addWidget(self.graphics, 1)
        self.plots: list[tuple[pg.PlotItem, pg.ImageItem]] = []
        self.data: list[tuple[ModelState, np.ndarray]] = []

    def _ensure_plots(self, count: int) -> None:
        if len(self.plots) == count:
            return
        self.graphics.clear()
        self.plots = []
        for _ in range(count):
            plot = self.graphics.addPlot()
            plot.setLabel("bottom", "θh (deg)")
            plot.setLabel("left", "θd (deg)")
            plot.setAspectLocked(True)
            plot.setMouseEnabled(False, False)
            image = pg.ImageItem(axisOrder="row-major")
            image.setRect(QRectF(0, 0, 90, 90))
            plot.addItem(image)
            plot.setRange(xRange=(0, 90), yRange=(0, 90), padding=0)
            self.plots.append((plot, image))

    def redraw(self, fast: bool = False) -> bool:
        s = self.lab.settings
        size = 96 if fast else 160
        self.data = []
        for state in self.lab.visible_models():
            key = state_key(state, s["phi_d"], size)
            image = self.cached(state, key, lambda st=state: self.renderer.slice(
                st.model, st.values, s["phi_d"], size))
            if image is not None:
                self.data.append((state, image))
        self._ensure_plots(len(self.data))
        scale = 2.0 ** s["exposure"]
        for (plot, item), (state, image) in zip(self.plots, self.data, strict=True):
            rgb = np.clip(np.nan_to_num(image[::-1]) * scale, 0.0, 1.0) ** (1.0 / s["gamma"])
            item.setImage((rgb * 255).astype(np.uint8), levels=(0, 255))
            item.setRect(QRectF(0, 0, 90, 90))
            if plot.titleLabel.text != state.label:
                plot.setTitle(state.label, color=state.color)
        return fast


class AlbedoView(View):
    """Directional albedo vs theta_i; values above the albedo = 1 line are energy gain."""

    title = "Directional albedo"
    name = "albedo"

    def __init__(self, lab, renderer):
        super().__init__(lab, renderer)
        self.note = QLabel("albedo = ∫ f_r cos θo dω (largest colour channel)")
        self.tools.addWidget(self.note)
        self.plot = pg.PlotWidget()
        self.plot.setLabel("bottom", "θi (deg)")
        self.plot.setLabel("left", "directional albedo")
        self.plot.setMouseEnabled(False, False)
        self.layout_.addWidget(self.plot, 1)
        self.data: list[tuple[ModelState, np.ndarray, np.ndarray]] = []
        self.plot.addItem(pg.InfiniteLine(pos=1.0, angle=0, pen=pg.mkPen(
            (220, 220, 220), style=Qt.PenStyle.DashLine), label="albedo = 1"))
        self.curves: list[tuple[pg.PlotDataItem, pg.PlotDataItem]] = []
        self.top = 0.0

    def redraw(self, fast: bool = False) -> bool:
        phi_i = self.lab.settings["phi_i"]
        quality = (np.linspace(0, 85, 9), 32, 16) if fast else (np.arange(0, 90, 2.5), 192, 48)
        thetas, samples, wedges = quality
        self.data = []
        refine = False
        for state in self.lab.visible_models():
            full_key = state_key(state, phi_i, "full")
            hit = self.cache.get(id(state))
            if hit is not None and hit[0] == full_key:
                result = hit[1]
            else:
                key = state_key(state, phi_i, "fast" if fast else "full")
                result = self.cached(state, key, lambda st=state: (thetas, self.renderer.albedo(
                    st.model, st.values, thetas, phi_i, samples=samples, wedges=wedges)))
                refine = refine or fast
            if result is not None:
                self.data.append((state, result[0], result[1].max(axis=1)))
        while len(self.curves) < len(self.data):
            gain_marks = self.plot.plot(pen=None, symbol="x", symbolBrush=None,
                                        symbolPen=pg.mkPen((255, 60, 60), width=2))
            self.curves.append((self.plot.plot(), gain_marks))
        gain = []
        for index, (curve, marks) in enumerate(self.curves):
            if index >= len(self.data):
                curve.setData([], [])
                marks.setData([], [])
                continue
            state, thetas_, albedo = self.data[index]
            curve.setData(thetas_, albedo, pen=pg.mkPen(state.color, width=2))
            over = albedo > 1.0 + 1e-3
            marks.setData(thetas_[over], albedo[over])
            if over.any():
                gain.append(state.label)
        top = max([finite_max(a) for _, _, a in self.data] + [1.0])
        if top != self.top:
            self.top = top
            self.plot.setRange(xRange=(0, 90), yRange=(0, top * 1.1), padding=0.02)
        if gain:
            self.note.setText("<span style='color:#ff5050'>energy gain (albedo > 1): "
                              + ", ".join(gain) + "</span>")
        else:
            self.note.setText("albedo = ∫ f_r cos θo dω (largest colour channel)")
        return refine


class ObjectView(View):
    """The selected model on a procedural object with several lights and ambient light."""

    title = "Lit object / spatially varying"
    name = "object"
    FILL_LIGHTS = [Light(60.0, 200.0, (0.35, 0.4, 0.55)), Light(75.0, 100.0, (0.5, 0.4, 0.3)),
                   Light(50.0, 300.0, (0.3, 0.3, 0.3))]

    def __init__(self, lab, renderer):
        super().__init__(lab, renderer)
        s = lab.settings
        self.tools.addWidget(SettingCombo(s, "shape", SHAPES))
        self.tools.addWidget(SettingCombo(s, "mode", MODES))
        self.tools.addWidget(SettingSlider(s, "lights", "lights", 1, 4, 1), 1)
        self.tools.addWidget(SettingSlider(s, "ambient", "ambient", 0.0, 0.3, 0.01), 1)
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

    def redraw(self, fast: bool = False) -> bool:
        s = self.lab.settings
        state = self.subject()
        if state is None:
            self.canvas.images = []
            self.canvas.update()
            return False
        full = max(min(self.canvas.width(), self.canvas.height() - 20, 512), 32)
        size = min(full, 112) if fast else full
        lights = [Light(s["theta_i"], s["phi_i"])] + self.FILL_LIGHTS[: s["lights"] - 1]
        ambient = (s["ambient"],) * 3
        key = state_key(state, size, s["theta_i"], s["phi_i"], s["lights"], s["ambient"],
                        s["shape"], s["mode"], s["yaw"], s["pitch"])
        self.cache = {k: v for k, v in self.cache.items() if k == id(state)}
        image = self.cached(state, key, lambda: self.renderer.object(
            state.model, state.values, lights, ambient, s["shape"], s["mode"], s["yaw"],
            s["pitch"], size))
        self.image = image
        if image is not None:
            caption = f"{state.label}: {MODES[s['mode']]}"
            self.canvas.images = [(tonemap(image, s["exposure"], s["gamma"]), caption,
                                   state.color)]
        self.canvas.update()
        return size < full


VIEW_CLASSES = [SphereView, PolarView, LobeView, SliceView, AlbedoView, ObjectView]


def big_font(widget: QWidget, scale: float) -> None:
    font = QFont(widget.font())
    font.setPointSizeF(font.pointSizeF() * scale)
    widget.setFont(font)

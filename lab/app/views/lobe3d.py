"""The 3D lobe's widget: the selected model's f_r as a surface, orbited with the mouse."""

from __future__ import annotations

import numpy as np
from PyQt6.QtCore import QPointF
from PyQt6.QtGui import QColor, QImage, QPainter
from PyQt6.QtWidgets import QCheckBox, QWidget

from lab.app.a11y import OrbitKeys
from lab.app.state import ModelState
from lab.app.views.base import BACKGROUND, View, opaque, state_key
from lab.app.widgets import LiveText, SettingCheck
from lab.glsl import ShaderCompileError
from lab.models import ModelError
from lab.render import LOBE_FAST_GRID, LOBE_GRID, LOBE_MARK_RGB, LobeCamera, direction


class LobeCanvas(QWidget):
    """The lobe image drawn by the models' GLSL, with the marks' names; drag rotates, the
    wheel zooms."""

    plot_text = True  # the marks' names in the plot font (View.apply_font)

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
        hint = LiveText("drag: rotate, wheel: zoom", short="drag, wheel", optional=True)
        self.tools.addWidget(hint, 1)
        self.canvas = LobeCanvas(self)
        self.canvas.setAccessibleName("3D lobe of the visible models")
        OrbitKeys(self.canvas, s, "lobe_yaw", "lobe_pitch", "lobe_zoom")
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

    settings_used = (
        "theta_i",
        "phi_i",
        "polar_cos",
        "polar_log",
        "lobe_yaw",
        "lobe_pitch",
        "lobe_zoom",
    )

    def own_inputs(self) -> tuple:
        return (self.wire.isChecked(), self.size_())

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

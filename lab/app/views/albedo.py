"""The directional albedo's widget: the energy each model reflects against θi."""

from __future__ import annotations

import math

import numpy as np
import pyqtgraph as pg
from PyQt6.QtCore import Qt

from lab.app.state import ModelState
from lab.app.views.base import View, finite_max, opaque, pen, state_key
from lab.app.widgets import LiveText
from lab.views import albedo as spec


class AlbedoView(View):
    """Directional albedo vs theta_i; values above the albedo = 1 line are energy gain."""

    title = "Directional albedo"
    name = "albedo"
    NOTE = "albedo = ∫ f_r cos θo dω (largest colour channel)"

    def __init__(self, lab, renderer):
        super().__init__(lab, renderer)
        self.note = LiveText(self.NOTE, short="albedo = ∫ f_r cos θo dω", optional=True)
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

    # Albedo is integrated over every outgoing direction: it does not depend on theta_i.
    settings_used = ("phi_i",)

    def draw(self, fast: bool) -> bool:
        phi_i = self.lab.settings["phi_i"]
        self.data = []
        coarse = False
        for state in self.lab.visible_models():
            key = state_key(state, phi_i)

            def compute(full: bool, st=state):
                quality = spec.FULL if full else spec.FAST
                angles = spec.thetas(quality)
                return angles, self.renderer.albedo(
                    st.model,
                    st.values,
                    angles,
                    phi_i,
                    samples=quality["samples"],
                    wedges=quality["wedges"],
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

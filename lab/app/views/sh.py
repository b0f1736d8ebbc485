"""The spherical-harmonics view: the selected model's lobe and its SH reconstruction.

The lobe g(w_o) = f_r(w_i, w_o) cos(theta_o) for the current light comes from the model's
GLSL (Renderer.probe on a quadrature grid, Renderer.polar in the plane of incidence); the
projection, reconstruction and errors are lab/measured/sh.py's. Left: g and its
reconstruction at order L in the plane of incidence (negative lobes of the truncated
series show as ringing below zero). Right: relative L2 error over the hemisphere vs order.
"""

from __future__ import annotations

import math
from functools import lru_cache
from typing import TYPE_CHECKING

import numpy as np
import pyqtgraph as pg
from PyQt6.QtCore import Qt
from PyQt6.QtWidgets import QLabel, QSpinBox

from lab import plotscale
from lab.app.state import ModelState, Settings
from lab.app.views.base import LUMA, View, look_key, pen, state_key
from lab.app.widgets import LiveText, setting_label
from lab.glsl import ShaderCompileError
from lab.models import ModelError
from lab.render import direction, plane_of_incidence
from lab.views.sh import GRID, MAX_ORDER

if TYPE_CHECKING:  # the SH maths is imported when first used: the first frame draws
    from lab.measured import sh  # only the plane of incidence

SERIES_COLOR = (255, 210, 0)


@lru_cache(maxsize=2)
def projector(n_theta: int, n_phi: int) -> sh.Projector:
    """Harmonics on the quadrature grid (the same for every light and model)."""
    from lab.measured import sh

    return sh.Projector(MAX_ORDER, sh.hemisphere_grid(n_theta, n_phi))


@lru_cache(maxsize=8)
def plane_basis(phi_i: float) -> tuple[np.ndarray, np.ndarray]:
    """theta_o and the harmonics at the plane of incidence's directions (1 deg steps).

    The directions depend on phi_i alone, so dragging theta_i reuses them.
    """
    from lab.measured import sh

    theta_o, V = plane_of_incidence(0.0, phi_i, step=1.0)
    theta = np.arccos(np.clip(V[:, 2], -1.0, 1.0))
    return theta_o, sh.real_sh(MAX_ORDER, theta, np.arctan2(V[:, 1], V[:, 0]))


class SettingSpin(QSpinBox):
    """A spin box bound to one int setting."""

    def __init__(self, settings: Settings, name: str, low: int, high: int):
        super().__init__()
        self.setRange(low, high)
        self.setAccessibleName(setting_label(name))
        self.setValue(int(settings[name]))
        self.valueChanged.connect(lambda v: settings.set(name, v))
        settings.changed.connect(
            lambda n: (
                n == name and self.value() != settings[name] and self.setValue(int(settings[name]))
            )
        )


class SHData:
    """One model's lobe at one light: coefficients, errors by order, the plane's curves."""

    def __init__(
        self,
        coefficients: np.ndarray,
        errors: np.ndarray,
        theta_o: np.ndarray,
        plane: np.ndarray,
        plane_basis: np.ndarray,
        peak: float,
    ):
        self.coefficients = coefficients  # ((MAX_ORDER + 1)^2,) of the luminance lobe
        self.errors = errors  # (MAX_ORDER + 1,) relative L2 error over the hemisphere
        self.theta_o = theta_o  # plane of incidence, -90 (light side) .. 90 deg
        self.plane = plane  # the lobe there (luminance of f_r cos theta_o)
        self.plane_basis = plane_basis
        self.peak = peak

    def reconstruction(self, order: int) -> np.ndarray:
        """The order-`order` series in the plane of incidence."""
        from lab.measured.sh import coefficient_count

        n = coefficient_count(order)
        return self.plane_basis[:, :n] @ self.coefficients[:n]


def sh_data(
    renderer, state: ModelState, theta_i: float, phi_i: float, grid: tuple[int, int] = GRID
) -> SHData:
    """Project the model's lobe (from its GLSL) for light (theta_i, phi_i) on harmonics."""
    proj = projector(*grid)
    V = proj.grid.directions
    L = np.repeat(direction(theta_i, phi_i)[None], len(V), axis=0)
    f = renderer.probe(state.model, state.values, L, V).astype(np.float64)
    # Non-finite values (a user shader dividing by zero) would swamp every coefficient.
    lobe = np.nan_to_num(f @ LUMA * V[:, 2], nan=0.0, posinf=0.0, neginf=0.0)[:, None]
    coefficients = proj.project(lobe)
    errors = proj.errors(lobe, coefficients)
    polar = renderer.polar(state.model, state.values, theta_i, phi_i, cos_weighted=True)
    theta_o, basis = plane_basis(float(phi_i))
    plane = np.nan_to_num(polar.values.astype(np.float64) @ LUMA, nan=0.0, posinf=0.0, neginf=0.0)
    peak = plotscale.peak_value(theta_o, plane)  # the scale rule of every plot
    return SHData(coefficients[:, 0], errors, theta_o, plane, basis, peak)


class SHView(View):
    """The selected model's lobe at the current light and its SH series at order L."""

    title = "Spherical harmonics"
    name = "sh"

    def __init__(self, lab, renderer):
        super().__init__(lab, renderer)
        self.tools.addWidget(QLabel("order L"))
        self.order_box = SettingSpin(lab.settings, "sh_order", 0, MAX_ORDER)
        self.tools.addWidget(self.order_box)
        self.info = LiveText()  # long texts are cut, they never widen the window
        self.tools.addWidget(self.info, 1)
        self.graphics = pg.GraphicsLayoutWidget()
        self.graphics.ci.layout.setColumnStretchFactor(0, 3)
        self.graphics.ci.layout.setColumnStretchFactor(1, 2)
        self.layout_.addWidget(self.graphics, 1)
        self.lobe_plot = self.graphics.addPlot()
        self.lobe_plot.setLabel("bottom", "θo (deg)")
        self.lobe_plot.setTitle("f_r cos θo in the plane of incidence")
        self.lobe_plot.setLabel("left", "relative to its peak")
        self.lobe_plot.getAxis("left").setTicks([[(0, "0"), (0.5, ".5"), (1, "1")]])
        self.lobe_plot.getAxis("bottom").setTicks([[(t, str(t)) for t in (-90, -45, 0, 45, 90)]])
        self.lobe_plot.setMouseEnabled(False, False)
        self.lobe_plot.hideButtons()
        self.lobe_plot.setRange(xRange=(-90, 90), yRange=(-0.35, 1.15), padding=0)
        self.lobe_plot.addItem(pg.InfiniteLine(pos=0.0, angle=0, pen=pg.mkPen((120, 120, 120))))
        self.mirror = pg.InfiniteLine(
            angle=90, pen=pg.mkPen((120, 200, 255), style=Qt.PenStyle.DashLine)
        )
        self.lobe_plot.addItem(self.mirror)
        # Which curve is which, on the plot itself.
        self.lobe_plot.addLegend(offset=(4, 4), labelTextSize="9pt")
        self.lobe_curve = self.lobe_plot.plot(name="original (GLSL)")
        self.series_curve = self.lobe_plot.plot(name="SH series, order L")
        self.error_plot = self.graphics.addPlot()
        self.error_plot.setLabel("bottom", "order L")
        self.error_plot.setTitle("relative L2 error")
        self.error_plot.setLabel("left", "error")
        self.error_plot.getAxis("bottom").setTicks(
            [[(k, str(k)) for k in range(0, MAX_ORDER + 1, 8)]]
        )
        self.error_plot.setLogMode(False, True)
        self.error_plot.setMouseEnabled(False, False)
        self.error_curve = self.error_plot.plot()
        self.order_mark = pg.InfiniteLine(angle=90, pen=pg.mkPen(SERIES_COLOR, width=1.5))
        self.error_plot.addItem(self.order_mark)
        self.info.setToolTip(
            "left: f_r cos θo in the plane of incidence (solid) and its "
            "spherical-harmonics series (dashed yellow); right: the "
            "relative L2 error over the hemisphere vs order (yellow: L)"
        )
        self.data: SHData | None = None
        self.state: ModelState | None = None
        self.shown: tuple = ()
        self.scale = 1.0
        self.low = 1
        self.setMinimumWidth(250)  # two plots side by side

    def subject(self) -> ModelState | None:
        visible = self.lab.visible_models()
        if self.lab.selected in visible:
            return self.lab.selected
        return visible[0] if visible else None

    @property
    def order(self) -> int:
        return int(self.lab.settings["sh_order"])

    @property
    def order_errors(self) -> np.ndarray:
        """Relative error by order 0..MAX_ORDER of the shown lobe (empty without one)."""
        return self.data.errors if self.data is not None else np.zeros(0)

    settings_used = ("theta_i", "phi_i")

    def shown_models(self) -> tuple:
        state = self.subject()
        return (look_key(state),) if state else ()

    def own_inputs(self) -> tuple:
        return (self.order,)

    def plane(self, state: ModelState, theta_i: float, phi_i: float) -> np.ndarray:
        """The lobe in the plane of incidence alone: the cheap part, drawn while sliding."""
        polar = self.renderer.polar(state.model, state.values, theta_i, phi_i, cos_weighted=True)
        return np.nan_to_num(
            polar.values.astype(np.float64) @ LUMA, nan=0.0, posinf=0.0, neginf=0.0
        )

    def draw(self, fast: bool) -> bool:
        s = self.lab.settings
        state = self.subject()
        self.state = state
        self.cache = {k: v for k, v in self.cache.items() if state is not None and k == id(state)}
        if state is None or state.model.delta:
            self.data = None
            self.shown = ()
            for curve in (self.lobe_curve, self.series_curve, self.error_curve):
                curve.setData([], [])
            self.info.setText(
                "an ideal mirror has no finite lobe to expand"
                if state is not None
                else "no model to show"
            )
            return False
        key = state_key(state, s["theta_i"], s["phi_i"])
        hit = self.cache.get(id(state))
        if fast and not (hit is not None and hit[0] == (*key, GRID)):
            # The projection is the heavy part: it waits for the slider to stop. The lobe
            # itself follows the slider; the series and the errors are cleared, not stale.
            try:
                plane = self.plane(state, s["theta_i"], s["phi_i"])
            except (ShaderCompileError, ModelError):
                return False
            theta_o = np.arange(-90.0, 90.5, 1.0)
            self.show_lobe(
                state,
                theta_o,
                plane,
                max(plotscale.peak_value(theta_o, plane), 1e-9),
            )
            self.series_curve.setData([], [])
            self.shown = ()
            self.info.setText("series and error follow when the slider stops")
            return True
        self.data = self.cached(
            state,
            (*key, GRID),
            lambda: sh_data(self.renderer, state, s["theta_i"], s["phi_i"], GRID),
        )
        data = self.data
        if data is None:
            return False
        from lab.measured.sh import coefficient_count  # loaded by sh_data by now

        order = self.order
        shown = (id(data), order, state.color)
        if shown == self.shown:
            return False
        self.shown = shown
        self.show_lobe(state, data.theta_o, data.plane, max(data.peak, 1e-9))
        self.series_curve.setData(
            data.theta_o,
            data.reconstruction(order) * self.scale,
            pen=pen(SERIES_COLOR, 1.5, Qt.PenStyle.DashLine),
        )
        errors = np.maximum(data.errors, 1e-6)  # log axis
        low = math.floor(math.log10(errors.min()))
        if low != self.low:
            self.low = low
            self.error_plot.setRange(xRange=(-0.5, MAX_ORDER + 0.5), yRange=(low, 0.2), padding=0)
            # A few decades labelled, never one per power of ten piled on top of each other.
            step = max(1, math.ceil(-low / 3))
            self.error_plot.getAxis("left").setTicks(
                [[(k, f"1e{k}" if k else "1") for k in range(0, low - 1, -step)], []]
            )
        self.error_curve.setData(np.arange(MAX_ORDER + 1), errors, pen=pen(state.color))
        self.order_mark.setValue(order)
        self.info.setText(
            f"L = {order}: {coefficient_count(order)} coefficients, "
            f"error {100 * data.errors[order]:.2g} %"
        )
        return False

    def show_lobe(
        self, state: ModelState, theta_o: np.ndarray, plane: np.ndarray, top: float
    ) -> None:
        """The lobe (and later its series) relative to the lobe's peak: a fixed y range,
        so no new ticks or layout while a slider moves, and the shape is what matters."""
        self.scale = 1.0 / top
        self.lobe_curve.setData(theta_o, plane * self.scale, pen=pen(state.color))
        self.mirror.setValue(self.lab.settings["theta_i"])

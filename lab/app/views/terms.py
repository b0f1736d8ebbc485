"""The microfacet terms view: D against θh, G against θo, F against θd for every visible
model that defines MICROFACET_TERMS, each in its colour (lab/views/terms.py computes them
from the model's GLSL)."""

from __future__ import annotations

import numpy as np
import pyqtgraph as pg
from PyQt6.QtCore import Qt

from lab.app.views.base import LUMA, View, pen, state_key
from lab.app.widgets import LiveText
from lab.views.terms import has_terms, microfacet_terms


class TermsView(View):
    """Three plots side by side; models without separate terms are named in the tool row."""

    title = "Microfacet terms D, G, F"
    name = "terms"

    def __init__(self, lab, renderer):
        super().__init__(lab, renderer)
        self.info = LiveText()
        self.tools.addWidget(self.info, 1)
        self.graphics = pg.GraphicsLayoutWidget()
        self.layout_.addWidget(self.graphics, 1)
        self.d_plot = self.graphics.addPlot(title="D (1/sr, log, 5 decades)")
        self.d_plot.setLabel("bottom", "θh: N to H (deg)")
        self.d_plot.setLogMode(False, True)
        self.g_plot = self.graphics.addPlot(title="G, plane of incidence")
        self.g_plot.setLabel("bottom", "θo (deg)")
        self.g_plot.setRange(xRange=(-90, 90), yRange=(0, 1.05), padding=0)
        self.mirror = pg.InfiniteLine(
            angle=90, pen=pg.mkPen((120, 200, 255), style=Qt.PenStyle.DashLine)
        )
        self.g_plot.addItem(self.mirror)
        self.f_plot = self.graphics.addPlot(title="F (luminance)")
        self.f_plot.setLabel("bottom", "θd: V to H (deg)")
        self.f_plot.setRange(xRange=(0, 90), yRange=(0, 1.05), padding=0)
        for plot in (self.d_plot, self.g_plot, self.f_plot):
            plot.setMouseEnabled(False, False)
            plot.hideButtons()
        self.curves: list = []
        self.shown: list = []  # (label, Terms) drawn, for tests
        self.setMinimumWidth(300)

    settings_used = ("theta_i", "phi_i")

    def draw(self, fast: bool) -> bool:
        s = self.lab.settings
        for plot, curve in self.curves:
            plot.removeItem(curve)
        self.curves, self.shown, others, tables = [], [], [], []
        for state in self.lab.visible_models():
            if not has_terms(state.model):
                # A measured table cannot define its terms: it is told to fit a model instead.
                (tables if getattr(state.model, "no_terms_reason", "") else others).append(
                    state.label
                )
                continue
            terms = self.cached(
                state,
                state_key(state, s["theta_i"], s["phi_i"]),
                lambda st=state: microfacet_terms(
                    self.renderer, st.model, st.values, s["theta_i"], s["phi_i"]
                ),
            )
            if terms is None:
                continue
            self.shown.append((state.label, terms))
            ok = np.isfinite(terms.D) & (terms.D > 0)
            f = np.nan_to_num(terms.F @ LUMA)
            for plot, x, y in (
                (self.d_plot, terms.theta[ok], terms.D[ok]),
                (self.g_plot, terms.theta_o, np.nan_to_num(terms.G)),
                (self.f_plot, terms.theta, f),
            ):
                self.curves.append((plot, plot.plot(x, y, pen=pen(state.color))))
        self.mirror.setValue(s["theta_i"])
        peaks = [
            float(t.D[np.isfinite(t.D)].max()) for _, t in self.shown if np.isfinite(t.D).any()
        ]
        if peaks and max(peaks) > 0:  # five decades below the highest peak (Beckmann dives)
            top = np.log10(max(peaks))
            self.d_plot.setRange(xRange=(0, 90), yRange=(top - 5.0, top + 0.3), padding=0)
        text = "" if self.shown else "no microfacet model shown"
        if others:
            text += ("; " if text else "") + (
                f"no separate D, G, F: {', '.join(others)} (define MICROFACET_TERMS)"
            )
        if tables:
            text += ("; " if text else "") + (
                f"{', '.join(tables)}: a measured table, fit a microfacet model to see its terms"
            )
        self.info.setText(text)
        return False

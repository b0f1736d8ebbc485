"""The lit spheres' widget: one sphere per visible model, drag to move the light."""

from __future__ import annotations

import math

import numpy as np
from PyQt6.QtWidgets import QLabel

from lab.app.state import ModelState
from lab.app.views.base import ImageRow, View, state_key
from lab.app.widgets import SettingCheck, SettingSlider
from lab.nonfinite import sphere_report
from lab.render import direction


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

    settings_used = ("theta_i", "phi_i", "multiply_cos", "exposure", "gamma")

    def own_inputs(self) -> tuple:
        return (self.side(),)

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

"""The retroreflection view's Qt widget: a label that shows the selected model's peak."""

from __future__ import annotations

from PyQt6.QtWidgets import QLabel

from lab.app.views.base import View, look_key

from .retro import retro_values


class RetroView(View):
    title = "Retroreflection"
    name = "retro"

    def __init__(self, lab, renderer):
        super().__init__(lab, renderer)
        self.label = QLabel("")
        self.layout_.addWidget(self.label)

    settings_used = ("phi_i", "retro_gain")  # it redraws when one of these changes

    def shown_models(self) -> tuple:
        state = self.lab.selected
        return (look_key(state),) if state else ()

    def draw(self, fast: bool) -> bool:
        state = self.lab.selected
        if state is not None:
            lum = retro_values(self.renderer, state.model, state.values, self.lab.settings["phi_i"])
            self.label.setText(f"peak {lum.max() * self.lab.settings['retro_gain']:.4g} 1/sr")
        return False

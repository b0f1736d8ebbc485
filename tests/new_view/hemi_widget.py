"""The hemisphere view's Qt widget: a label with the selected model's peak f_r."""

from __future__ import annotations

from lab.views.hemi import image
from PyQt6.QtWidgets import QLabel

from lab.app.views.base import View, look_key


class HemiView(View):
    title = "Hemisphere of f_r"
    name = "hemi"
    settings_used = ("theta_i", "phi_i", "hemi_gain")

    def __init__(self, lab, renderer):
        super().__init__(lab, renderer)
        self.label = QLabel("")
        self.layout_.addWidget(self.label)

    def shown_models(self) -> tuple:
        state = self.lab.selected
        return (look_key(state),) if state else ()

    def draw(self, fast: bool) -> bool:
        state = self.lab.selected
        if state is not None:
            s = self.lab.settings
            picture = image(self.renderer, state.model, state.values, s["theta_i"], s["phi_i"], 32)
            self.label.setText(f"peak {picture[..., :3].max() * s['hemi_gain']:.4g} 1/sr")
        return False

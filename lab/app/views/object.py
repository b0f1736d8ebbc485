"""The lit object's widget: a shape under several lights, with the spatially varying steps."""

from __future__ import annotations

import numpy as np
from PyQt6.QtWidgets import QComboBox, QHBoxLayout

from lab.app.a11y import OrbitKeys
from lab.app.renderer import MODES, SHAPES
from lab.app.state import ModelState
from lab.app.views.base import ImageRow, View, look_key, state_key, tonemap
from lab.app.widgets import SettingCombo, SettingSlider
from lab.render import Light


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
        self.canvas.setAccessibleName("lit object")
        OrbitKeys(self.canvas, s, "yaw", "pitch")
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

    settings_used = (
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

    def shown_models(self) -> tuple:
        state = self.subject()
        return (look_key(state),) if state else ()

    def own_inputs(self) -> tuple:
        return (self.side(),)

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

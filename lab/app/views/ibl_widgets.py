"""Widgets of the IBL view (lab/app/views/ibl.py): the log axes of its error plot and its
menu of sample counts."""

from __future__ import annotations

import math

import pyqtgraph as pg
from PyQt6.QtGui import QFontMetrics
from PyQt6.QtWidgets import QComboBox

SAMPLE_TARGETS = (16, 64, 256, 1024, 4096, 16384)  # the target menu's choices (per pixel)


class LogAxis(pg.AxisItem):
    """A log axis whose ticks are round values in the value's own unit ('64' samples,
    '5 %' error), spaced so that no two labels touch. (pyqtgraph labels the minor ticks of
    a log axis as powers, '6·10²' for a ratio of 0.06, and they overlap in large fonts.)"""

    def __init__(self, orientation: str, base: float = 0.0, percent: bool = False):
        super().__init__(orientation)
        self.base, self.percent = base, percent  # base: ticks at its powers, else 1-2-5
        self.enableAutoSIPrefix(False)

    def text(self, value: float) -> str:
        return f"{value * 100:.2g} %" if self.percent else f"{value:.4g}"

    def candidates(self, low: float, high: float) -> list[float]:
        """log10 of the round values between 10^low and 10^high."""
        if self.base > 1:
            step = math.log10(self.base)
            return [k * step for k in range(math.floor(low / step), math.ceil(high / step) + 1)]
        decades = range(math.floor(low), math.ceil(high) + 1)
        return [k + math.log10(m) for k in decades for m in (1, 2, 5)]

    def tickValues(self, minVal, maxVal, size):  # noqa: N802, N803 (pyqtgraph's names)
        if not self.logMode:
            return super().tickValues(minVal, maxVal, size)
        low, high = sorted((minVal, maxVal))
        font = self.style.get("tickFont") or self.font()
        metrics = QFontMetrics(font)
        per_decade = size / max(high - low, 1e-9)
        kept: list[float] = []
        for value in sorted(c for c in self.candidates(low, high) if low <= c <= high):
            label = self.text(10.0**value)
            room = (
                metrics.height() * 1.4
                if self.orientation in ("left", "right")
                else metrics.horizontalAdvance(label) * 1.3 + 8
            )
            if not kept or (value - kept[-1]) * per_decade >= room:
                kept.append(value)
        if not kept:  # a range narrower than one step: its middle, as it is
            kept = [(low + high) / 2]
        return [(1.0, kept)]

    def tickStrings(self, values, scale, spacing):  # noqa: N802 (pyqtgraph's name)
        if not self.logMode:
            return super().tickStrings(values, scale, spacing)
        return [self.text(10.0**v) for v in values]


class SamplesCombo(QComboBox):
    """The sample target per pixel, bound to the `ibl_samples` setting."""

    def __init__(self, settings):
        super().__init__()
        self.settings = settings
        self.setToolTip("samples per pixel to stop at (each strategy, both halves)")
        self.setAccessibleName("samples per pixel to stop at")
        for count in SAMPLE_TARGETS:
            self.addItem(f"{count} spp", count)
        self.follow("ibl_samples")
        self.currentIndexChanged.connect(
            lambda i: i >= 0 and settings.set("ibl_samples", int(self.itemData(i)))
        )
        settings.changed.connect(self.follow)

    def follow(self, name: str) -> None:
        if name != "ibl_samples":
            return
        value = int(self.settings["ibl_samples"])
        if self.findData(value) < 0:  # a preset's own target joins the menu
            self.addItem(f"{value} spp", value)
        self.blockSignals(True)
        self.setCurrentIndex(self.findData(value))
        self.blockSignals(False)

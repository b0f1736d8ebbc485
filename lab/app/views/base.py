"""What every view widget shares: the View base class (tool row, per-model cache,
refinement, PNG export), the image row, tone mapping and the cache keys."""

from __future__ import annotations

import math
from collections.abc import Callable
from functools import lru_cache
from pathlib import Path

import numpy as np
import pyqtgraph as pg
from PyQt6.QtCore import QRect, Qt
from PyQt6.QtGui import QColor, QFont, QFontMetrics, QImage, QPainter, QPen
from PyQt6.QtWidgets import QHBoxLayout, QVBoxLayout, QWidget

from lab import constants
from lab.app.renderer import AppRenderer
from lab.app.state import LabState, ModelState
from lab.glsl import ShaderCompileError
from lab.models import ModelError

LUMA = np.array(constants.LUMA)
QWIDGETSIZE_MAX = (1 << 24) - 1
# The smallest text inside a view when presenting: about 1/32 of a 768-row projector, what
# a reader in the back of a lecture hall still reads (the slides' rule too).
PLOT_TEXT_PX = 24
BACKGROUND = (40, 40, 44)
_BACKGROUND_BGR = np.array(BACKGROUND[::-1], np.float32) / 255.0


def tonemap(image: np.ndarray, exposure: float, gamma: float) -> QImage:
    """Float RGB(A) -> QImage: 2^exposure, clamp, 1/gamma, background where alpha is 0.

    Float32 in place throughout (it runs for every image of every frame), built in the
    BGRA byte order of a 32-bit RGB QImage, which the raster engine draws unconverted.
    """
    bgr = image[..., 2::-1] * np.float32(2.0**exposure)
    np.fmax(bgr, np.float32(0.0), out=bgr)  # fmax also turns NaN into 0
    np.fmin(bgr, np.float32(1.0), out=bgr)
    np.power(bgr, np.float32(1.0 / max(gamma, 0.1)), out=bgr)
    if image.shape[-1] == 4:  # (c - bg) * alpha + bg
        bgr -= _BACKGROUND_BGR
        bgr *= image[..., 3:4]
        bgr += _BACKGROUND_BGR
    bgr *= np.float32(255.0)
    bgr += np.float32(0.5)
    height, width = bgr.shape[:2]
    data = np.full((height, width, 4), 255, np.uint8)
    data[..., :3] = bgr
    return QImage(data.data, width, height, 4 * width, QImage.Format.Format_RGB32).copy()


def finite_max(values: np.ndarray) -> float:
    finite = values[np.isfinite(values)]
    return float(finite.max()) if finite.size else 0.0


def state_key(state: ModelState, *extra) -> tuple:
    return (state.model.code, str(state.model.path), tuple(sorted(state.values.items())), *extra)


def look_key(state: ModelState) -> tuple:
    """What a view shows of a model besides its values: identity, label and colour."""
    return (id(state), state_key(state), state.label, state.color)


@lru_cache(maxsize=64)
def pen(color, width: float = 2.0, style: Qt.PenStyle = Qt.PenStyle.SolidLine) -> QPen:
    """Pens made once per colour (pyqtgraph copies them)."""
    made = pg.mkPen(color, width=width, style=style)
    made.setCosmetic(True)
    return made


def opaque(widget: QWidget) -> QWidget:
    """A widget that paints every pixel: Qt need not paint its parents below it first."""
    widget.setAttribute(Qt.WidgetAttribute.WA_OpaquePaintEvent, True)
    return widget


class View(QWidget):
    """Base: a tool row above the content, a per-model cache and PNG export.

    `redraw(fast)` does nothing when the view's `inputs()` are those it last drew (a light
    change leaves the slice alone, a model's change leaves views of other models alone).
    Subclasses name their `settings_used` (and `own_inputs()`) and implement
    `draw(fast) -> needs a finer pass`.
    """

    title = "view"
    name = "view"

    def __init__(self, lab: LabState, renderer: AppRenderer):
        super().__init__()
        self.lab, self.renderer = lab, renderer
        self.cache: dict[int, tuple[tuple, object]] = {}
        self.toned: dict[int, tuple] = {}  # (image, (exposure, gamma), QImage): tone-map once
        self.layout_ = QVBoxLayout(self)
        self.layout_.setContentsMargins(2, 2, 2, 2)
        self.tools = QHBoxLayout()
        self.layout_.addLayout(self.tools)
        self.errors: list[str] = []
        self.drawn: tuple | None = None  # the inputs of the last draw
        self.coarse = False  # the last draw asked for a finer pass
        self.draws = 0  # how many times the view really drew (tests count them)
        self.budget = 0  # full-quality computations left in this refinement step

    def is_shown(self) -> bool:
        return self.isVisible() and not self.visibleRegion().isEmpty()

    # The lab's settings the picture depends on; inputs() adds the models it shows and
    # own_inputs() (the widget's size, its own controls).
    settings_used: tuple[str, ...] = ()

    def inputs(self) -> tuple:
        """Everything the view's picture depends on."""
        s = self.lab.settings
        return (self.shown_models(), *(s[k] for k in self.settings_used), *self.own_inputs())

    def shown_models(self) -> tuple:
        """The models drawn, as look_key()s (every visible model unless a view says otherwise)."""
        return tuple(look_key(m) for m in self.lab.visible_models())

    def own_inputs(self) -> tuple:
        """What else the picture depends on: the widget's size, the view's own controls."""
        return ()

    def draw(self, fast: bool) -> bool:
        raise NotImplementedError

    def redraw(self, fast: bool = False) -> bool:
        """Draw if the inputs changed (or a finer pass is due); True: refine me later."""
        inputs = self.inputs()
        if inputs == self.drawn and (fast or not self.coarse):
            return self.coarse
        # One full-quality computation per refinement step: a step never holds input back.
        self.budget = 0 if fast else 1
        self.coarse = bool(self.draw(fast))
        self.drawn = inputs
        self.draws += 1
        if not self.coarse:  # at full quality: say what it shows (screen readers)
            from lab.app.plot_words import describe_view

            describe_view(self)
        return self.coarse

    def invalidate(self) -> None:
        self.drawn = None

    def plot_items(self) -> list[pg.PlotItem]:
        """The pyqtgraph plots in the view (their fonts follow presenter mode)."""
        items = []
        for widget in self.findChildren(pg.GraphicsView):
            items += [item for item in widget.items() if isinstance(item, pg.PlotItem)]
        return items

    def apply_font(self, font: QFont, small: QFont | None = None) -> None:
        """Presenter mode: pyqtgraph draws its text with its own fonts; give them `small`
        (the plot text: 0.9 of `font` on the desk, at least PLOT_TEXT_PX when presenting).
        Widgets that paint a picture's captions (`plot_text = True`) get it too."""
        if small is None:
            small = QFont(font)
            small.setPointSizeF(font.pointSizeF() * 0.9)
        for plot in self.plot_items():
            for name in ("left", "bottom"):
                axis = plot.getAxis(name)
                axis.setStyle(tickFont=small)
                axis.label.setFont(small)
                axis.setLabel(axis.labelText, axis.labelUnits)
                if name == "left" and axis.fixedWidth is not None:
                    axis.setWidth(QFontMetrics(small).horizontalAdvance("0.00") * 2 + 8)
            if plot.legend is not None:  # legends drawn later take the size too
                plot.legend.setLabelTextSize(f"{small.pointSizeF():.1f}pt")
        for item in self.findChildren(QWidget):
            if getattr(item, "plot_text", False):
                item.setFont(small)
            item.update()
        for text in getattr(self, "texts", []):
            text.setFont(small)
        self.invalidate()

    def resizeEvent(self, event) -> None:
        super().resizeEvent(event)
        request = getattr(self.window(), "request", None)
        if request is not None:
            request()  # views drawn at their size on screen check their inputs again

    def toned_image(self, state: ModelState, image: np.ndarray, tone: tuple) -> QImage:
        """`image` tone-mapped for display, computed again only when it or the tone changes."""
        known = self.toned.get(id(state))
        if known is None or known[0] is not image or known[1] != tone:
            known = (image, tone, tonemap(image, *tone))
            self.toned[id(state)] = known
        return known[2]

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

    def best(
        self, state: ModelState, fast: bool, fast_key: tuple, full_key: tuple, compute
    ) -> tuple[object, bool]:
        """(result, coarse): the full-quality result when at hand or within this step's
        budget, else the interactive one. `compute(full)` makes either."""
        hit = self.cache.get(id(state))
        if hit is not None and hit[0] == full_key:
            return hit[1], False
        if not fast and self.budget > 0 or fast_key == full_key:
            self.budget -= not fast
            return self.cached(state, full_key, lambda: compute(True)), False
        return self.cached(state, fast_key, lambda: compute(False)), True

    def climb(
        self, state: ModelState, fast: bool, key: tuple, sizes: list[int], compute
    ) -> tuple[object, bool]:
        """(result, coarse) for resolutions `sizes` (ascending): while sliding the smallest
        (or whatever is at hand), then one size up per refinement step, so no single
        step is long. `compute(size)` makes one."""
        hit = self.cache.get(id(state))
        have = hit[0][-1] if hit is not None and hit[0][:-1] == key else None
        if have in sizes and (fast or have == sizes[-1]):
            return hit[1], have != sizes[-1]
        size = sizes[0] if fast or have not in sizes else sizes[sizes.index(have) + 1]
        return self.cached(state, (*key, size), lambda: compute(size)), size != sizes[-1]

    def up_to_date(self) -> None:
        """Draw at full quality now: a hidden view is not redrawn, and exports must not
        save what it showed before the last change."""
        for _ in range(8):  # the refinement steps of the finest view
            if not self.redraw(fast=False):
                break

    def file_actions(self) -> list[tuple[str, Callable[[], None]]]:
        """(menu text, slot) of what the view adds to the File menu besides its PNG."""
        return []

    def export_png(self, path: str | Path) -> None:
        self.up_to_date()
        self.grab().save(str(path))


class ImageRow(QWidget):
    """Images side by side, each with a coloured caption; emits drags as unit-disc points.

    An image as large as its cell is drawn at its own size (no scaling); a coarse one
    (while a slider moves) is scaled up without smoothing.
    """

    CAPTION = 20
    plot_text = True  # captions in the plot font (View.apply_font)

    def __init__(self, on_drag=None):
        super().__init__()
        self.images: list[tuple[QImage, str, str]] = []
        self.on_drag = on_drag
        self.setMinimumSize(160, 120)
        opaque(self)

    def caption_height(self) -> int:
        """Lines enough for every caption across its column (captions wrap, never elide,
        never run into the next one): up to three."""
        metrics = self.fontMetrics()
        column = self.width() // max(len(self.images), 1)
        widths = [metrics.horizontalAdvance(c) + 8 for _, c, _ in self.images]
        lines = min(max([math.ceil(w / max(column, 1)) for w in widths] + [1]), 3)
        return max(self.CAPTION, metrics.height() * lines + 4)

    def cell(self) -> tuple[int, int]:
        n = max(len(self.images), 1)
        side = max(min(self.width() // n, self.height() - self.caption_height()), 16)
        return n, side

    def image_left(self, index: int) -> int:
        """Each image centred in its own column, so a caption may use the column's width."""
        n, side = self.cell()
        column = self.width() // n
        return index * column + (column - side) // 2

    def paintEvent(self, event) -> None:
        painter = QPainter(self)
        painter.fillRect(self.rect(), QColor(*BACKGROUND))
        n, side = self.cell()
        column = self.width() // n
        for index, (image, caption, color) in enumerate(self.images):
            left = self.image_left(index)
            if image.width() == side and image.height() == side:
                painter.drawImage(left, 0, image)
            else:
                painter.drawImage(QRect(left, 0, side, side), image)
            painter.setPen(QColor(color))
            painter.drawText(
                QRect(index * column + 4, side, column - 8, self.caption_height()),
                Qt.AlignmentFlag.AlignHCenter
                | Qt.AlignmentFlag.AlignTop
                | Qt.TextFlag.TextWordWrap,
                caption,
            )
        painter.end()

    def _drag(self, event) -> None:
        if self.on_drag is None or not self.images:
            return
        n, side = self.cell()
        x = event.position().x()
        index = min(max(int(x // max(self.width() // n, 1)), 0), n - 1)
        px, py = x - self.image_left(index), event.position().y()
        self.on_drag(2.0 * px / side - 1.0, 1.0 - 2.0 * py / side)

    def mousePressEvent(self, event) -> None:
        self._drag(event)

    def mouseMoveEvent(self, event) -> None:
        if event.buttons():
            self._drag(event)

"""Controls bound to the lab's settings (sliders, check boxes, menus) and a cheap live
text line: what the views' tool rows and the light panel are made of."""

from __future__ import annotations

from PyQt6.QtCore import QEvent, QSize, Qt
from PyQt6.QtGui import QColor, QPainter
from PyQt6.QtWidgets import (
    QCheckBox,
    QComboBox,
    QHBoxLayout,
    QLabel,
    QSizePolicy,
    QSlider,
    QWidget,
)

from lab import views
from lab.app.state import Settings


class LiveText(QWidget):
    """One line of text that changes often (values, status): a new text only repaints it.

    A QLabel asks its parents to lay themselves out again on every new text, which
    costs more than a whole frame's drawing; this keeps a fixed height. Where the text does
    not fit it shows `short`, or nothing if it is `optional` (a hint its tooltip repeats),
    and elides only as a last resort.
    """

    def __init__(
        self,
        text: str = "",
        width: int | None = None,
        align: Qt.AlignmentFlag = Qt.AlignmentFlag.AlignLeft,
        short: str | None = None,
        optional: bool = False,
    ):
        super().__init__()
        self._text, self.color, self.align, self.width_ = text, None, align, width
        self.short, self.optional = short, optional
        self._fit()

    def _fit(self) -> None:
        metrics = self.fontMetrics()
        if self.width_ is not None:
            self.setFixedSize(
                metrics.horizontalAdvance("0") * self.width_ + 4, metrics.height() + 4
            )
        else:
            self.setSizePolicy(QSizePolicy.Policy.Ignored, QSizePolicy.Policy.Fixed)
            self.setFixedHeight(metrics.height() + 4)

    def text(self) -> str:
        return self._text

    def painted(self) -> str:
        """The text as it shows in the widget's width now."""
        metrics, room = self.fontMetrics(), self.width() - 4
        for text in (self._text, self.short):
            if text is not None and metrics.horizontalAdvance(text) <= room:
                return text
        if self.optional:
            return ""
        return metrics.elidedText(self._text, Qt.TextElideMode.ElideRight, room)

    def setText(self, text: str, color: str | None = None) -> None:  # noqa: N802 (Qt style)
        if text != self._text or color != self.color:
            self._text, self.color = text, color
            self.update()

    def sizeHint(self) -> QSize:
        return QSize(self.fontMetrics().horizontalAdvance(self._text) + 4, self.height())

    def changeEvent(self, event) -> None:
        if event.type() == QEvent.Type.FontChange:
            self._fit()
        super().changeEvent(event)

    def paintEvent(self, event) -> None:
        painter = QPainter(self)
        if self.color:
            painter.setPen(QColor(self.color))
        rect = self.rect().adjusted(2, 0, -2, 0)
        painter.drawText(rect, self.align | Qt.AlignmentFlag.AlignVCenter, self.painted())
        painter.end()


def setting_label(name: str) -> str:
    """A setting's label from the view registry (its name when it has none)."""
    spec = views.all_settings().get(name)
    return (spec.label if spec is not None else "") or name


class SettingSlider(QWidget):
    """A labelled slider bound to one float setting (theta_i, phi_i, exposure, ...)."""

    def __init__(
        self, settings: Settings, name: str, label: str, low: float, high: float, step: float = 0.5
    ):
        super().__init__()
        self.settings, self.name, self.low, self.step = settings, name, low, step
        layout = QHBoxLayout(self)
        layout.setContentsMargins(0, 0, 0, 0)
        title = QLabel(label)
        layout.addWidget(title)
        self.slider = QSlider(Qt.Orientation.Horizontal)
        title.setBuddy(self.slider)
        self.slider.setAccessibleName(label)  # its value in words: _changed
        self.slider.setRange(0, round((high - low) / step))
        self.slider.setMinimumWidth(60)
        self.value_label = LiveText(width=5, align=Qt.AlignmentFlag.AlignRight)
        layout.addWidget(self.slider, 1)
        layout.addWidget(self.value_label)
        self.slider.valueChanged.connect(lambda pos: settings.set(name, low + pos * step))
        settings.changed.connect(self._changed)
        self._changed(name)

    @classmethod
    def of(cls, settings: Settings, name: str) -> SettingSlider:
        """The slider for a registered setting, with its label, range and step (lab/views)."""
        spec = views.all_settings()[name]
        return cls(settings, name, spec.label or name, spec.minimum, spec.maximum, spec.step)

    def _changed(self, name: str) -> None:
        if name != self.name:
            return
        value = float(self.settings[self.name])
        self.slider.blockSignals(True)
        self.slider.setValue(round((value - self.low) / self.step))
        self.slider.blockSignals(False)
        self.value_label.setText(f"{value:g}")
        # A screen reader reads the slider's position (0..180); the value, in its unit:
        unit = " degrees" if self.name.startswith(("theta", "phi")) else ""
        self.slider.setAccessibleDescription(f"{value:g}{unit}")


class SettingCheck(QCheckBox):
    """A check box bound to one bool setting."""

    def __init__(self, settings: Settings, name: str, label: str):
        super().__init__(label)
        self.setChecked(bool(settings[name]))
        self.toggled.connect(lambda on: settings.set(name, on))
        settings.changed.connect(
            lambda n: (
                n == name
                and self.isChecked() != settings[name]
                and self.setChecked(bool(settings[name]))
            )
        )


class SettingCombo(QComboBox):
    """A menu bound to one int setting (an index)."""

    def __init__(self, settings: Settings, name: str, items: tuple[str, ...]):
        super().__init__()
        self.addItems(items)
        self.setAccessibleName(setting_label(name))
        self.setCurrentIndex(int(settings[name]))
        self.currentIndexChanged.connect(lambda i: settings.set(name, i))
        settings.changed.connect(
            lambda n: (
                n == name
                and self.currentIndex() != settings[name]
                and self.setCurrentIndex(int(settings[name]))
            )
        )

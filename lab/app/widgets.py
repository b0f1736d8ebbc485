"""Controls generated from the shader headers: the models list and the parameter panel."""

from __future__ import annotations

import math
from html import escape

from PyQt6.QtCore import QEvent, QSize, Qt, pyqtSignal
from PyQt6.QtGui import QColor, QIcon, QPainter, QPixmap
from PyQt6.QtWidgets import (
    QCheckBox,
    QColorDialog,
    QComboBox,
    QFormLayout,
    QGridLayout,
    QHBoxLayout,
    QLabel,
    QLineEdit,
    QListWidget,
    QListWidgetItem,
    QPushButton,
    QSizePolicy,
    QSlider,
    QToolButton,
    QVBoxLayout,
    QWidget,
)

from lab import views
from lab.app.state import LabState, ModelState, Settings
from lab.models import ModelError, Param, model_names

STEPS = 1000  # slider resolution


def slider_position(param: Param, value: float) -> int:
    """Where `value` sits on the slider (linear or log, as the header says)."""
    low, high = param.minimum, param.maximum
    if param.scale == "log":
        t = (math.log(value) - math.log(low)) / (math.log(high) - math.log(low))
    else:
        t = (value - low) / (high - low)
    return round(min(max(t, 0.0), 1.0) * STEPS)


def slider_value(param: Param, position: int) -> float:
    t = position / STEPS
    low, high = param.minimum, param.maximum
    if param.scale == "log":
        return math.exp(math.log(low) + t * (math.log(high) - math.log(low)))
    return low + t * (high - low)


def format_number(value: float) -> str:
    return f"{value:.4g}"


def color_hex(rgb) -> str:
    return QColor.fromRgbF(*(min(max(c, 0.0), 1.0) for c in rgb)).name()


class ParamControl(QWidget):
    """One parameter's control row; writes through the ModelState, reads on refresh()."""

    def __init__(self, state: ModelState, param: Param):
        super().__init__()
        self.state = state
        self.param = param
        layout = QHBoxLayout(self)
        layout.setContentsMargins(0, 0, 0, 0)
        self.slider = self.text = self.check = self.combo = self.swatch = None
        if param.kind == "float":
            self.slider = QSlider(Qt.Orientation.Horizontal)
            self.slider.setRange(0, STEPS)
            self.slider.valueChanged.connect(self._from_slider)
            self.text = QLineEdit()
            self.text.setFixedWidth(70)
            self.text.editingFinished.connect(self._from_text)
            layout.addWidget(self.slider, 1)
            layout.addWidget(self.text)
        elif param.kind == "color":
            self.swatch = QPushButton()
            self.swatch.setFixedWidth(36)
            self.swatch.clicked.connect(self._pick_color)
            self.text = QLineEdit()
            self.text.editingFinished.connect(self._from_text)
            layout.addWidget(self.swatch)
            layout.addWidget(self.text, 1)
        elif param.kind == "bool":
            self.check = QCheckBox()
            self.check.toggled.connect(lambda on: self._set(on))
            layout.addWidget(self.check, 1)
        else:
            self.combo = QComboBox()
            self.combo.addItems(param.choices)
            self.combo.currentTextChanged.connect(lambda text: self._set(text))
            layout.addWidget(self.combo, 1)
        reset = QToolButton()
        reset.setText("↺")
        reset.setToolTip(f"reset {param.name} to its default")
        reset.clicked.connect(lambda: self.state.reset(param.name))
        layout.addWidget(reset)
        self.setToolTip(param.doc)
        self.refresh()

    def _set(self, value) -> None:
        try:
            self.state.set_value(self.param.name, value)
        except ModelError as err:
            self._reject(str(err))
            return
        if self.text is not None:
            self.text.setToolTip("")  # an old rejection no longer applies

    def _reject(self, reason: str) -> None:
        """Keep the old value and say why, in the status bar where the eye goes."""
        message = f"{self.state.label}: rejected — {reason}; kept {self.param.name} as it was"
        window = self.window()
        if hasattr(window, "statusBar"):
            window.statusBar().showMessage(message, 15000)
        if self.text is not None:
            self.text.setToolTip(message)
        self.refresh()

    def _from_slider(self, position: int) -> None:
        self._set(slider_value(self.param, position))

    def _from_text(self) -> None:
        try:
            value = self.param.parse(self.text.text())
        except ModelError as err:
            self._reject(str(err))
            return
        self._set(value)

    def _pick_color(self) -> None:
        color = QColorDialog.getColor(QColor(color_hex(self.state.values[self.param.name])), self)
        if color.isValid():
            self._set((color.redF(), color.greenF(), color.blueF()))

    def _show_text(self, text: str) -> None:
        if self.text.text() != text:
            self.text.setText(text)

    def refresh(self) -> None:
        """Show the state's value without echoing it back."""
        value = self.state.values[self.param.name]
        for widget in (self.slider, self.text, self.check, self.combo):
            if widget is not None:
                widget.blockSignals(True)
        # Only what changed is touched: a new style sheet re-polishes and lays out again.
        if self.param.kind == "float":
            if slider_value(self.param, self.slider.value()) != value:
                self.slider.setValue(slider_position(self.param, value))
            self._show_text(format_number(value))
        elif self.param.kind == "color":
            style = f"background: {color_hex(value)}"
            if self.swatch.styleSheet() != style:
                self.swatch.setStyleSheet(style)
            # A grey is one number (as typed): the box stays short enough for presenter fonts.
            grey = value[0] == value[1] == value[2]
            self._show_text(
                format_number(value[0]) if grey else ", ".join(map(format_number, value))
            )
        elif self.param.kind == "bool":
            self.check.setChecked(bool(value))
        else:
            self.combo.setCurrentText(value)
        for widget in (self.slider, self.text, self.check, self.combo):
            if widget is not None:
                widget.blockSignals(False)


class ParamPanel(QWidget):
    """The selected model's parameters, built from its header.

    The title takes one line; the formula folds out under it (and is the title's tooltip),
    so the sliders stay in view at 1280x800.
    """

    def __init__(self, lab: LabState):
        super().__init__()
        self.lab = lab
        self.controls: dict[str, ParamControl] = {}
        self.current: ModelState | None = None
        self.layout_ = QVBoxLayout(self)
        self.layout_.setContentsMargins(4, 4, 4, 4)
        self.layout_.setSpacing(4)
        header = QHBoxLayout()
        self.title = QLabel()
        self.title.setWordWrap(True)
        self.title.setTextFormat(Qt.TextFormat.RichText)
        header.addWidget(self.title, 1)
        self.formula_button = QToolButton()
        self.formula_button.setText("formula")
        self.formula_button.setCheckable(True)
        self.formula_button.setToolButtonStyle(Qt.ToolButtonStyle.ToolButtonTextBesideIcon)
        self.formula_button.setArrowType(Qt.ArrowType.RightArrow)
        self.formula_button.setToolTip("show the model's formula from its shader header")
        self.formula_button.toggled.connect(self._show_formula)
        header.addWidget(self.formula_button, 0, Qt.AlignmentFlag.AlignTop)
        self.layout_.addLayout(header)
        self.formula = QLabel()
        self.formula.setWordWrap(True)
        self.formula.setTextInteractionFlags(Qt.TextInteractionFlag.TextSelectableByMouse)
        self.formula.setStyleSheet("QLabel { background: palette(base); padding: 4px; }")
        self.formula.hide()
        self.layout_.addWidget(self.formula)
        self.form_host = QWidget()
        self.layout_.addWidget(self.form_host)
        self.layout_.addStretch(1)
        lab.selection_changed.connect(self.rebuild)
        self.rebuild()

    def _show_formula(self, shown: bool) -> None:
        self.formula_button.setArrowType(
            Qt.ArrowType.DownArrow if shown else Qt.ArrowType.RightArrow
        )
        self.formula.setVisible(shown and bool(self.formula.text()))

    def rebuild(self) -> None:
        if self.current is not None:
            try:
                self.current.changed.disconnect(self.refresh)
            except TypeError:
                pass
        self.current = self.lab.selected
        self.form_host.setParent(None)
        self.form_host = QWidget()
        form = QFormLayout(self.form_host)
        form.setContentsMargins(0, 0, 0, 0)
        form.setVerticalSpacing(3)
        self.controls = {}
        state = self.current
        if state is None:
            self.title.setText("No model: add one from the list above.")
            self.title.setToolTip("")
            self.formula.setText("")
        else:
            model = state.model
            formula = "<br>".join(escape(line) for line in model.formula)
            self.title.setText(f"<b>{escape(state.label)}</b> — {escape(model.title)}")
            self.title.setToolTip(f"<p style='white-space:pre'>{formula}</p>" if formula else "")
            self.formula.setText(f"<small>{formula}</small>" if formula else "")
            for param in model.params.values():
                control = ParamControl(state, param)
                label = QLabel(param.name)
                label.setToolTip(param.doc)
                form.addRow(label, control)
                self.controls[param.name] = control
            state.changed.connect(self.refresh)
        self.formula_button.setEnabled(bool(self.formula.text()))
        self._show_formula(self.formula_button.isChecked())
        self.layout_.insertWidget(2, self.form_host)

    def refresh(self) -> None:
        state = self.current
        if state is None:
            return
        if set(self.controls) != set(state.model.params):
            self.rebuild()  # the file was edited and its header changed
            return
        for control in self.controls.values():
            control.param = state.model.params[control.param.name]
            control.refresh()


class ModelList(QWidget):
    """Models in the lab: add, duplicate, remove, colour, visible (check box), solo."""

    open_file = pyqtSignal()

    def __init__(self, lab: LabState):
        super().__init__()
        self.lab = lab
        layout = QVBoxLayout(self)
        layout.setContentsMargins(0, 0, 0, 0)
        self.top = QGridLayout()
        self.library = QComboBox()
        self.library.addItems(model_names())
        add = QPushButton("Add")
        add.clicked.connect(self.add_selected)
        opener = QPushButton("Open…")
        opener.setToolTip(
            "open a model .glsl file or a BRDF Explorer .brdf file (watched), "
            "or a MERL .binary table (the measured model)"
        )
        opener.clicked.connect(self.open_file.emit)
        self.top.addWidget(self.library, 0, 0)
        self.top.addWidget(add, 0, 1)
        self.top.addWidget(opener, 0, 2)
        self.top.setColumnStretch(0, 1)
        self.top_widgets = (self.library, add, opener)
        layout.addLayout(self.top)
        self.list = QListWidget()
        self.list.setToolTip("tick: visible in the views; select: edit its parameters")
        self.list.setSizePolicy(QSizePolicy.Policy.Preferred, QSizePolicy.Policy.Fixed)
        self.list.currentRowChanged.connect(self._selected)
        self.list.itemChanged.connect(self._checked)
        layout.addWidget(self.list)
        self.buttons = QGridLayout()
        self.buttons.setSpacing(2)
        for text, slot, tip in (
            ("Duplicate", lambda: self._on_current(self.lab.duplicate), "a copy to vary"),
            ("Remove", lambda: self._on_current(self.lab.remove), "remove the model"),
            ("Solo", lambda: self._on_current(self.lab.set_solo), "show only this model"),
            ("Colour", self.pick_color, "the model's colour in every view"),
        ):
            button = QToolButton()
            button.setText(text)
            button.setToolTip(tip)
            button.setSizePolicy(QSizePolicy.Policy.Expanding, QSizePolicy.Policy.Fixed)
            button.clicked.connect(slot)
            self.buttons.addWidget(button, 0, self.buttons.count())
        layout.addLayout(self.buttons)
        self.shown: list[tuple] = []
        lab.models_changed.connect(self.rebuild)
        lab.changed.connect(self._update_labels)
        lab.selection_changed.connect(self._update_labels)

    def arrange(self, columns: int) -> None:
        """The Duplicate/Remove/Solo/Colour buttons in `columns` columns (2 when presenting,
        where four large labels would not fit one row of the narrow controls column)."""
        items = [self.buttons.itemAt(i).widget() for i in range(self.buttons.count())]
        for index, button in enumerate(items):
            self.buttons.removeWidget(button)
            self.buttons.addWidget(button, index // columns, index % columns)
        # The library menu gets a row of its own too, so that no model name is cut short.
        places = (
            [(0, 0, 1), (0, 1, 1), (0, 2, 1)] if columns >= 4 else [(0, 0, 2), (1, 0, 1), (1, 1, 1)]
        )
        for widget in self.top_widgets:
            self.top.removeWidget(widget)
        for widget, (row, column, span) in zip(self.top_widgets, places, strict=True):
            self.top.addWidget(widget, row, column, 1, span)
        self.top.setColumnStretch(0, 1 if columns >= 4 else 0)

    def add_selected(self) -> None:
        from lab.models import load_model

        self.lab.add(load_model(self.library.currentText()))

    def _on_current(self, action) -> None:
        if self.lab.selected is not None:
            action(self.lab.selected)

    def pick_color(self) -> None:
        state = self.lab.selected
        if state is not None:
            color = QColorDialog.getColor(QColor(state.color), self)
            if color.isValid():
                state.set_color(color.name())

    def rebuild(self) -> None:
        self.list.blockSignals(True)
        self.list.clear()
        for _ in self.lab.models:
            item = QListWidgetItem()
            item.setFlags(item.flags() | Qt.ItemFlag.ItemIsUserCheckable)
            self.list.addItem(item)
        self.list.blockSignals(False)
        self.shown = []
        self._update_labels()
        self.fit_rows()

    def fit_rows(self) -> None:
        """As tall as its rows (two to five of them): the parameters below stay in view."""
        rows = min(max(self.list.count(), 2), 5)
        height = self.list.sizeHintForRow(0) if self.list.count() else 0
        height = height if height > 0 else self.list.fontMetrics().height() + 4
        self.list.setFixedHeight(rows * height + 2 * self.list.frameWidth() + 2)

    def changeEvent(self, event) -> None:
        super().changeEvent(event)
        if event.type() == QEvent.Type.FontChange:
            self.fit_rows()

    def _update_labels(self) -> None:
        # Called on every change: the rows are rebuilt only when what they show changed.
        shown = [
            (s.label, s.color, s.visible, s.error, self.lab.solo is s, s is self.lab.selected)
            for s in self.lab.models
        ]
        if shown == self.shown and self.list.count() == len(shown):
            return
        self.shown = shown
        self.list.blockSignals(True)
        for row, state in enumerate(self.lab.models):
            item = self.list.item(row)
            if item is None:
                continue
            solo = "  [solo]" if self.lab.solo is state else ""
            error = "  ⚠ error" if state.error else ""
            item.setText(f"{state.label}{solo}{error}")
            pixmap = QPixmap(14, 14)
            pixmap.fill(QColor(state.color))
            item.setIcon(QIcon(pixmap))
            item.setCheckState(Qt.CheckState.Checked if state.visible else Qt.CheckState.Unchecked)
            if state is self.lab.selected and self.list.currentRow() != row:
                self.list.setCurrentRow(row)
        self.list.blockSignals(False)

    def _selected(self, row: int) -> None:
        if 0 <= row < len(self.lab.models):
            self.lab.select(self.lab.models[row])

    def _checked(self, item: QListWidgetItem) -> None:
        row = self.list.row(item)
        if 0 <= row < len(self.lab.models):
            self.lab.models[row].set_visible(item.checkState() == Qt.CheckState.Checked)


class LiveText(QWidget):
    """One line of text that changes often (values, status): a new text only repaints it.

    A QLabel asks its parents to lay themselves out again on every new text, which
    costs more than a whole frame's drawing; this keeps a fixed height and elides.
    """

    def __init__(
        self,
        text: str = "",
        width: int | None = None,
        align: Qt.AlignmentFlag = Qt.AlignmentFlag.AlignLeft,
    ):
        super().__init__()
        self._text, self.color, self.align, self.width_ = text, None, align, width
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
        text = self.fontMetrics().elidedText(self._text, Qt.TextElideMode.ElideRight, rect.width())
        painter.drawText(rect, self.align | Qt.AlignmentFlag.AlignVCenter, text)
        painter.end()


class SettingSlider(QWidget):
    """A labelled slider bound to one float setting (theta_i, phi_i, exposure, ...)."""

    def __init__(
        self, settings: Settings, name: str, label: str, low: float, high: float, step: float = 0.5
    ):
        super().__init__()
        self.settings, self.name, self.low, self.step = settings, name, low, step
        layout = QHBoxLayout(self)
        layout.setContentsMargins(0, 0, 0, 0)
        layout.addWidget(QLabel(label))
        self.slider = QSlider(Qt.Orientation.Horizontal)
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
        self.setCurrentIndex(int(settings[name]))
        self.currentIndexChanged.connect(lambda i: settings.set(name, i))
        settings.changed.connect(
            lambda n: (
                n == name
                and self.currentIndex() != settings[name]
                and self.setCurrentIndex(int(settings[name]))
            )
        )

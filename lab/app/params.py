"""The parameter panel: one control per parameter of the selected model, built from its
shader header (sliders linear or log as the header says, colours, switches, menus)."""

from __future__ import annotations

import math
from html import escape

from PyQt6.QtCore import QSize, Qt
from PyQt6.QtGui import QColor
from PyQt6.QtWidgets import (
    QCheckBox,
    QColorDialog,
    QComboBox,
    QFormLayout,
    QHBoxLayout,
    QLabel,
    QLineEdit,
    QPushButton,
    QSlider,
    QToolButton,
    QVBoxLayout,
    QWidget,
)

from lab.app.state import LabState, ModelState
from lab.constants import SLIDER_STEPS
from lab.models import ModelError, Param

STEPS = SLIDER_STEPS  # slider resolution, the page's too (lab/constants.py)


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


class TextBox(QLineEdit):
    """A line edit at least as wide as its text: a form wraps its row rather than cut it."""

    def minimumSizeHint(self) -> QSize:  # noqa: N802 (Qt style)
        hint = super().minimumSizeHint()
        need = self.fontMetrics().horizontalAdvance(self.text()) + 14  # frame and margins
        return QSize(max(hint.width(), need), hint.height())


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
            self.text = TextBox()
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
        reset.setAccessibleName(f"reset {param.name}")
        self.name_controls(param)
        reset.clicked.connect(lambda: self.state.reset(param.name))
        layout.addWidget(reset)
        self.setToolTip(param.doc)
        self.refresh()

    def name_controls(self, param: Param) -> None:
        """Names a screen reader says for each control, the parameter's meaning as their
        description (sighted users get it as the row's tooltip)."""
        names = {
            self.slider: param.name,
            self.text: f"{param.name} {'as r,g,b' if param.kind == 'color' else 'value'}",
            self.swatch: f"{param.name} colour: choose",
            self.check: param.name,
            self.combo: param.name,
        }
        for widget, name in names.items():
            if widget is not None:
                widget.setAccessibleName(name)
                widget.setAccessibleDescription(param.doc)

    def _set(self, value) -> None:
        try:
            self.state.set_value(self.param.name, value)
        except ModelError as err:
            self._reject(str(err))
            return
        if self.text is not None:
            self.text.setToolTip("")  # an old rejection no longer applies
            self.text.setAccessibleDescription(self.param.doc)

    def _reject(self, reason: str) -> None:
        """Keep the old value and say why, in the status bar where the eye goes."""
        message = f"{self.state.label}: rejected — {reason}; kept {self.param.name} as it was"
        window = self.window()
        if hasattr(window, "statusBar"):
            window.statusBar().showMessage(message, 15000)
        if self.text is not None:
            self.text.setToolTip(message)
            self.text.setAccessibleDescription(message)  # the error, tied to its field
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
            if isinstance(self.text, TextBox):
                self.text.updateGeometry()

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
            # Read as the value, not the slider's position (0..STEPS).
            self.slider.setAccessibleDescription(f"{format_number(value)}; {self.param.doc}")
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
        # A field too wide beside its label (presenter fonts) goes on a line of its own.
        form.setRowWrapPolicy(QFormLayout.RowWrapPolicy.WrapLongRows)
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

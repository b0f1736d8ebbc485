"""The models list: add from the library or a file, duplicate, remove, colour, show, solo."""

from __future__ import annotations

from PyQt6.QtCore import QEvent, Qt, pyqtSignal
from PyQt6.QtGui import QColor, QIcon, QPixmap
from PyQt6.QtWidgets import (
    QColorDialog,
    QComboBox,
    QGridLayout,
    QListWidget,
    QListWidgetItem,
    QPushButton,
    QSizePolicy,
    QToolButton,
    QVBoxLayout,
    QWidget,
)

from lab.app.state import LabState
from lab.models import model_names


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
        self.library.setAccessibleName("model to add from the library")
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
        self.list.setAccessibleName("models in the lab")
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

"""The lab's state: parameter objects with signals. Views listen; they own nothing.

A preset is this state written to a small TOML file; the format (and reading and writing
it without Qt) is in lab/presets.py, shipped presets in lab/app/presets/.
"""

from __future__ import annotations

import math
from pathlib import Path

from PyQt6.QtCore import QObject, pyqtSignal

from lab import presets, views
from lab.constants import MODEL_COLORS
from lab.models import Model, ModelError, Value
from lab.presets import (  # noqa: F401 (the app's modules import these from here)
    PRESET_DIR,
    dump_toml,
    load_any,
    read_preset,
    shipped_presets,
)

# The colour-blind safe colours first (six models apart for every reader), then more.
PALETTE = [*MODEL_COLORS, "#f032e6", "#bfef45", "#9a6324", "#a0a6b0"]


class ModelState(QObject):
    """One model in the list: its values, colour, visibility and (for files) its path."""

    changed = pyqtSignal()  # parameter values or code: the views redraw
    display_changed = pyqtSignal()  # colour, label, visibility

    def __init__(
        self,
        model: Model,
        values: dict | None = None,
        color: str = "#e6194b",
        label: str = "",
        from_file: bool = False,
    ):
        super().__init__()
        self.model = model
        self.values: dict[str, Value] = model.resolve(values or {})
        self.color = color
        self.label = label or presets.default_label(model)
        self.visible = True
        self.from_file = from_file
        self.error = ""  # the last compile error of a watched file ("" when it compiles)

    @property
    def source(self) -> str:
        """How presets refer to the model: its library name, its file or its table."""
        table = presets.table_path(self.model)
        if table is not None:
            return str(table)
        return str(self.model.path) if self.from_file else self.model.name

    def set_value(self, name: str, value: Value) -> None:
        value = self.model.params[name].check(value)
        if self.values.get(name) != value:
            self.values[name] = value
            self.changed.emit()

    def reset(self, name: str) -> None:
        self.set_value(name, self.model.params[name].default)

    def set_values(self, values: dict[str, Value]) -> None:
        self.values = self.model.resolve({**self.values, **values})
        self.changed.emit()

    def replace_model(self, model: Model) -> None:
        """A new version of the file: keep the values its parameters still accept."""
        kept = {}
        for name, value in self.values.items():
            if name in model.params:
                try:
                    kept[name] = model.params[name].check(value)
                except ModelError:
                    pass
        self.model = model
        self.values = model.resolve(kept)
        self.changed.emit()

    def set_color(self, color: str) -> None:
        self.color = color
        self.display_changed.emit()

    def set_visible(self, visible: bool) -> None:
        if self.visible != visible:
            self.visible = visible
            self.display_changed.emit()
            self.changed.emit()


class Settings(QObject):
    """Light and view settings: plain named values with one `changed(name)` signal."""

    changed = pyqtSignal(str)

    def __init__(self):
        super().__init__()
        # The light's and every registered view's settings (lab/views), at their defaults.
        self.values: dict[str, Value] = views.defaults()

    def __getitem__(self, name: str) -> Value:
        return self.values[name]

    def set(self, name: str, value: Value) -> None:
        if name not in self.values:
            raise KeyError(name)
        kind = type(self.values[name])
        value = kind(value)
        if isinstance(value, float) and not math.isfinite(value):
            return
        if self.values[name] != value:
            self.values[name] = value
            self.changed.emit(name)


class LabState(QObject):
    """The models in the list, which one is selected or solo, and the settings."""

    models_changed = pyqtSignal()  # added, removed or reordered
    selection_changed = pyqtSignal()
    changed = pyqtSignal()  # anything a view draws has changed

    def __init__(self):
        super().__init__()
        self.models: list[ModelState] = []
        self.settings = Settings()
        self.selected: ModelState | None = None
        self.solo: ModelState | None = None
        self.settings.changed.connect(lambda _name: self.changed.emit())

    def next_color(self) -> str:
        used = {m.color for m in self.models}
        free = [c for c in PALETTE if c not in used]
        return free[0] if free else PALETTE[len(self.models) % len(PALETTE)]

    def add(
        self,
        model: Model,
        values: dict | None = None,
        label: str = "",
        from_file: bool = False,
        color: str | None = None,
    ) -> ModelState:
        state = ModelState(model, values, color or self.next_color(), label, from_file)
        state.changed.connect(self.changed.emit)
        state.display_changed.connect(self.changed.emit)
        self.models.append(state)
        self.selected = state
        self.models_changed.emit()
        self.selection_changed.emit()
        self.changed.emit()
        return state

    def duplicate(self, state: ModelState) -> ModelState:
        return self.add(state.model, dict(state.values), f"{state.label} (copy)", state.from_file)

    def remove(self, state: ModelState) -> None:
        if state not in self.models:
            return
        self.models.remove(state)
        state.changed.disconnect()
        state.display_changed.disconnect()
        if self.solo is state:
            self.solo = None
        # A measured model's table texture goes when no other entry (a duplicate) shows it.
        release = getattr(state.model, "release", None)
        if release is not None and all(m.model is not state.model for m in self.models):
            release()
        if self.selected is state:
            self.selected = self.models[-1] if self.models else None
            self.selection_changed.emit()
        self.models_changed.emit()
        self.changed.emit()

    def clear(self) -> None:
        for state in list(self.models):
            self.remove(state)

    def select(self, state: ModelState | None) -> None:
        if state is not self.selected:
            self.selected = state
            self.selection_changed.emit()

    def set_solo(self, state: ModelState | None) -> None:
        self.solo = None if state is self.solo else state
        self.models_changed.emit()
        self.changed.emit()

    def visible_models(self) -> list[ModelState]:
        """The models the views draw: the solo one, or every visible one."""
        if self.solo is not None:
            return [self.solo]
        return [m for m in self.models if m.visible]

    # -- presets ------------------------------------------------------------------------
    def to_dict(self, base: Path | None = None) -> dict:
        """The state in the preset layout (lab/presets.py); paths relative to `base`."""
        models = [
            presets.model_entry(m.model, m.values, m.label, m.color, m.visible, m.from_file, base)
            for m in self.models
        ]
        return {"settings": dict(self.settings.values), "model": models}

    def from_dict(self, data: dict, base: Path | None = None, where: str = "preset") -> list[str]:
        """Replace the state with a preset's; raises ModelError naming what is wrong, and
        returns one message per setting that was clamped into its range."""
        entries = data.get("model", [])
        if not isinstance(entries, list):
            raise ModelError("'model' must be a list of [[model]] tables", where)
        # Everything is loaded and checked before anything changes.
        loaded = [
            (*presets.entry_model(entry, number, base, where), entry)
            for number, entry in enumerate(entries, start=1)
        ]
        raw = data.get("settings", {})
        settings = presets.check_settings(raw, where)
        notes = presets.clamped_notes(raw, settings, where)
        self.clear()
        # A preset names only some settings; the rest go back to their defaults so nothing
        # leaks from the previous preset.
        for name, value in {**views.defaults(), **settings}.items():
            self.settings.set(name, value)
        for model, values, from_file, entry in loaded:
            state = self.add(
                model,
                values,
                str(entry.get("label", "")),
                from_file,
                str(entry.get("color", "")) or None,
            )
            state.visible = bool(entry.get("visible", True))
        if self.models:
            self.select(self.models[0])
        self.changed.emit()
        return notes

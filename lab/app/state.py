"""The lab's state: parameter objects with signals. Views listen; they own nothing.

A preset is this state written to a small TOML file (see lab/app/presets/).
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

from PyQt6.QtCore import QObject, pyqtSignal

from lab.models import Model, ModelError, Value, load_model

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

PALETTE = ["#e6194b", "#3cb44b", "#4363d8", "#f58231", "#911eb4", "#42d4f4", "#f032e6",
           "#bfef45", "#9a6324", "#808000"]
PRESET_DIR = Path(__file__).parent / "presets"


def load_any(path_or_name: str | Path) -> Model:
    """A library model by name, a .glsl model file or a BRDF Explorer .brdf file."""
    if str(path_or_name).endswith(".brdf"):
        from lab.brdf_explorer import read_brdf

        return read_brdf(path_or_name)
    return load_model(path_or_name)


class ModelState(QObject):
    """One model in the list: its values, colour, visibility and (for files) its path."""

    changed = pyqtSignal()  # parameter values or code: the views redraw
    display_changed = pyqtSignal()  # colour, label, visibility

    def __init__(self, model: Model, values: dict | None = None, color: str = "#e6194b",
                 label: str = "", from_file: bool = False):
        super().__init__()
        self.model = model
        self.values: dict[str, Value] = model.resolve(values or {})
        self.color = color
        self.label = label or model.name
        self.visible = True
        self.from_file = from_file
        self.error = ""  # the last compile error of a watched file ("" when it compiles)

    @property
    def source(self) -> str:
        """How presets refer to the model: its library name or its file."""
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

    DEFAULTS: dict[str, Value] = {
        "theta_i": 30.0, "phi_i": 0.0,
        "exposure": 0.0, "gamma": 2.2, "multiply_cos": True,
        "polar_log": False, "polar_cos": False,
        "phi_d": 90.0,
        "shape": 0, "mode": 1, "lights": 3, "ambient": 0.03, "yaw": 0.6, "pitch": 0.5,
        "lobe_yaw": -0.6, "lobe_pitch": 0.35, "lobe_zoom": 1.0,
    }

    def __init__(self):
        super().__init__()
        self.values: dict[str, Value] = dict(self.DEFAULTS)

    def __getitem__(self, name: str) -> Value:
        return self.values[name]

    def set(self, name: str, value: Value) -> None:
        if name not in self.DEFAULTS:
            raise KeyError(name)
        kind = type(self.DEFAULTS[name])
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

    def add(self, model: Model, values: dict | None = None, label: str = "",
            from_file: bool = False, color: str | None = None) -> ModelState:
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

    # -- presets --------------------------------------------------------------------------
    def to_dict(self, base: Path | None = None) -> dict:
        models = []
        for m in self.models:
            source = m.source
            if m.from_file and base is not None:
                try:
                    source = str(Path(source).resolve().relative_to(base.resolve()))
                except ValueError:
                    pass
            models.append({
                "model": source, "label": m.label, "color": m.color, "visible": m.visible,
                "values": {k: list(v) if isinstance(v, tuple) else v for k, v in m.values.items()},
            })
        return {"settings": dict(self.settings.values), "model": models}

    def from_dict(self, data: dict, base: Path | None = None, where: str = "preset") -> None:
        """Replace the state with a preset's; raises ModelError naming what is wrong."""
        entries = data.get("model", [])
        if not isinstance(entries, list):
            raise ModelError("'model' must be a list of [[model]] tables", where)
        loaded = []
        for number, entry in enumerate(entries, start=1):
            if not isinstance(entry, dict) or "model" not in entry:
                raise ModelError(f"[[model]] number {number} has no 'model = NAME' line", where)
            source = str(entry["model"])
            if base is not None and (source.endswith(".glsl") or source.endswith(".brdf")):
                if not Path(source).is_absolute():
                    source = str(base / source)
            model = load_any(source)
            values = {k: tuple(v) if isinstance(v, list) else v
                      for k, v in dict(entry.get("values", {})).items()}
            model.resolve(values)  # check before changing anything
            loaded.append((model, values, entry, source != model.name))
        settings = dict(data.get("settings", {}))
        unknown = [k for k in settings if k not in Settings.DEFAULTS]
        if unknown:
            raise ModelError(f"unknown setting(s) {', '.join(unknown)}", where)
        self.clear()
        for name, value in settings.items():
            self.settings.set(name, value)
        for model, values, entry, from_file in loaded:
            state = self.add(model, values, str(entry.get("label", "")), from_file,
                             str(entry.get("color", "")) or None)
            state.visible = bool(entry.get("visible", True))
        if self.models:
            self.select(self.models[0])
        self.changed.emit()


# -- TOML files -----------------------------------------------------------------------------
def _toml_value(value) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (int, float)):
        return repr(value)  # exact, so a preset restores the same pixels
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(_toml_value(v) for v in value) + "]"
    if isinstance(value, str):
        escaped = value.replace("\\", "\\\\").replace('"', '\\"')
        return f'"{escaped}"'
    raise TypeError(f"cannot write {value!r} to TOML")


def dump_toml(data: dict) -> str:
    """Our preset dictionaries as TOML: top-level keys, tables and arrays of tables."""
    lines = []
    for key, value in data.items():
        if not isinstance(value, (dict, list)) or (isinstance(value, list) and value
                                                   and not isinstance(value[0], dict)):
            lines.append(f"{key} = {_toml_value(value)}")
    for key, value in data.items():
        if isinstance(value, dict):
            lines += ["", f"[{key}]"] + [f"{k} = {_toml_value(v)}" for k, v in value.items()]
        elif isinstance(value, list) and value and isinstance(value[0], dict):
            for table in value:
                lines += ["", f"[[{key}]]"]
                lines += [f"{k} = {_toml_value(v)}" for k, v in table.items()
                          if not isinstance(v, dict)]
                for k, v in table.items():
                    if isinstance(v, dict):
                        lines.append(f"[{key}.{k}]")
                        lines += [f"{a} = {_toml_value(b)}" for a, b in v.items()]
    return "\n".join(lines) + "\n"


def read_preset(path: str | Path) -> dict:
    """A preset file as a dictionary; a ModelError with the line for bad TOML."""
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except OSError as err:
        raise ModelError(f"cannot read the preset: {err.strerror}", path) from None
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as err:
        line = getattr(err, "lineno", None)
        raise ModelError(f"not valid TOML ({str(err).split(' (at')[0]})", path, line) from None


def shipped_presets() -> list[Path]:
    """The presets that come with the lab, in lecture order (by file name)."""
    return sorted(PRESET_DIR.glob("*.toml"))

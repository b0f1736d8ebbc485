"""Presets: the lab's state as a small TOML file, read and written without Qt.

The desktop app saves and opens these files, `brdf-lab fit` writes them, and the lab
ships its lecture demonstrations as presets in lab/app/presets/. Layout::

    # comments are allowed anywhere
    title = "Phong exponents"           # shown in the window title and Presets menu
    notes = "what to try"                # shown in the status bar
    views = ["sphere", "polar"]          # the views to show (others are hidden)
    layout = "sphere_polar"              # the focus layout presenter mode opens (LAYOUTS)

    [settings]                           # light and view settings (lab/views); others: defaults
    theta_i = 30.0

    [[model]]                            # one table per model, in list order
    model = "phong"                      # a library name, a .glsl/.brdf file or "measured"
    table = "gold.binary"                # measured only: the MERL .binary table
    label = "ke = 4"                     # optional: name in the list and legends
    color = "#e6194b"                    # optional: colour in every view
    visible = true                       # optional
    [model.values]                       # parameters by name; colours as [r, g, b]
    ke = 4.0

Relative file paths (.glsl, .brdf, .binary) are relative to the preset's folder.
"""

from __future__ import annotations

import os
import sys
from dataclasses import dataclass
from pathlib import Path

from lab import views
from lab.models import Model, ModelError, Value
from lab.sources import MEASURED, open_model

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

PRESET_DIR = Path(__file__).parent / "app" / "presets"
MODEL_FILES = (".glsl", ".brdf")


@dataclass(frozen=True)
class Layout:
    """An arrangement of the app's views. The desk shows every chosen view in a grid beside
    full controls (a laptop); a focus layout shows one or two views large beside compact
    controls, with plot text for the back row of a lecture hall (a projector)."""

    title: str
    views: tuple[str, ...] = ()  # () for the desk: the preset's (or every) view
    across: bool = False  # two views side by side (else the first above the second)
    shares: tuple[float, ...] = (1.0,)  # each view's share of the room

    @property
    def focus(self) -> bool:
        return bool(self.views)


# The spheres are a wide row of small pictures: they go above a second view, which gets
# most of the height. The 3D lobe and the object are square-ish: beside the spheres.
LAYOUTS = {
    "desk": Layout("Desk: every view, full controls"),
    "sphere_polar": Layout("Spheres and polar plot", ("sphere", "polar"), False, (0.36, 0.64)),
    "sphere_lobe3d": Layout("Spheres and 3D lobe", ("sphere", "lobe3d"), False, (0.36, 0.64)),
    "sphere_slice": Layout("Spheres and (θh, θd) slice", ("sphere", "slice"), False, (0.36, 0.64)),
    "sphere_albedo": Layout("Spheres and albedo", ("sphere", "albedo"), False, (0.36, 0.64)),
    "sphere_object": Layout("Spheres and object", ("sphere", "object"), False, (0.36, 0.64)),
    "polar_lobe3d": Layout("Polar plot and 3D lobe", ("polar", "lobe3d"), True, (0.55, 0.45)),
    "ibl": Layout("Image-based lighting alone", ("ibl",)),
}
DEFAULT_FOCUS = "sphere_polar"


def load_any(path_or_name: str | Path) -> Model:
    """A library model by name, a .glsl model file, a BRDF Explorer .brdf file or a
    MERL .binary table (as the `measured` model)."""
    if str(path_or_name) == MEASURED:
        raise ModelError("the measured model needs a table: open a MERL .binary file")
    return open_model(path_or_name)


def table_path(model: Model) -> Path | None:
    """The .binary file a measured model was read from (None for other models)."""
    table = getattr(model, "table", None)
    path = getattr(table, "path", None)
    return Path(path) if path is not None else None


def default_label(model: Model) -> str:
    """A model's name in the list: a measured model is named after its table file."""
    table = table_path(model)
    return table.stem if table is not None else model.name


def relative(path: str | Path, base: Path | None) -> str:
    """`path` relative to the folder `base` where that is possible, else as given."""
    if base is None:
        return str(path)
    try:
        return os.path.relpath(Path(path).resolve(), base.resolve())
    except ValueError:  # another drive (Windows)
        return str(path)


def plain_values(values: dict[str, Value]) -> dict:
    """Parameter values as TOML holds them (colours as lists)."""
    return {k: list(v) if isinstance(v, tuple) else v for k, v in values.items()}


def model_entry(
    model: Model,
    values: dict[str, Value],
    label: str = "",
    color: str = "",
    visible: bool = True,
    from_file: bool = False,
    base: Path | None = None,
) -> dict:
    """One [[model]] table for `model` (a measured model also gets its `table` path)."""
    entry: dict = {}
    table = table_path(model)
    if table is not None:
        entry["model"] = MEASURED
        entry["table"] = relative(table, base)
    elif from_file:
        entry["model"] = relative(model.path, base)
    else:
        entry["model"] = model.name
    if label:
        entry["label"] = label
    if color:
        entry["color"] = color
    entry["visible"] = bool(visible)
    entry["values"] = plain_values(values)
    return entry


def entry_model(
    entry: object, number: int, base: Path | None, where: str
) -> tuple[Model, dict[str, Value], bool]:
    """The model, checked values and whether it is a file, of one [[model]] table."""
    if not isinstance(entry, dict) or "model" not in entry:
        raise ModelError(f"[[model]] number {number} has no 'model = NAME' line", where)
    source = str(entry["model"])

    def local(path: str) -> str:
        return str(base / path) if base is not None and not Path(path).is_absolute() else path

    if source == MEASURED:
        if "table" not in entry:
            raise ModelError(
                f"[[model]] number {number} is measured but has no 'table = \"FILE.binary\"' line",
                where,
            )
        model: Model = open_model(MEASURED, local(str(entry["table"])))
    elif "table" in entry:
        raise ModelError(
            f"[[model]] number {number} has a table but model {source!r}: "
            f'only model = "{MEASURED}" reads a table',
            where,
        )
    else:
        if source.endswith(MODEL_FILES):
            source = local(source)
        model = load_any(source)
    raw = entry.get("values", {})
    if not isinstance(raw, dict):
        raise ModelError(
            f"[[model]] number {number}: 'values' must be a [model.values] table", where
        )
    values = {k: tuple(v) if isinstance(v, list) else v for k, v in raw.items()}
    model.resolve(values)  # check before anyone changes state
    return model, values, source.endswith(MODEL_FILES)


def check_settings(settings: object, where: str) -> dict[str, Value]:
    if not isinstance(settings, dict):
        raise ModelError("'settings' must be a [settings] table", where)
    known = views.all_settings()
    unknown = [k for k in settings if k not in known]
    if unknown:
        raise ModelError(
            f"unknown setting(s) {', '.join(unknown)}; known: {', '.join(known)}", where
        )
    # Wrong types are errors naming the setting; numbers outside a range are clamped.
    return {name: known[name].check(name, value, where) for name, value in settings.items()}


# -- TOML files -----------------------------------------------------------------------------
def _toml_value(value) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (int, float)):
        return repr(value)  # exact, so a preset restores the same pixels
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(_toml_value(v) for v in value) + "]"
    if isinstance(value, str):
        escaped = value.replace("\\", "\\\\").replace('"', '\\"').replace("\n", "\\n")
        return f'"{escaped}"'
    raise TypeError(f"cannot write {value!r} to TOML")


def dump_toml(data: dict) -> str:
    """Our preset dictionaries as TOML: top-level keys, tables and arrays of tables."""
    lines = []
    for key, value in data.items():
        if not isinstance(value, (dict, list)) or (
            isinstance(value, list) and value and not isinstance(value[0], dict)
        ):
            lines.append(f"{key} = {_toml_value(value)}")
    for key, value in data.items():
        if isinstance(value, dict):
            lines += ["", f"[{key}]"] + [f"{k} = {_toml_value(v)}" for k, v in value.items()]
        elif isinstance(value, list) and value and isinstance(value[0], dict):
            for table in value:
                lines += ["", f"[[{key}]]"]
                lines += [
                    f"{k} = {_toml_value(v)}" for k, v in table.items() if not isinstance(v, dict)
                ]
                for k, v in table.items():
                    if isinstance(v, dict):
                        lines.append(f"[{key}.{k}]")
                        lines += [f"{a} = {_toml_value(b)}" for a, b in v.items()]
    return "\n".join(lines) + "\n"


def write_preset(data: dict, path: str | Path, comment: str = "") -> Path:
    """Write a preset dictionary; `comment` becomes '# ' lines at the top."""
    path = Path(path)
    head = "".join(f"# {line}\n" for line in comment.splitlines())
    try:
        path.write_text(head + dump_toml(data), encoding="utf-8")
    except OSError as err:
        raise ModelError(f"cannot write the preset: {err.strerror}", path) from None
    return path


def read_preset(path: str | Path) -> dict:
    """A preset file as a dictionary; a ModelError with the line for bad TOML."""
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except OSError as err:
        raise ModelError(f"cannot read the preset: {err.strerror}", path) from None
    except UnicodeDecodeError:
        raise ModelError("not a text file: a preset is TOML", path) from None
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as err:
        line = getattr(err, "lineno", None)
        raise ModelError(f"not valid TOML ({str(err).split(' (at')[0]})", path, line) from None
    shown = data.get("views", [])
    known = [v.name for v in views.all_views()]
    if not isinstance(shown, list) or not all(isinstance(name, str) for name in shown):
        raise ModelError(f"'views' must be a list of view names: {', '.join(known)}", path)
    unknown = [name for name in shown if name not in known]
    if unknown:
        raise ModelError(f"unknown view(s) {', '.join(unknown)}; known: {', '.join(known)}", path)
    layout = data.get("layout", DEFAULT_FOCUS)
    if layout not in LAYOUTS:
        raise ModelError(
            f"unknown layout {layout!r}; write one of {', '.join(map(repr, LAYOUTS))}", path
        )
    return data


def shipped_presets() -> list[Path]:
    """The presets that come with the lab, in lecture order (by file name)."""
    return sorted(PRESET_DIR.glob("*.toml"))


def clamped_notes(raw: dict, checked: dict[str, Value], where: str) -> list[str]:
    """One line per number that check_settings clamped into its range (shown to the user)."""
    return [
        f"{where}: setting {name} = {raw[name]!r} is outside its range; using {value!r}"
        for name, value in checked.items()
        if not isinstance(value, bool) and raw[name] != value
    ]

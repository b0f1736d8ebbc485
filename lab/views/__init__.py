"""The registry of views: every front end (CLI, app, presets, web page, tests) reads it.

A view is one module in this package (or in a package added with `add_package`) that
defines `VIEW = ViewSpec(...)`: its name and title, its settings with defaults and ranges,
where its dock goes in the app, its Qt widget and, where it has one, its PNG plot. Its
GLSL template sits beside the others in shaders/views/. Adding a view is then that module,
its template and its widget; the CLI's --view choices, the app's docks, the presets'
settings and the web page's manifest pick it up from here.
"""

from __future__ import annotations

import importlib
import math
import pkgutil
from collections.abc import Callable
from dataclasses import dataclass, field

from lab.models import ModelError, Value


@dataclass(frozen=True)
class Setting:
    """One light or view setting: its default (which fixes its type), range and label."""

    default: Value
    minimum: float | None = None
    maximum: float | None = None
    label: str = ""
    step: float = 1.0  # a slider's step
    choices: tuple[str, ...] = ()  # for an int setting picked from a menu
    unit: str = ""  # what its value is shown with ("°")
    doc: str = ""  # what it means, for a control's tooltip (the web page's)

    def check(self, name: str, value: object, where: str = "") -> Value:
        """`value` as this setting's type, clamped to its range; ModelError if it is not one."""
        kind = type(self.default)

        def wrong(what: str) -> ModelError:
            return ModelError(f"setting {name} = {value!r}: {what}", where or None)

        if kind is bool:
            if not isinstance(value, bool):
                raise wrong("write true or false")
            return value
        if isinstance(value, bool) or not isinstance(value, int | float):
            raise wrong(f"expected a number (default {self.default!r})")
        if not math.isfinite(value):
            raise wrong("expected a finite number")
        if self.choices and (value != int(value) or not 0 <= value < len(self.choices)):
            raise wrong(
                "choose one of " + ", ".join(f"{i} ({c})" for i, c in enumerate(self.choices))
            )
        if kind is int and value != int(value):
            raise wrong("expected a whole number")
        low = -math.inf if self.minimum is None else self.minimum
        high = math.inf if self.maximum is None else self.maximum
        return kind(min(max(value, low), high))


@dataclass
class PlotJob:
    """What `brdf-lab render` asks of a view's PNG plot."""

    renderer: object  # lab.render.Renderer
    model: object  # lab.models.Model
    values: dict
    theta_i: float
    phi_i: float
    out: object  # path of the PNG
    size: int = 512
    exposure: float = 0.0
    lights: list | None = None  # lab.render.Light, for views that take several
    ambient: tuple[float, float, float] = (0.0, 0.0, 0.0)
    warnings: list[str] = field(default_factory=list)  # what the user must hear of (NaN pixels)


@dataclass(frozen=True)
class ViewSpec:
    """What the lab needs to know of a view."""

    name: str
    title: str
    settings: dict[str, Setting] = field(default_factory=dict)
    # The app's dock area ("right" or "bottom") and row there: views of a row sit side by side.
    dock: tuple[str, int] = ("right", 1)
    tab_of: str = ""  # another view's name: share its dock as a tab behind it (heavy views)
    # Its share of its row's width, and its row's share of the window's height (a row takes
    # the largest of its views'), when the window lays the docks out.
    size: tuple[float, float] = (0.33, 0.3)
    short_title: str = ""  # what a dock too narrow for the title calls it
    widget: str = ""  # "module:Class" of its Qt widget (imported only by the app)
    plot: Callable[[PlotJob], None] | None = None  # its PNG for `render --view` (None: app only)
    order: int = 100  # position in menus and docks
    # Constants its web page module reads (the manifest's "data"): written here once.
    page_data: dict = field(default_factory=dict)

    def widget_class(self):
        module, _, name = self.widget.partition(":")
        return getattr(importlib.import_module(module), name)


# The light is not a view's: every view reads it.
LIGHT = {
    "theta_i": Setting(30.0, 0.0, 90.0, "θi", 0.5, unit="°"),
    "phi_i": Setting(0.0, 0.0, 360.0, "φi", 0.5, unit="°"),
}

_PACKAGES = ["lab.views"]
_cache: list[ViewSpec] | None = None
_files: dict[str, str] = {}  # view name -> the file of the module that declares it


def add_package(package: str) -> None:
    """Also collect the views of `package` (a plug-in, or a test's own views)."""
    global _cache
    if package not in _PACKAGES:
        _PACKAGES.append(package)
    _cache = None


def all_views() -> list[ViewSpec]:
    """Every registered view, in order."""
    global _cache
    if _cache is None:
        found: dict[str, ViewSpec] = {}
        for package in _PACKAGES:
            root = importlib.import_module(package)
            for info in pkgutil.iter_modules(root.__path__):
                module = importlib.import_module(f"{package}.{info.name}")
                spec = getattr(module, "VIEW", None)
                if isinstance(spec, ViewSpec):
                    if spec.name in found:
                        raise ValueError(f"two views are named {spec.name!r}")
                    found[spec.name] = spec
                    _files[spec.name] = module.__file__
        _cache = sorted(found.values(), key=lambda v: (v.order, v.name))
        owners: dict[str, str] = {}
        for spec in _cache:  # a setting belongs to one view; others may read it
            for name in spec.settings:
                if name in owners or name in LIGHT:
                    raise ValueError(f"setting {name!r} is declared by {owners.get(name)} too")
                owners[name] = spec.name
    return _cache


def view(name: str) -> ViewSpec:
    for spec in all_views():
        if spec.name == name:
            return spec
    raise KeyError(name)


def module_file(name: str) -> str:
    """The file of the Python module that declares view `name` (its page module may sit
    beside it: lab/web/site.py)."""
    all_views()
    return _files[name]


def plot_views() -> list[str]:
    """The views `brdf-lab render --view` can write as PNG."""
    return [v.name for v in all_views() if v.plot is not None]


def all_settings() -> dict[str, Setting]:
    """The light's settings and every view's."""
    merged = dict(LIGHT)
    for spec in all_views():
        merged.update(spec.settings)
    return merged


def defaults() -> dict[str, Value]:
    return {name: s.default for name, s in all_settings().items()}


def setting_kind(setting: Setting) -> str:
    """ "bool", "int" or "float": what a front end parses the setting as."""
    return type(setting.default).__name__


def manifest() -> list[dict]:
    """The views for the web page's manifest: each view's name, titles, order and settings
    (default, range, step, label, choices and kind), which the page builds its view list,
    controls, defaults and address keys from. A view the page can draw also names its page
    module (lab/web/site.py adds "page")."""
    return [
        {
            "name": v.name,
            "title": v.title,
            "short_title": v.short_title or v.title,
            "order": v.order,
            "data": v.page_data,
            "settings": {
                name: {
                    "default": s.default,
                    "min": s.minimum,
                    "max": s.maximum,
                    "step": s.step,
                    "label": s.label,
                    "choices": list(s.choices),
                    "kind": setting_kind(s),
                    "unit": s.unit,
                    "doc": s.doc,
                }
                for name, s in v.settings.items()
            },
        }
        for v in all_views()
    ]

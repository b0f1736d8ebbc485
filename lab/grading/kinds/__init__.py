"""Check kinds: one class per kind of graded check, and the registry that lists them.

A kind owns everything about its checks, in five parts:

- inputs: the keys of its `[[checks]]` table in exercise.toml (`parse`, `fields`; every
  kind also reads `ranges`, the parameter ranges hidden mode draws from, and `purpose`,
  what its lights are for: spec.PURPOSES, see `purpose_of`), the direction pairs it
  evaluates (`angles`) and the model hidden mode draws its parameters from (`params_model`);
- render: what it renders from a model (`render`), stored as (`stored`), and where a
  stopped loop was (`where`);
- compare: the verdict against the reference, with tolerance and message (`compare`,
  `differs`);
- reference: how its reference is saved and read back (`save_reference`, `load_reference`);
- report: its HTML figures (`figures`), its explanation of a failure (`nearest`,
  `explain`) and its entry in the web page's practice mode (`practice`).

Each module of this package (and of any package given to `add_package`) that defines
`KIND = SomeKind()` is registered under `KIND.name`; exercise.toml's `kind = "..."` picks
it. A new kind is one module: the grader, references, reports and explanations read it
from here, with no other edit.
"""

from __future__ import annotations

import base64
import functools
import html
import importlib
import pkgutil
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from lab.grading.result import CheckResult
from lab.grading.spec import (
    Check,
    ExerciseError,
    parse_lights,
    parse_purpose,
    parse_ranges,
    parse_same,
)
from lab.grading.tables import bound, made_here, parse_table
from lab.grading.visuals import difference_legend, polar_svg

if TYPE_CHECKING:
    from lab.models import Model
    from lab.render import Renderer

VALUES_FILE = "values.npz"  # every kind's values-type references, one array per check


class CheckKind:
    """The base of every check kind; subclasses override what differs.

    `exercise` arguments are lab.grading.exercise.Exercise (not imported: it imports this).
    """

    name = ""
    order = 100  # position in listings (built-in kinds first)
    fields: dict[str, Any] = {}  # the keys this kind adds to its table, with their defaults
    diagnose_terms = False  # explanations evaluate the exercise's declared terms alone
    # What `purpose` names the purpose of: "lights" (one per light), "theta_i" (the check's
    # light at theta_i, phi_i) or "" (the kind draws its own directions: no purpose).
    purpose_of = "theta_i"

    def __init_subclass__(cls, **kwargs: Any) -> None:
        """Each kind's `render` draws the model bound to the check's `table`, if it names one
        (lab.grading.tables): every kind reads tables with no code of its own."""
        super().__init_subclass__(**kwargs)
        own = cls.__dict__.get("render")
        if own is not None and not getattr(own, "binds_tables", False):

            @functools.wraps(own)
            def render(self, renderer, model, check, _own=own):
                return _own(self, renderer, bound(renderer, model, check), check)

            render.binds_tables = True  # type: ignore[attr-defined]
            cls.render = render
        practice = cls.__dict__.get("practice")
        if practice is not None and not getattr(practice, "binds_tables", False):

            @functools.wraps(practice)
            def practise(self, exercise, check, values, _own=practice):
                # The page makes a check's table itself (static/tables.js); the grader's is
                # made here too, for the tolerances it gives (tables.spread). No OpenGL here:
                # the check is the grader's alone.
                return _own(self, exercise, check, values) if made_here(check) else None

            practise.binds_tables = True  # type: ignore[attr-defined]
            cls.practice = practise

    # -- inputs ------------------------------------------------------------------------------
    def parse(self, table: dict, where: str) -> Check:
        """A Check from its table in exercise.toml (the exercise's defaults merged in, `kind`
        taken out); raises ExerciseError, KeyError or TypeError saying what is wrong."""
        table = dict(table)
        lights = parse_lights(table.pop("lights", [[45.0, 0.0]]), where)
        ambient = tuple(float(c) for c in table.pop("ambient", (0.0, 0.0, 0.0)))
        params = {
            k: tuple(v) if isinstance(v, list) else v for k, v in table.pop("params", {}).items()
        }
        options = {
            key: self._option(table, key, default, where) for key, default in self.fields.items()
        }
        here = f"{where}: check {table.get('name', '?')}"
        ranges = parse_ranges(table.pop("ranges", {}), here)
        same = parse_same(table.pop("same", []), here)
        tabled = parse_table(table.pop("table", []), here)
        purpose: tuple[str, ...] = ()
        if "purpose" in table:
            count = {"lights": len(lights), "theta_i": 1}.get(self.purpose_of, 0)
            if not count:
                raise ExerciseError(
                    f"{here}: a {self.name} check draws its own directions; remove `purpose`"
                )
            purpose = parse_purpose(table.pop("purpose"), count, here)
        check = Check(
            kind=self.name,
            lights=lights,
            ambient=ambient,
            params=params,
            options=options,
            purpose=purpose,
            ranges=ranges,
            same=same,
            table=tabled,
            **table,
        )
        self.validate(check, where)
        return check

    @staticmethod
    def _option(table: dict, key: str, default: Any, where: str) -> Any:
        value = table.pop(key, default)
        want = type(default)
        ok = isinstance(value, want) and not (isinstance(value, bool) and want is not bool)
        if want is float and isinstance(value, int) and not isinstance(value, bool):
            value, ok = float(value), True
        if not ok:
            what = {bool: "true or false", int: "a whole number", float: "a number"}
            raise ExerciseError(
                f"{where}: check {table.get('name', '?')}: {key} = {value!r} should be "
                f"{what.get(want, 'a ' + want.__name__)} (for example {key} = {default!r})"
            )
        return value

    def validate(self, check: Check, where: str) -> None:
        """Reject settings this kind cannot grade with (ExerciseError); nothing by default."""

    def params_model(self, check: Check, model: Model) -> Model:
        """The model whose header hidden mode draws this check's parameters from (and checks
        its `ranges` against): the exercise's solution `model`, unless the kind runs the
        student's code on another model (exercise 11's tests of a target BRDF)."""
        return model

    def portable(self, exercise, model: Model) -> Model:
        """The program the web page compiles the student's file as on its own (what the
        GLSL ES portability check compiles): the submission itself, unless the kind links
        the file with models of its own."""
        return model

    def angles(self, check: Check) -> np.ndarray | None:
        """(n, 4) rows theta_i, phi_i, theta_o, phi_o in degrees, or None (not pairs)."""
        return None

    # -- render --------------------------------------------------------------------------
    def render(self, renderer: Renderer, model: Model, check: Check) -> np.ndarray:
        """The raw float output of `model` for this check."""
        raise NotImplementedError(f"check kind {self.name} renders nothing")

    def stored(self, raw: np.ndarray, check: Check) -> np.ndarray:
        """What is stored as the reference (and compared by explanations): values as they are."""
        return raw.astype(np.float32)

    def where(self, check: Check, x: int, y: int) -> str:
        """The input at pixel (x, y) of the render, in words (where a loop was stopped)."""
        angles = self.angles(check)
        if angles is None:
            return f"pixel ({x}, {y})"
        row = angles[min(y * min(len(angles), 1024) + x, len(angles) - 1)]
        return "(θi, φi, θo, φo) = ({:.1f}°, {:.1f}°, {:.1f}°, {:.1f}°)".format(*row)

    # -- compare -------------------------------------------------------------------------
    def compare(self, check: Check, expected: np.ndarray, raw: np.ndarray) -> CheckResult:
        """The verdict on the student's raw render against the stored reference."""
        raise NotImplementedError(f"check kind {self.name} compares nothing")

    def differs(self, check: Check, values: np.ndarray, reference: np.ndarray) -> bool:
        """Would these stored-form values fail the check against the reference?"""
        return not np.allclose(values, reference, rtol=check.rtol, atol=check.atol)

    # -- reference -----------------------------------------------------------------------
    def save_reference(
        self, exercise, check: Check, reference: np.ndarray, values: dict
    ) -> list[Path]:
        """Keep the reference: by default in `values` (written to references/values.npz);
        returns the files written apart from that."""
        values[check.name] = reference
        return []

    def load_reference(self, exercise, check: Check) -> np.ndarray:
        """The committed reference (OSError or KeyError where there is none)."""
        with np.load(exercise.references / VALUES_FILE) as data:
            return data[check.name]

    # -- report --------------------------------------------------------------------------
    captions: dict[str, str] = {}  # report captions of the result's images, by their label
    alts: dict[str, str] = {}  # their text alternatives (default: the label)

    def figures(self, result: CheckResult) -> list[str]:
        """HTML <figure> elements for the report's section of this check: the result's
        images (a passed check leaves out its difference images) and polar curve."""
        out = []
        for label, data in result.images.items():
            if result.passed and label in ("difference", "failing pixels"):
                continue
            uri = "data:image/png;base64," + base64.b64encode(data).decode()
            legend = difference_legend(result.threshold) if label == "difference" else ""
            alt = html.escape(self.alts.get(label, label))
            out.append(
                f'<figure><img src="{uri}" alt="{alt}"><figcaption>'
                f"{html.escape(self.captions.get(label, label))}</figcaption>{legend}</figure>"
            )
        if result.curve:
            out.append(f"<figure>{polar_svg(result.curve, result.failing)}</figure>")
        return out

    def nearest(
        self, check: Check, got: np.ndarray, expected: np.ndarray, candidates: dict
    ) -> str | None:
        """The known mistake (a key of `candidates`, stored-form values) the student's
        values match, or None."""
        return None

    # -- hidden mode: likely wrong programs rendered now, at the check's random settings ----
    by_program = False  # live values describe the program, not this check (one match each)
    confirm_elsewhere = False  # a match must hold at the other checks' settings (cheap renders)

    def live_values(self, renderer: Renderer, model: Model, check: Check) -> np.ndarray:
        """What hidden mode compares of a likely wrong program and the student's, rendered
        at the check's settings: by default the check's own values (stored form)."""
        return self.stored(self.render(renderer, model, check), check)

    def live_same(self, check: Check, values: np.ndarray, other: np.ndarray) -> bool:
        """Do two programs' live values agree (as far as this check can tell)?"""
        return not self.differs(check, values, other)

    def live_match(
        self, check: Check, mine: np.ndarray, solution: np.ndarray, candidates: dict
    ) -> str | None:
        """The candidate whose live values the student's match (of those that fail)."""
        failing = {k: v for k, v in candidates.items() if self.differs(check, v, solution)}
        return self.nearest(check, mine, solution, failing)

    def explain(
        self, explainer, exercise, check: Check, model: Model, expected, got, live: bool
    ) -> str:
        """What else the evidence says about a failure (a phrase, or ''), when no known
        mistake matched; `explainer` is the worker's lab.grading.explain.Explainer."""
        return ""

    def practice(self, exercise, check: Check, values) -> dict | None:
        """What the web page's practice mode needs beyond the check's settings, or None
        when the page cannot run this kind (it is then left out there)."""
        return None


# -- the registry -----------------------------------------------------------------------------
_PACKAGES = ["lab.grading.kinds"]
_cache: dict[str, CheckKind] | None = None
_UNKNOWN = CheckKind()  # reports of a kind this process does not know: generic sections


def add_package(package: str) -> None:
    """Also collect the kinds of `package` (a plug-in, or a test's own kinds)."""
    global _cache
    if package not in _PACKAGES:
        _PACKAGES.append(package)
    _cache = None


def remove_package(package: str) -> None:
    global _cache
    if package in _PACKAGES[1:]:
        _PACKAGES.remove(package)
    _cache = None


def packages() -> list[str]:
    """The packages kinds are collected from (the grading workers collect the same)."""
    return list(_PACKAGES)


def use_packages(names: list[str]) -> None:
    for name in names:
        add_package(name)


def all_kinds() -> dict[str, CheckKind]:
    """Every registered kind by name, in order."""
    global _cache
    if _cache is None:
        found: dict[str, CheckKind] = {}
        for package in _PACKAGES:
            root = importlib.import_module(package)
            for info in pkgutil.iter_modules(root.__path__):
                kind = getattr(importlib.import_module(f"{package}.{info.name}"), "KIND", None)
                if isinstance(kind, CheckKind):
                    if kind.name in found and found[kind.name] is not kind:
                        raise ValueError(f"two check kinds are named {kind.name!r}")
                    found[kind.name] = kind
        _cache = dict(sorted(found.items(), key=lambda item: (item[1].order, item[0])))
    return _cache


def names() -> tuple[str, ...]:
    return tuple(all_kinds())


def find(name: str) -> CheckKind | None:
    return all_kinds().get(name)


def kind_of(check: Check | CheckResult) -> CheckKind:
    """The kind of a check or result; a result of a kind unknown here gets generic parts."""
    kind = find(check.kind)
    if kind is None:
        if isinstance(check, Check):
            raise ExerciseError(f"check {check.name}: kind {check.kind!r} is not one of {names()}")
        return _UNKNOWN
    return kind

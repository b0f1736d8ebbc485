"""A check as `exercise.toml` declares it, and the error for a broken exercise folder.

The bottom of the grading package: the check kinds (lab.grading.kinds) read these, and
lab.grading.exercise builds on them.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING

if TYPE_CHECKING:  # lab.render (numpy, moderngl) loads only where lights are read
    from lab.render import Light


class ExerciseError(ValueError):
    """A broken exercise folder (instructor side): a usage error."""


@dataclass
class Check:
    """One graded check of an exercise, as `exercise.toml` declares it."""

    name: str
    kind: str  # a registered check kind: probe | sphere | polar | ...
    points: float
    params: dict = field(default_factory=dict)
    view: str = "sphere"
    lights: list[Light] = field(default_factory=list)
    ambient: tuple[float, float, float] = (0.0, 0.0, 0.0)
    size: int = 128
    theta_i: float = 45.0
    phi_i: float = 0.0
    pairs: int = 256
    seed: int = 1
    rtol: float = 2e-3
    atol: float = 1e-4
    threshold: float = 5.0  # per channel, in 1/255 after tone mapping
    max_fraction: float = 0.001
    options: dict = field(default_factory=dict)  # the keys a kind adds (CheckKind.fields)
    # What each light is for (one of PURPOSES per light, or for a polar check's light):
    # hidden mode draws new directions within it. Empty: inferred from the committed one.
    purpose: tuple[str, ...] = ()
    # Ranges hidden mode draws parameters from, where the header's whole range would make
    # this check meaningless or numerically extreme: {name: (low, high)}.
    ranges: dict = field(default_factory=dict)
    # Groups of parameters that hidden mode draws once and shares (an isotropic check's
    # alpha_x and alpha_y): [["alpha_x", "alpha_y"]].
    same: tuple[tuple[str, ...], ...] = ()
    # The exercise's model in lab.reference and its header's defaults (set on loading,
    # with_reference): the value kinds measure how well-conditioned each row is with them.
    model: str = ""
    defaults: dict = field(default_factory=dict)
    # Tables the check binds (lab.grading.tables.TableSpec, from its `table` key): a model
    # tabulated by the grader; hidden mode picks one and draws its parameters.
    table: tuple = ()


# Light directions by what they are for: the polar angle in degrees from the view axis (a
# sphere's lights) or from the normal (a polar check's light). Hidden mode draws within.
PURPOSES: dict[str, tuple[float, float]] = {
    "front": (10.0, 70.0),  # lit from the viewer's side, the usual setting
    "highlight": (15.0, 60.0),  # the mirror highlight well inside the sphere or curve
    "grazing": (75.0, 88.0),  # a light near the horizon or the sphere's terminator
    "below": (95.0, 115.0),  # just behind the horizon: N.L < 0 over most of the sphere
    "back": (120.0, 170.0),  # behind the object: a rim light
}


def infer_purpose(theta: float) -> str:
    """The purpose of a light at `theta` degrees, for checks that do not declare one."""
    if theta >= 120.0:
        return "back"
    if theta > 90.0:
        return "below"
    if theta >= 75.0:
        return "grazing"
    return "front"


def parse_purpose(raw, count: int, where: str) -> tuple[str, ...]:
    """`purpose = "grazing"` or one name per light, validated against PURPOSES."""
    names = [raw] if isinstance(raw, str) else raw
    if not isinstance(names, list) or not all(isinstance(n, str) for n in names):
        raise ExerciseError(f"{where}: purpose is a name or a list of names, one per light")
    for name in names:
        if name not in PURPOSES:
            raise ExerciseError(
                f"{where}: purpose {name!r} is not one of {', '.join(PURPOSES)}; it says "
                "what a light is for, so hidden mode draws its direction within that class"
            )
    if len(names) != count:
        raise ExerciseError(
            f"{where}: purpose names {len(names)} lights but the check has {count}; give one "
            "name per light, in the order of `lights`"
        )
    return tuple(names)


def parse_ranges(raw, where: str) -> dict[str, tuple[float, float]]:
    """`ranges = { ke = [1, 200] }`: the parameter ranges hidden mode draws from."""
    if not isinstance(raw, dict):
        raise ExerciseError(f"{where}: ranges is a table, for example ranges = {{ ke = [1, 200] }}")
    out = {}
    for name, pair in raw.items():
        ok = isinstance(pair, list) and len(pair) == 2
        ok = ok and all(isinstance(x, (int, float)) and not isinstance(x, bool) for x in pair)
        if not ok or pair[0] > pair[1]:
            raise ExerciseError(
                f"{where}: ranges.{name} = {pair!r} should be [low, high] with low <= high "
                f"(for example {name} = [1, 200])"
            )
        out[name] = (float(pair[0]), float(pair[1]))
    return out


def parse_same(raw, where: str) -> tuple[tuple[str, ...], ...]:
    """`same = [["alpha_x", "alpha_y"]]`: parameters hidden mode keeps equal."""
    flat = isinstance(raw, list) and raw and all(isinstance(x, str) for x in raw)
    groups = [raw] if flat else raw
    ok = isinstance(groups, list) and all(
        isinstance(g, list) and len(g) >= 2 and all(isinstance(n, str) for n in g) for g in groups
    )
    if not ok:
        raise ExerciseError(
            f'{where}: same is a list of parameter groups, for example same = [["alpha_x", '
            '"alpha_y"]]: hidden mode draws one value for each group'
        )
    return tuple(tuple(g) for g in groups)


def parse_lights(raw, where: str) -> list[Light]:
    """[[theta, phi], [theta, phi, [r, g, b]], ...] from exercise.toml."""
    from lab.render import Light

    lights = []
    for item in raw:
        if not isinstance(item, list) or len(item) not in (2, 3):
            raise ExerciseError(f"{where}: each light is [theta, phi] or [theta, phi, [r, g, b]]")
        rgb = tuple(float(c) for c in item[2]) if len(item) == 3 else (1.0, 1.0, 1.0)
        lights.append(Light(float(item[0]), float(item[1]), rgb))
    return lights


def with_reference(checks: list[Check], model: str, stub, wrapper: str | None) -> list[Check]:
    """The checks with the exercise's reference model and its header's defaults (`stub`:
    the student file's path, whose header holds them unless `wrapper` names the library
    model that does); unchanged where the header cannot be read."""
    from lab.models import ModelError, load_model, parse_model

    try:
        header = load_model(wrapper) if wrapper else parse_model(stub.read_text("utf-8"), stub)
    except (OSError, ModelError, UnicodeDecodeError):
        return checks
    defaults = {name: param.default for name, param in header.params.items()}
    return [replace(c, model=c.model or model, defaults=defaults) for c in checks]

"""Checks that read a tabulated BRDF: a check's `table` key, the table the grader makes from
it, and the model bound to that table while the check renders.

`table = { model = "ggx", params = { alpha = 0.2 } }` in a [[checks]] table tells the grader
to tabulate a library model in the MERL layout (lab.measured.tabulate, the same function as
`brdf-lab tabulate`) and bind the table as a 3D float texture (texel (phi_d, theta_d, theta_h),
RGB f_r; lab.measured.model, the texture the lab's `measured` model reads) to the uniform
`uniform` of the student's file and of the solution alike. A list of such tables lets hidden
mode pick one of them; each draws its parameters in its own `ranges`.

Every kind gets this without code of its own: CheckKind.render is wrapped (kinds/__init__.py)
so that the model it draws is `bound` to the check's table first.
"""

from __future__ import annotations

import math
import zlib
from collections import OrderedDict
from dataclasses import dataclass
from typing import Any

import numpy as np

from lab.grading.spec import ExerciseError
from lab.measured.merl import MERL_DIMS, TABLE_UNIFORM
from lab.models import Model, ModelError, load_model, model_names

UNIFORM = TABLE_UNIFORM  # the sampler a table is bound to unless the check says otherwise
KEYS = ("model", "params", "ranges", "noise", "dims", "uniform")
_CACHE = 3  # tables kept per process (about 50 MB each at the MERL size: data and texture)


@dataclass(frozen=True)
class TableSpec:
    """One table a check reads: which model is tabulated, with what, and where it is bound."""

    model: str
    params: tuple = ()  # sorted (name, value) pairs
    ranges: tuple = ()  # sorted (name, (low, high)) pairs: hidden mode draws within
    noise: float = 0.0  # relative error per bin (lab.measured.tabulate: a hash, nearly Gaussian)
    dims: tuple[int, int, int] = MERL_DIMS
    uniform: str = UNIFORM

    def values(self) -> dict[str, Any]:
        return dict(self.params)


def _frozen(value: Any) -> Any:
    return tuple(float(v) for v in value) if isinstance(value, list) else value


def parse_table(raw: Any, where: str) -> tuple[TableSpec, ...]:
    """`table = {...}` or `table = [{...}, ...]` from a [[checks]] table, validated against
    the tabulated model's header: ExerciseError saying what to write otherwise."""
    if raw is None or raw == []:
        return ()
    entries = raw if isinstance(raw, list) else [raw]
    out = []
    for number, entry in enumerate(entries, 1):
        here = f"{where}: table" + (f" {number}" if len(entries) > 1 else "")
        if not isinstance(entry, dict):
            raise ExerciseError(
                f'{here}: write a table such as {{ model = "ggx", params = {{ alpha = 0.2 }} }}'
            )
        unknown = [k for k in entry if k not in KEYS]
        if unknown:
            raise ExerciseError(f"{here}: no key {unknown[0]!r}; its keys are {', '.join(KEYS)}")
        name = entry.get("model")
        if not isinstance(name, str) or name not in model_names():
            raise ExerciseError(
                f"{here}: model = {name!r} should name a library model to tabulate, one of "
                f"{', '.join(model_names())}"
            )
        header = load_model(name).params
        params = entry.get("params", {})
        ranges = entry.get("ranges", {})
        for key, table in (("params", params), ("ranges", ranges)):
            if not isinstance(table, dict):
                raise ExerciseError(f"{here}: {key} should be a table, e.g. {{ alpha = 0.2 }}")
            for pname in table:
                if pname not in header:
                    raise ExerciseError(
                        f"{here}: {key} names {pname!r}, which is no parameter of {name} "
                        f"(its header declares {', '.join(header)})"
                    )
        try:
            load_model(name).resolve({k: _frozen(v) for k, v in params.items()})
        except (ModelError, TypeError, ValueError) as err:
            raise ExerciseError(f"{here}: params: {err}") from None
        for pname, pair in ranges.items():
            p = header[pname]
            ok = isinstance(pair, list) and len(pair) == 2
            ok = ok and all(isinstance(x, (int, float)) and not isinstance(x, bool) for x in pair)
            if not ok or not p.minimum <= pair[0] <= pair[1] <= p.maximum:
                raise ExerciseError(
                    f"{here}: ranges.{pname} = {pair!r} should be [low, high] within the "
                    f"header's range [{p.minimum:g}, {p.maximum:g}]"
                )
        noise = entry.get("noise", 0.0)
        if not isinstance(noise, (int, float)) or isinstance(noise, bool) or not 0 <= noise < 1:
            raise ExerciseError(f"{here}: noise = {noise!r} should be a number in [0, 1)")
        dims = entry.get("dims", list(MERL_DIMS))
        if not (
            isinstance(dims, list)
            and len(dims) == 3
            and all(isinstance(n, int) and 2 <= n <= 256 for n in dims)
        ):
            raise ExerciseError(
                f"{here}: dims = {dims!r} should be three whole numbers 2 to 256, the bins of "
                "(theta_h, theta_d, phi_d), e.g. [90, 90, 180]"
            )
        uniform = entry.get("uniform", UNIFORM)
        if not isinstance(uniform, str) or not uniform.isidentifier():
            raise ExerciseError(f"{here}: uniform = {uniform!r} should be a GLSL name")
        out.append(
            TableSpec(
                model=name,
                params=tuple(sorted((k, _frozen(v)) for k, v in params.items())),
                ranges=tuple(sorted((k, (float(a), float(b))) for k, (a, b) in ranges.items())),
                noise=float(noise),
                dims=tuple(dims),
                uniform=uniform,
            )
        )
    return tuple(out)


def hidden(specs: tuple[TableSpec, ...], seed: int) -> tuple[TableSpec, ...]:
    """Hidden mode: one of the check's tables, its `ranges` parameters drawn anew.

    The draw depends on the seed and the tables only (not their noise), so the checks of one
    seed that name the same tables read one model with the same parameters."""
    if not specs:
        return specs
    # Keyed on the tables less their noise: checks that read one model with and without
    # noise read the same draw (and the grader draws its values on the GPU once).
    plain = tuple(TableSpec(**{**vars(s), "noise": 0.0}) for s in specs)
    rng = np.random.default_rng([seed, zlib.crc32(repr(plain).encode())])
    spec = specs[int(rng.integers(len(specs)))]
    header = load_model(spec.model).params
    params = dict(spec.params)
    for name, (low, high) in spec.ranges:
        param = header[name]
        if param.kind == "color":
            params[name] = tuple(float(c) for c in rng.uniform(low, high, 3))
        elif param.scale == "log" and low > 0.0:
            params[name] = float(math.exp(rng.uniform(math.log(low), math.log(high))))
        else:
            params[name] = float(rng.uniform(low, high))
    params_drawn = tuple(sorted(params.items()))
    return (TableSpec(spec.model, params_drawn, (), spec.noise, spec.dims, spec.uniform),)


def describe(specs: tuple[TableSpec, ...]) -> str:
    """The table a check read, in words (hidden mode's report says which was drawn)."""
    if not specs:
        return ""
    spec = specs[0]
    values = ", ".join(
        f"{k}=({', '.join(f'{c:.3g}' for c in v)})"
        if isinstance(v, tuple)
        else f"{k}={v:.4g}"
        if isinstance(v, float)
        else f"{k}={v}"
        for k, v in spec.params
    )
    noise = f", noise {100 * spec.noise:g}%" if spec.noise else ""
    return f"{spec.model} ({values or 'its defaults'}{noise})"


# -- the tables, made on the GPU once per process -----------------------------------------------
_tables: OrderedDict[tuple, Any] = OrderedDict()  # key -> lab.measured MeasuredModel
_smooth: OrderedDict[tuple, np.ndarray] = OrderedDict()  # noise-free values at the bins


def measured(renderer, spec: TableSpec):
    """The lab's `measured` model holding `spec`'s table, made as `tabulate` makes it (its two
    steps: the noise-free values, drawn on the GPU once per model and parameters, then the
    noise), once per process."""
    from lab.measured.model import measured_model
    from lab.measured.tabulate import bin_values, measure

    key = _key(spec)
    found = _tables.get(key)
    if found is None:
        plain = key[:2] + key[3:]
        if plain not in _smooth:
            _smooth[plain] = bin_values(spec.model, spec.values(), spec.dims, renderer)
            while len(_smooth) > _CACHE:
                _smooth.popitem(last=False)
        _smooth.move_to_end(plain)
        found = _tables[key] = measured_model(measure(_smooth[plain], spec.dims, spec.noise))
        while len(_tables) > _CACHE:
            _tables.popitem(last=False)[1].release()
    _tables.move_to_end(key)
    return found


def _key(spec: TableSpec) -> tuple:
    return (spec.model, spec.params, spec.noise, spec.dims)


_here: list = []  # the renderer made_here() draws tables with, made at its first call


def made_here(check) -> bool:
    """Makes the check's table in this process (the web page's exercises.json: its value
    checks carry the grader's tolerances, which spread() reads from the table; the page
    makes the table itself, static/tables.js); False where no OpenGL is to be had."""
    specs = getattr(check, "table", ())
    if not specs or _key(specs[0]) in _tables:
        return True  # made already: no GL call (a server answers in threads of its own)
    try:
        if not _here:
            from lab.render import Renderer

            _here.append(Renderer())
        measured(_here[0], specs[0])
    except Exception:  # noqa: BLE001 - no GL context (moderngl's errors have no common base)
        return False
    return True


def bound(renderer, model: Model, check) -> Model:
    """`model` bound to the check's table (the first of its `table` list: hidden mode has
    drawn one already); the model itself where the check reads no table."""
    specs = getattr(check, "table", ())
    if not specs:
        return model
    from lab.measured.model import with_table

    spec = specs[0]
    return with_table(model, measured(renderer, spec), spec.uniform)


# How far a correct float32 program may place a pair's angles (radians): GLSL leaves acos
# and asin's precision to the driver, and Mesa's llvmpipe (the grader's) is off by up to
# 1.6e-4 (acos) and 3.9e-4 (asin) in mid-range, against 3e-6 for atan. theta_h's first
# bins are ten thousand times narrower than that, so there the allowance is relative (what
# atan keeps; acos(N.H) loses the peak's bins to the cosine's rounding, a mistake the
# handout teaches) plus float32's absolute error.
ANGLE = 4e-4
THETA_H_RELATIVE = 4e-4
THETA_H_ABSOLUTE = 2e-6
SPREAD_GROW = 2.0


def spread(check, angles: np.ndarray) -> np.ndarray | None:
    """(n, 3) how far a correct program's trilinear lookup of the check's table may be from
    the exact one at each row (degrees theta_i, phi_i, theta_o, phi_o): the lookup's change
    when each of theta_h, theta_d and phi_d moves by what float32 arithmetic and the driver's
    inverse trigonometry may move it. None where the check reads no table or the table has
    not been made yet (the grader makes it when it renders the check)."""
    specs = getattr(check, "table", ())
    if not specs:
        return None
    spec = specs[0]
    found = _tables.get(_key(spec))
    if found is None or found.table is None:
        return None
    from lab import reference
    from lab.measured.merl import continuous_index, half_diff, interpolate

    theta = np.radians(np.asarray(angles, dtype=np.float64))
    L = reference.direction(theta[:, 0], theta[:, 1])
    V = reference.direction(theta[:, 2], theta[:, 3])
    rgb = np.maximum(found.table.rgb, 0.0)
    exact = list(half_diff(L, V))
    base = interpolate(rgb, continuous_index(*exact, spec.dims), spec.dims)
    moves = (THETA_H_RELATIVE * exact[0] + THETA_H_ABSOLUTE, ANGLE, ANGLE)
    out = np.zeros_like(base)
    for axis, move in enumerate(moves):
        change = np.zeros_like(base)
        for sign in (1.0, -1.0):
            moved = list(exact)
            moved[axis] = moved[axis] + sign * move
            if axis < 2:  # theta below 0 is theta 0 (phi_d wraps)
                moved[axis] = np.maximum(moved[axis], 0.0)
            value = interpolate(rgb, continuous_index(*moved, spec.dims), spec.dims)
            change = np.maximum(change, np.abs(value - base))
        out += change
    below = (L[:, 2] <= 0.0) | (V[:, 2] <= 0.0)
    out[below] = 0.0
    return SPREAD_GROW * out

"""The exercise format: every key of `exercise.toml` and `mistakes.toml`, in one table.

Each key has a type, a default and a meaning, and for checks the kinds that read it. The
same table validates a file when the grader loads it (an unknown key, a wrong type or a
key its check kind ignores stops with the file, the line and what to write instead) and
writes the format reference, docs/exercise-format.md (`python -m lab.grading.schema`,
kept in sync by tests/test_schema.py).
"""

from __future__ import annotations

import difflib
import re
import sys
from dataclasses import dataclass
from typing import Any

from lab.constants import LOOP_LIMIT
from lab.grading.spec import PURPOSES, ExerciseError

REQUIRED = "(required)"
DEFAULT_API = ["PI", "INV_PI", "EPS"]  # terms/common.glsl's constants


def _number(v) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool)


def _numbers(v, n: int | None = None) -> bool:
    return isinstance(v, list) and all(_number(x) for x in v) and (n is None or len(v) == n)


def _light(v) -> bool:
    if not isinstance(v, list) or len(v) not in (2, 3) or not all(_number(x) for x in v[:2]):
        return False
    return len(v) == 2 or _numbers(v[2], 3)


def _param_value(v) -> bool:
    return _number(v) or isinstance(v, (bool, str)) or _numbers(v, 3)


# type name -> (test, how to write it)
TYPES: dict[str, tuple[Any, str]] = {
    "string": (lambda v: isinstance(v, str), 'text in quotes, e.g. "probe.grey"'),
    "integer": (lambda v: isinstance(v, int) and not isinstance(v, bool), "a whole number"),
    "number": (_number, "a number, e.g. 2.0"),
    "boolean": (lambda v: isinstance(v, bool), "true or false"),
    "strings": (
        lambda v: isinstance(v, list) and all(isinstance(x, str) for x in v),
        'a list of strings, e.g. ["PI", "INV_PI"]',
    ),
    "rgb": (lambda v: _numbers(v, 3), "three numbers, e.g. [0.2, 0.2, 0.2]"),
    "params": (
        lambda v: isinstance(v, dict) and all(_param_value(x) for x in v.values()),
        "a table of header parameters, e.g. { kd = [0.5, 0.5, 0.5], ke = 20.0 }",
    ),
    "ranges": (
        lambda v: isinstance(v, dict) and all(_numbers(x, 2) for x in v.values()),
        "a table of [low, high] pairs, e.g. { ke = [1.0, 200.0] }",
    ),
    "lights": (
        lambda v: isinstance(v, list) and all(_light(x) for x in v),
        "a list of [theta, phi] or [theta, phi, [r, g, b]], e.g. [[35.0, 210.0, [2.0, 2.0, 2.0]]]",
    ),
    "purpose": (
        lambda v: (
            isinstance(v, str) or (isinstance(v, list) and all(isinstance(x, str) for x in v))
        ),
        'a name or a list of names, one per light, e.g. ["highlight"]',
    ),
    "same": (
        lambda v: (
            isinstance(v, list)
            and (
                all(isinstance(x, str) for x in v)
                or all(isinstance(g, list) and all(isinstance(x, str) for x in g) for g in v)
            )
        ),
        'a list of parameter groups, e.g. [["alpha_x", "alpha_y"]]',
    ),
    "views": (
        lambda v: isinstance(v, list) and all(_numbers(x, 2) for x in v),
        "a list of [theta, phi] in degrees, e.g. [[10.0, 0.0], [70.0, 130.0]]",
    ),
    "edits": (
        lambda v: (
            isinstance(v, list)
            and len(v) > 0
            and all(
                isinstance(e, list) and len(e) == 2 and all(isinstance(s, str) for s in e)
                for e in v
            )
        ),
        "a list of ['old text', 'new text'] pairs, e.g. [['kd * INV_PI', 'kd']]",
    ),
    "table": (lambda v: isinstance(v, dict), "a table, e.g. [defaults] or { ... }"),
    "tabulated": (
        lambda v: (
            isinstance(v, dict) or (isinstance(v, list) and all(isinstance(x, dict) for x in v))
        ),
        'a model to tabulate or a list of them, e.g. { model = "ggx", params = { alpha = 0.2 }, '
        "ranges = { alpha = [0.1, 0.5] }, noise = 0.02 }",
    ),
    "tables": (
        lambda v: isinstance(v, list) and all(isinstance(x, dict) for x in v),
        "an array of tables: one [[checks]] or [[mistake]] header per entry",
    ),
}


@dataclass(frozen=True)
class Key:
    """One key of the format."""

    name: str
    type: str  # a key of TYPES
    default: Any  # REQUIRED, None (unset) or the value used when the key is left out
    meaning: str
    kinds: tuple[str, ...] = ()  # built-in kinds that read it; () for every kind


EXERCISE: tuple[Key, ...] = (
    Key("title", "string", REQUIRED, "the exercise's title in reports and listings"),
    Key("student_file", "string", REQUIRED, "the GLSL file the student edits, in the folder"),
    Key("functions", "strings", [], "GLSL signatures the student file must define"),
    Key("api", "strings", DEFAULT_API, "library names the student may call (others refused)"),
    Key("wrapper", "string", None, "a library model that calls the student's term functions"),
    Key("replaces", "string", None, "the library term file the student file stands in for"),
    Key("sampler_for", "string", None, "a library model whose BRDF sampler the student writes"),
    Key(
        "estimator",
        "boolean",
        False,
        "with sampler_for: the student writes the model's Monte Carlo estimate of the "
        "reflection equation (estimate_radiance), not its sampler",
    ),
    Key("loop_limit", "integer", LOOP_LIMIT, "loop iterations per invocation (nested: all passes)"),
    Key("defaults", "table", {}, "check keys merged into every [[checks]] table"),
    Key("checks", "tables", REQUIRED, "the graded checks, one [[checks]] table each"),
)

IMAGES = ("sphere", "object")  # the kinds that render a lit image and compare its pixels
CHECK: tuple[Key, ...] = (
    Key("name", "string", REQUIRED, "unique name, shown to students (e.g. probe.grey)"),
    Key("kind", "string", REQUIRED, "the check kind: probe, sphere, polar, ... (see below)"),
    Key("points", "number", REQUIRED, "points the check is worth"),
    Key("params", "params", {}, "header parameters set for the check; others keep defaults"),
    Key("ranges", "ranges", {}, "hidden mode draws these parameters within [low, high]"),
    Key("purpose", "purpose", None, "what each light is for; hidden mode draws within it"),
    Key("same", "same", [], "parameter groups hidden mode draws one value for (isotropy)"),
    Key(
        "table",
        "tabulated",
        [],
        "a library model the grader tabulates (MERL layout) and binds as a sampler3D (see below)",
    ),
    Key(
        "pairs",
        "integer",
        256,
        "random direction pairs (probe: plus 18 special ones)",
        ("probe", "properties", "bin_edges", "sh"),
    ),
    Key(
        "seed",
        "integer",
        1,
        "fixes the random directions or samples",
        ("probe", "chi_square", "pdf_integral", "ibl_render", "properties", "bin_edges")
        + ("object", "sh"),
    ),
    Key(
        "rtol",
        "number",
        2e-3,
        "relative tolerance of each value",
        ("probe", "polar", "properties", "bin_edges", "sh"),
    ),
    Key(
        "atol",
        "number",
        1e-4,
        "absolute tolerance of each value",
        ("probe", "polar", "properties", "bin_edges", "sh"),
    ),
    Key(
        "theta_i",
        "number",
        45.0,
        "polar angle of the light, degrees from the normal",
        ("polar", "chi_square", "pdf_integral", "ibl_render"),
    ),
    Key(
        "phi_i",
        "number",
        0.0,
        "azimuth of the light, degrees",
        ("polar", "chi_square", "pdf_integral", "ibl_render"),
    ),
    Key("view", "string", "sphere", "the grading template the sphere is drawn with", ("sphere",)),
    Key("lights", "lights", [[45.0, 0.0]], "theta, phi (degrees) and RGB per light", IMAGES),
    Key("ambient", "rgb", [0.0, 0.0, 0.0], "ambient light colour", ("sphere",)),
    Key("size", "integer", 128, "image side in pixels", ("sphere", "ibl_render", "object")),
    Key("threshold", "number", 5.0, "per-channel difference allowed, in 1/255", IMAGES),
    Key("max_fraction", "number", 0.001, "share of pixels allowed past threshold", IMAGES),
)

# The keys each built-in kind adds (CheckKind.fields), in words.
FIELD_MEANINGS: dict[tuple[str, str], str] = {
    ("chi_square", "views"): "extra view directions [theta, phi] the sampler is tested at",
    ("chi_square", "samples"): "samples per view (1000 to 4000000)",
    ("chi_square", "alpha"): "significance of the test over all views (0 to 0.5)",
    ("pdf_integral", "views"): "extra view directions [theta, phi] the pdf is integrated at",
    ("pdf_integral", "tolerance"): "allowed distance of the pdf's integral from 1 (0 to 0.5)",
    ("pdf_integral", "samples"): "quadrature samples per view",
    ("ibl_render", "samples"): "samples per pixel of the graded render",
    ("ibl_render", "converged"): "samples per pixel of the converged reference",
    ("ibl_render", "environment"): "the procedural environment map lit with",
    ("ibl_render", "factor"): "how much noisier than the solution the render may be (>= 1)",
    ("ibl_render", "alpha"): "significance of the noise test (0 to 0.1)",
    ("properties", "target"): "the model tested: a library model or a .glsl file in the folder",
    ("properties", "albedo_rows"): "viewing angles directional_albedo is run at (1 to 64)",
    ("properties", "grazing_rows"): "how many of them lie between 80 and 88 degrees",
    ("sh", "target"): "the library model whose lobe sh_coefficient projects; unset: sh_basis",
    ("sh", "order"): "the highest band l of the harmonics checked (0 to 8)",
    ("sh", "incidences"): "light directions the lobe is projected at (1 to 16)",
    ("object", "shape"): "the lit object: torus, sphere, rounded box or bumpy sphere",
    ("object", "yaw"): "the object's turn about the vertical, degrees (hidden mode draws it)",
    ("object", "pitch"): "its tilt towards the viewer, degrees",
    ("object", "textures"): "sampler2D name = PNG file in the folder; hidden mode generates them",
}

MISTAKE: tuple[Key, ...] = (
    Key("edits", "edits", REQUIRED, "text edits of the solution, each applied once, in order"),
    Key("hint", "string", REQUIRED, "what the student is told when their values match"),
)
TERM: tuple[Key, ...] = (
    Key("define", "strings", [], "macros that make other functions neutral, e.g. 'F(a) 1.0'"),
    Key("within", "string", "", "the term this one is a factor of (e.g. specular)"),
)
MISTAKES_TOP: tuple[Key, ...] = (
    Key("mistake", "tables", [], "the known mistakes, one [[mistake]] table each"),
    Key("terms", "table", {}, "terms shown alone: name = { parameter settings }"),
)


def kind_keys(kind) -> list[Key]:
    """The keys a kind adds to its checks (its `fields`), typed from their defaults."""
    types = {bool: "boolean", int: "integer", float: "number", str: "string", list: "views"}
    return [
        Key(
            key,
            types.get(type(default), "table"),
            default,
            FIELD_MEANINGS.get((kind.name, key), f"read by the {kind.name} kind (see its module)"),
            (kind.name,),
        )
        for key, default in kind.fields.items()
    ]


# -- where a key is written: line numbers of a TOML file --------------------------------------
class Lines:
    """Line numbers of the keys in a TOML text: (section, index, key) -> line."""

    _HEADER = re.compile(r"^\s*(\[\[?)\s*([\w.]+)\s*\]\]?")
    _KEY = re.compile(r"^\s*([\w-]+)\s*=")

    def __init__(self, text: str) -> None:
        self.found: dict[tuple[str, int, str], int] = {}
        self.tables: dict[tuple[str, int], int] = {}
        section, counts = "", {}
        for number, line in enumerate(text.splitlines(), 1):
            header = self._HEADER.match(line)
            if header:
                section = header.group(2)
                counts[section] = counts.get(section, -1) + 1 if header.group(1) == "[[" else 0
                self.tables[(section, counts[section])] = number
                continue
            key = self._KEY.match(line)
            if key:
                self.found.setdefault((section, counts.get(section, 0), key.group(1)), number)

    def line(self, section: str, index: int, key: str | None = None) -> int:
        if key is not None and (section, index, key) in self.found:
            return self.found[(section, index, key)]
        return self.tables.get((section, index), 1)


def _close(word: str, known) -> str:
    near = difflib.get_close_matches(word, list(known), n=1, cutoff=0.6)
    return f" (did you mean {near[0]!r}?)" if near else ""


def check_keys(table: dict, keys: list[Key], where: str, what: str, place) -> None:
    """Unknown keys and wrong types in `table` -> ExerciseError with the line.

    `place(key)` gives the line of a key; `what` names the table in the message."""
    known = {k.name: k for k in keys}
    for name, value in table.items():
        key = known.get(name)
        if key is None:
            raise ExerciseError(
                f"{where}:{place(name)}: {what} has no key {name!r}{_close(name, known)}; "
                f"its keys are {', '.join(known)} (python -m lab.grading.schema prints the format)"
            )
        test, words = TYPES[key.type]
        if not test(value):
            raise ExerciseError(
                f"{where}:{place(name)}: {what}: {name} = {value!r} should be {words}"
            )


def check_table_keys(table: dict, kind, where: str, place, own: set[str]) -> None:
    """A [[checks]] table against the common keys and its kind's: unknown keys, types, and
    keys (written in the table itself, not merged from [defaults]) its kind never reads."""
    extra = kind_keys(kind)
    builtin = kind.__module__.startswith("lab.grading.kinds.")
    keys = [*CHECK, *extra]
    check_keys(table, keys, where, f"check {table.get('name', '?')}", place)
    if not builtin:
        return  # a plug-in kind may read any common key
    for key in CHECK:
        if key.name in own and key.kinds and kind.name not in key.kinds:
            raise ExerciseError(
                f"{where}:{place(key.name)}: check {table.get('name', '?')}: a {kind.name} "
                f"check does not read {key.name} (only {', '.join(key.kinds)} checks do); "
                "remove it"
            )


def check_param_names(names, header: dict, where: str, line: int, what: str) -> None:
    """Each name is a parameter of the model's header, else the error names the header's."""
    for name in names:
        if name not in header:
            raise ExerciseError(
                f"{where}:{line}: {what} names {name!r}, which is no parameter of the model"
                f"{_close(name, header)}; its header declares {', '.join(header) or 'none'}"
            )


def require(table: dict, keys, where: str, what: str, line: int) -> None:
    """Every required key is there, else an error naming it and how to write it."""
    for key in keys:
        if key.default is REQUIRED and key.name not in table:
            raise ExerciseError(
                f"{where}:{line}: {what} lacks {key.name} ({key.meaning}); write "
                f"{key.name} = ... as {TYPES[key.type][1]}"
            )


def param_value_problem(param, value) -> str:
    """What is wrong with `value` for a header parameter, in words ('' if nothing)."""
    if param.kind == "color" and not _numbers(
        list(value) if isinstance(value, tuple) else value, 3
    ):
        return f"= {value!r} should be a colour, three numbers such as [0.5, 0.5, 0.5]"
    if param.kind == "float" and not _number(value):
        return f"= {value!r} should be a number such as {param.default:g}"
    if param.kind == "bool" and not isinstance(value, bool):
        return f"= {value!r} should be true or false"
    if param.kind == "enum" and value not in param.choices:
        return f"= {value!r} should be one of {', '.join(param.choices)}"
    if param.kind == "float" and not param.minimum <= value <= param.maximum:
        return f"= {value:g} lies outside the header's range [{param.minimum:g}, {param.maximum:g}]"
    return ""


# -- the format reference -----------------------------------------------------------------------
def _shown(value) -> str:
    if value is REQUIRED:
        return "required"
    if value is None:
        return "unset"
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str):
        return f'"{value}"'
    return f"`{value!r}`".replace("'", '"')


def _rows(keys, kinds_column: bool) -> list[str]:
    head = "| key | type | default | meaning |" + (" kinds |" if kinds_column else "")
    rule = "|---|---|---|---|" + ("---|" if kinds_column else "")
    rows = [head, rule]
    for k in keys:
        row = f"| `{k.name}` | {k.type} | {_shown(k.default)} | {k.meaning} |"
        if kinds_column:
            row += f" {', '.join(k.kinds) or 'all'} |"
        rows.append(row)
    return rows


def reference_markdown() -> str:
    """docs/exercise-format.md: every key of both files, generated from this module."""
    from lab.grading import kinds

    out = [
        "# The exercise format",
        "",
        "Generated by `python -m lab.grading.schema > docs/exercise-format.md` from",
        "`lab/grading/schema.py`, the table the grader validates every exercise with. An",
        "unknown key, a wrong type, a key the check's kind does not read, a parameter the",
        "model's header does not declare, or a mistake edit that is not in the solution",
        "stops the grader with the file, the line and what to write instead.",
        "`brdf-lab exercise check DIR` runs all of it. The authoring guide is",
        "docs/authoring.md.",
        "",
        "## exercise.toml: top level",
        "",
        *_rows(EXERCISE, False),
        "",
        "## exercise.toml: each `[[checks]]` table (and `[defaults]`)",
        "",
        "`kinds` names the check kinds that read a key; a key written for a kind that does",
        "not read it is an error (keys merged from `[defaults]` are ignored there).",
        "",
        *_rows(CHECK, True),
        "",
        "Types:",
        "",
        *(f"- **{name}**: {words}" for name, (_, words) in TYPES.items()),
        "",
        "Light purposes (`purpose`), by the light's angle in degrees:",
        "",
        *(f"- `{n}`: {lo:g} to {hi:g}" for n, (lo, hi) in PURPOSES.items()),
        "",
        "A sphere check names one per light (angle from the view axis); polar and the",
        "sampling kinds name the light at theta_i; probe draws its own directions and takes",
        "none. Without `purpose`, hidden mode infers it from each committed angle.",
        "",
        "## Hidden mode (`--seed N`)",
        "",
        "Each check's parameters are drawn across the header's range (log-uniform on `log`",
        "sliders) or the check's `ranges`; colours the check sets to 0 stay 0 and enum",
        "choices stay. Each light is drawn anew within its purpose, at a random azimuth;",
        "`seed` is drawn too. The solution is rendered live with the same draw, so hidden",
        "mode needs `solutions/` beside `exercises/`. An `object` check's textures are",
        "generated from the drawn seed (same size, grey or colour, within the committed",
        "file's values) and its yaw is drawn.",
        "",
        "## Tables (`table`)",
        "",
        '`table = { model = "ggx", params = { alpha = 0.2 } }` makes the grader tabulate that',
        "library model in the MERL layout (as `brdf-lab tabulate` does) and bind the table as",
        "`uniform highp sampler3D u_table;` in the student's file and the solution: texel",
        "(phi_d, theta_d, theta_h) holds f_r in RGB, read with texelFetch. Its keys: `model`",
        "(required), `params`, `ranges` (hidden mode draws these), `noise` (relative error per",
        "bin, default 0), `dims` (bins of theta_h, theta_d, phi_d, default [90, 90, 180]) and",
        "`uniform` (the sampler's name, default u_table). A list of tables: the committed",
        "references use the first, hidden mode picks one of them at each seed. The web page's",
        "practice mode makes the first on its own GPU (lab/web/static/tables.js); `noise` is a",
        "hash of bin, channel and seed (lab/measured/tabulate.py; shaders/views/tabulate.glsl",
        "for the page), so both tables agree to float precision.",
        "",
        "## Keys each check kind adds",
        "",
    ]
    for kind in kinds.all_kinds().values():
        extra = kind_keys(kind)
        if not extra or not kind.__module__.startswith("lab.grading.kinds."):
            continue
        out += [f'### `kind = "{kind.name}"`', "", *_rows(extra, False), ""]
    out += [
        "## solutions/NN_topic/mistakes.toml",
        "",
        *_rows(MISTAKES_TOP, False),
        "",
        "### each `[[mistake]]` table",
        "",
        *_rows(MISTAKE, False),
        "",
        "Each edit `['old', 'new']` replaces the first occurrence of `old` below the file's",
        "comment header, one edit after the other; `old` must occur there, as written",
        "(spaces included). The edited program must compile.",
        "",
        "### each entry of `[terms]`",
        "",
        '`name = { param = value, ..., define = [...], within = "..." }`: the parameter',
        "settings (header parameters only) that show one term alone, plus:",
        "",
        *_rows(TERM, False),
        "",
    ]
    return "\n".join(out)


def main() -> int:
    sys.stdout.write(reference_markdown())
    return 0


if __name__ == "__main__":
    sys.exit(main())

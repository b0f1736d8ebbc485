"""Exercises: their `exercise.toml`, the student's file, and how it becomes a model.

Everything here runs without OpenGL, so the supervising process can read exercises,
check a submission file and name the checks before any child process renders.
"""

from __future__ import annotations

import difflib
import re
import sys
from dataclasses import dataclass, field, replace
from pathlib import Path

from lab.constants import LOOP_LIMIT, LOOP_LIMIT_MAX
from lab.glsl import SAMPLER_LINE_BASE, guard_loops, label_of
from lab.grading import headers, kinds, schema
from lab.grading.scope import check_names, exercise_names
from lab.grading.spec import Check, ExerciseError, with_reference  # noqa: F401
from lab.grading.submission import SourceError, check_directives, linked_part, preprocess
from lab.models import Model, ModelError, Param, load_model, parse_model

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

MAX_BYTES = 256 * 1024
DEFAULT_API = tuple(schema.DEFAULT_API)  # an exercise without `api`


class SubmissionError(ValueError):
    """A submission that cannot be graded at all; the message is for the student."""


@dataclass
class Exercise:
    """An exercise folder: handout, student file, checks and committed references."""

    folder: Path
    title: str
    student_file: str
    checks: list[Check]
    functions: list[str]
    wrapper: str | None = None  # library model that calls the student's term functions
    replaces: str | None = None  # the library term file the student's file stands in for
    loop_limit: int = LOOP_LIMIT  # iterations per loop and invocation before the guard stops it
    sampler_for: str | None = None  # a library model whose BRDF sampler the student writes
    estimator: bool = False  # with sampler_for: the student writes the estimate itself
    api: list[str] = field(default_factory=list)  # library names the handout gives (scope.py)

    @property
    def name(self) -> str:
        return self.folder.name

    @property
    def stub(self) -> Path:
        return self.folder / self.student_file

    @property
    def references(self) -> Path:
        return self.folder / "references"

    @property
    def solution(self) -> Path:
        """The solved file: solutions/ mirrors exercises/ path for path."""
        return self.folder.parent.parent / "solutions" / self.folder.name / self.student_file

    @property
    def model_name(self) -> str:
        """The library model a submission stands for (what lab.reference evaluates): the
        wrapper's or sampled model's, else the stub's @model line (not the student's)."""
        if self.wrapper or self.sampler_for:
            return str(self.wrapper or self.sampler_for)
        try:
            found = re.search(r"^//\s*@model\s+(\w+)", self.stub.read_text("utf-8"), re.M)
        except OSError:
            return ""
        return found.group(1) if found else ""

    @property
    def max_points(self) -> float:
        return sum(c.points for c in self.checks)


def load_exercise(folder: str | Path) -> Exercise:
    """Read `folder/exercise.toml`, validated against lab.grading.schema; raises
    ExerciseError with the file, the line and what is wrong."""
    folder = Path(folder)
    spec_path = folder / "exercise.toml"
    if not spec_path.is_file():
        raise ExerciseError(f"{folder}: not an exercise folder (no exercise.toml in it)")
    try:
        text = spec_path.read_text(encoding="utf-8")
        spec = tomllib.loads(text)
    except (tomllib.TOMLDecodeError, UnicodeDecodeError) as err:
        raise ExerciseError(f"{spec_path}: {err}") from None
    where, lines = str(spec_path), schema.Lines(text)
    schema.check_keys(
        spec, list(schema.EXERCISE), where, "exercise.toml", lambda k: lines.line("", 0, k)
    )
    schema.require(spec, schema.EXERCISE, where, "exercise.toml", lines.line("", 0))
    defaults = spec.get("defaults", {})
    every = [
        *schema.CHECK,
        *(k for kind in kinds.all_kinds().values() for k in schema.kind_keys(kind)),
    ]
    unique = list({k.name: k for k in every}.values())
    schema.check_keys(defaults, unique, where, "[defaults]", lambda k: lines.line("defaults", 0, k))
    checks = []
    for index, raw in enumerate(spec["checks"]):
        merged = {**defaults, **raw}

        def place(key: str, index: int = index, raw: dict = raw) -> int:
            return lines.line(
                "checks" if key in raw else "defaults", index if key in raw else 0, key
            )

        label = f"check {merged.get('name', index + 1)}"
        schema.check_keys(merged, unique, where, label, place)  # a misspelt key first
        schema.require(merged, schema.CHECK, where, label, lines.line("checks", index))
        name = merged.pop("kind")
        kind = kinds.find(name) if isinstance(name, str) else None
        if kind is None:
            raise ExerciseError(
                f"{where}:{place('kind')}: check kind {name!r} is not one of "
                f"{', '.join(kinds.names())}"
            )
        schema.check_table_keys(merged, kind, where, place, own=set(raw))
        try:
            checks.append(kind.parse(merged, where))
        except (KeyError, TypeError, ValueError) as err:
            if isinstance(err, ExerciseError):
                raise
            raise ExerciseError(
                f"{where}:{place('name')}: check {merged.get('name')}: {err}"
            ) from None
    exercise = Exercise(
        folder=folder,
        title=spec["title"],
        student_file=spec["student_file"],
        checks=checks,
        functions=list(spec.get("functions", [])),
        wrapper=spec.get("wrapper"),
        replaces=spec.get("replaces"),
        loop_limit=int(spec.get("loop_limit", LOOP_LIMIT)),
        sampler_for=spec.get("sampler_for"),
        estimator=bool(spec.get("estimator", False)),
        api=[str(name) for name in spec.get("api", DEFAULT_API)],
    )
    if not 1 <= exercise.loop_limit <= LOOP_LIMIT_MAX:
        raise ExerciseError(
            f"{where}:{lines.line('', 0, 'loop_limit')}: loop_limit must be a positive number "
            f"of iterations, at most {LOOP_LIMIT_MAX:,} (Mesa's llvmpipe ends longer loops "
            "silently, before the guard could say so)"
        )
    if exercise.estimator:
        _check_estimator(exercise, spec, where, lines)
    headers.check_files(exercise, where, lines)
    headers.check_params(exercise, spec, where, lines)
    wrapper = exercise.wrapper or exercise.sampler_for  # the value kinds' conditioning:
    exercise.checks = with_reference(exercise.checks, exercise.model_name, exercise.stub, wrapper)
    seen: dict[str, int] = {}
    for index, check in enumerate(exercise.checks):
        if check.name in seen:
            raise ExerciseError(
                f"{where}:{lines.line('checks', index, 'name')}: two checks are named "
                f"{check.name!r} (the other at line {seen[check.name]}); give each its own name"
            )
        seen[check.name] = lines.line("checks", index, "name")
    return exercise


def _check_estimator(exercise: Exercise, spec: dict, where: str, lines) -> None:
    """An estimator exercise names the model it estimates with, and its checks render with
    the student's estimate (there is no sampler of theirs to test)."""
    at = lines.line("", 0, "estimator")
    if not exercise.sampler_for:
        raise ExerciseError(
            f'{where}:{at}: estimator = true needs sampler_for = "MODEL", the library model '
            "whose BRDF the student's estimate integrates"
        )
    for index, check in enumerate(exercise.checks):
        if check.kind != "ibl_render":
            raise ExerciseError(
                f"{where}:{lines.line('checks', index, 'kind')}: check {check.name}: kind "
                f"{check.kind!r} tests a sampler; an estimator exercise (estimator = true) "
                'is graded by its renders: use kind = "ibl_render"'
            )


def find_exercises(root: str | Path) -> list[Exercise]:
    """One exercise folder, or every exercise folder directly inside `root`."""
    root = Path(root)
    if (root / "exercise.toml").is_file():
        return [load_exercise(root)]
    found = [load_exercise(p.parent) for p in sorted(root.glob("*/exercise.toml"))]
    if not found:
        raise ExerciseError(f"{root}: no exercise.toml in it or in its sub-folders")
    return found


# -- the student's file --------------------------------------------------------------------
def read_submission(path: Path, root: Path | None = None) -> str:
    """The submission's text, or SubmissionError saying what is wrong with the file.

    `root` is the submission's top folder: no link may lie between it and the file.
    """
    link = linked_part(root, path) if root is not None else None
    if link is None and path.is_symlink():
        link = path
    if link is not None:
        raise SubmissionError(
            f"{link}: is a symbolic link; links are not followed (they could point at "
            "the solutions or another student's work): submit the files themselves"
        )
    if not path.exists():
        raise SubmissionError(f"{path}: file not found; submit it under this name")
    if not path.is_file():
        raise SubmissionError(f"{path}: is not a regular file")
    size = path.stat().st_size
    if size > MAX_BYTES:
        raise SubmissionError(
            f"{path}: the file has {size // 1024} KB, over the limit of {MAX_BYTES // 1024} KB"
        )
    raw = path.read_bytes()
    try:
        code = raw.decode("utf-8")
    except UnicodeDecodeError as err:
        line = raw[: err.start].count(b"\n") + 1
        raise SubmissionError(
            f"{path}:{line}: the file is not UTF-8 text (byte 0x{raw[err.start]:02x}); "
            "save it as UTF-8"
        ) from None
    code = code.removeprefix("\ufeff")  # editors on Windows save a byte-order mark: harmless
    if not code.strip():
        raise SubmissionError(f"{path}: the file is empty; start from the stub in the exercise")
    return code


_COMMENTS = re.compile(r"//[^\n]*|/\*.*?\*/", re.S)
_SIGNATURE = headers.SIGNATURE


def _types(params: str) -> list[str]:
    """Parameter types of a GLSL parameter list ('in vec3 L, float x' -> [vec3, float])."""
    types = []
    for part in params.split(","):
        words = [w for w in part.split() if w not in ("in", "const", "highp", "mediump", "lowp")]
        if words and words != ["void"]:
            types.append(" ".join(words[:-1]) if len(words) > 1 else words[0])
    return types


def check_functions(code: str, required: list[str], label: str) -> None:
    """Each required function is defined with the expected signature (no GL needed)."""
    stripped = _COMMENTS.sub(lambda m: re.sub(r"[^\n]", " ", m.group(0)), code)
    defined: dict[str, tuple[str, list[str], int]] = {}
    for match in _SIGNATURE.finditer(stripped):
        ret, name, params = match.groups()
        if ret in ("if", "for", "while", "return", "else"):
            continue
        line = stripped[: match.start()].count("\n") + 1
        defined.setdefault(name, (ret, _types(params), line))
    for signature in required:
        want = _SIGNATURE.match(signature + " {")
        ret, name, params = want.groups()
        if name not in defined:
            close = difflib.get_close_matches(name, list(defined), n=1, cutoff=0.6)
            close += [n for n in defined if n.lower() == name.lower() and n not in close]
            hint = f" (you defined {close[0]}: check the spelling)" if close else ""
            raise SubmissionError(f"{label}: function {name} is missing{hint}; define {signature}")
        got_ret, got_types, line = defined[name]
        if got_ret != ret or got_types != _types(params):
            got = f"{got_ret} {name}({', '.join(got_types)})"
            raise SubmissionError(
                f"{label}:{line}: {got} has the wrong signature; the grader calls {signature}"
            )


def _preprocessed(exercise: Exercise, code: str, label: str, trusted: bool) -> str:
    """What the compiler sees. The instructor's own code without directives (a variant of
    the solution, `trusted`) only loses its comments to the preprocessor, so they are
    blanked here: a glslang process per variant would cost 40-70 ms each. A student's file
    may only name the library's API (lab.grading.scope)."""
    if trusted and "#" not in code:
        code = re.sub(r"/\*.*?\*/", lambda m: "\n" * m.group().count("\n"), code, flags=re.S)
        return re.sub(r"//[^\n]*", "", code)
    compiled = preprocess(code, label)
    if not trusted:
        check_names(compiled, label, exercise_names(exercise), exercise.api)
    return compiled


def build_model(exercise: Exercise, path: Path, code: str, trusted: bool = False) -> Model:
    """The submission as a model that every view can render (`trusted`: the instructor's
    own code, see _preprocessed).

    A term exercise's file is put in front of its wrapper model from the library, whose
    include of the term file it replaces is dropped.
    """
    label = label_of(path)
    if exercise.sampler_for:
        return sampler_model(exercise, path, code, trusted)
    stub = parse_model(exercise.stub.read_text(encoding="utf-8"), exercise.stub)
    try:
        check_directives(code, label, stub.includes)
        compiled = _preprocessed(exercise, code, label, trusted)  # no #if 0, no macros
        check_functions(compiled, exercise.functions, label)
        if exercise.wrapper:
            wrapper = load_model(exercise.wrapper)
            return Model(
                name=wrapper.name,
                path=path,
                code=compiled.rstrip("\n") + "\n" + wrapper.code,
                title=wrapper.title,
                includes=[i for i in wrapper.includes if i != exercise.replaces],
                params=wrapper.params,
                loop_limit=exercise.loop_limit,
            )
        model = parse_model(code, path)
        model.code = compiled
        model.loop_limit = exercise.loop_limit
    except (ModelError, SourceError) as err:
        raise SubmissionError(str(err)) from None
    for name, param in stub.params.items():
        mine = model.params.get(name)
        what = header_edit(param, mine)
        if what:
            where = f"{label}:{mine.line}" if mine is not None and mine.line else label
            raise SubmissionError(
                f"{where}: {what} in the header; put back the stub's line "
                f"'{param.header_line()}' (the grader sets this parameter)"
            )
        if header_changes(param, mine):  # tried out: costs nothing, the stub's line counts
            model.params[name] = replace(
                mine,
                default=param.default,
                minimum=param.minimum,
                maximum=param.maximum,
                scale=param.scale,
            )
    return model


def header_notes(exercise: Exercise, path: Path, code: str) -> list[str]:
    """Header lines whose default or range a submission changed, in words: the grader uses
    the stub's (build_model), and says so ([] when unchanged or unreadable)."""
    try:
        stub = parse_model(exercise.stub.read_text(encoding="utf-8"), exercise.stub)
        mine = parse_model(code.lstrip("\ufeff"), path)
    except (ModelError, OSError):
        return []
    notes = []
    for name, param in stub.params.items():
        other = mine.params.get(name)
        for change in header_changes(param, other) if other is not None else []:
            where = f"{label_of(path)}:{other.line}" if other.line else label_of(path)
            notes.append(
                f"{where}: you changed {change} in the header; the grader uses the stub's "
                f"line '{param.header_line()}'"
            )
    return notes


def header_changes(stub: Param, mine: Param) -> list[str]:
    """What a submission changed in a header line that the grader can put back."""
    changes = []
    if mine.default != stub.default:
        changes.append(
            f"the default of {stub.name} from {_shown(stub.default)} to {_shown(mine.default)}"
        )
    if (mine.minimum, mine.maximum) != (stub.minimum, stub.maximum) and stub.kind != "enum":
        changes.append(
            f"the range of {stub.name} from [{stub.minimum:g}, {stub.maximum:g}] to "
            f"[{mine.minimum:g}, {mine.maximum:g}]"
        )
    if mine.scale != stub.scale and stub.kind == "float":
        changes.append(f"the slider scale of {stub.name} from {stub.scale} to {mine.scale}")
    return changes


def sampler_model(exercise: Exercise, path: Path, code: str, trusted: bool = False) -> Model:
    """A sampling exercise: the library model, with the student's file as its sampler."""
    from lab.ibl.integrator import ESTIMATOR_HOST, ESTIMATOR_LINE, LOBE_SAMPLER

    label = label_of(path)
    try:
        check_directives(code, label, [])
        compiled = _preprocessed(exercise, code, label, trusted)
        check_functions(compiled, exercise.functions, label)
        model = replace(load_model(exercise.sampler_for))
    except (ModelError, SourceError) as err:
        raise SubmissionError(str(err)) from None
    model.sampler_path = path
    model.loop_limit = exercise.loop_limit
    code, loops = compiled, []
    if model.loop_limit > 0:  # the student's loops, guarded as a model file's are
        code, loops = guard_loops(compiled, "lab_loop_sampler_", SAMPLER_LINE_BASE)
    # The counters share the first line, so the file's line numbers stay its own.
    counters = "".join(f"int lab_loop_sampler_{k} = 0; " for k in range(len(loops)))
    if exercise.estimator:  # the estimate itself: the IBL view calls it (ESTIMATOR_HOST)
        model.estimator = True
        model.sampler_code = counters + ESTIMATOR_LINE + code.rstrip("\n") + "\n" + ESTIMATOR_HOST
        return model
    model.sampler_code = counters + code.rstrip("\n") + "\n" + LOBE_SAMPLER
    return model


def header_edit(stub: Param, mine: Param | None) -> str:
    """What a submission changed in a parameter's header line, in words ('' if nothing)."""
    if mine is None:
        return f"you removed the parameter {stub.name}"
    if mine.kind != stub.kind:
        return f"you changed the type of {stub.name} from {stub.kind} to {mine.kind}"
    if mine.choices != stub.choices:
        return f"you changed the choices of {stub.name}"
    return ""


def _shown(value) -> str:
    """A header value as written: 0.5, 0.1,0.1,0.1, beckmann, True."""
    if isinstance(value, tuple):
        return ",".join(f"{c:g}" for c in value)
    return f"{value:g}" if isinstance(value, float) else str(value)


def wrapper_origin(exercise: Exercise, code: str, file: str, line: int) -> tuple[str, int]:
    """Map a compile error in the wrapper part of a term exercise back to the wrapper file."""
    if not exercise.wrapper:
        return file, line
    student_lines = len(code.rstrip("\n").splitlines())
    if line <= student_lines:
        return file, line
    return label_of(load_model(exercise.wrapper).path), line - student_lines

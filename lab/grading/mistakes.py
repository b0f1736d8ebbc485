"""Known mistakes and single-edit mutants of a solution: the grader's error model.

After Singh, Gulwani and Solar-Lezama (PLDI 2013, "Automated feedback generation for
introductory programming assignments"): a wrong submission is compared with likely wrong
programs, each carrying a hint for the student. Two sources:

- `solutions/NN_topic/mistakes.toml` lists the common mistakes an instructor has seen, each
  a few text edits of the solution with a hint written for students;
- `mutants()` makes single edits of the solution mechanically (a dot product for another,
  a dropped 1/pi, a wrong constant) and words a hint from the edit;

and the exercise's unfinished file itself (the stub), the commonest wrong submission of all:
what it gives often equals some mistake's values by chance (a stub without its specular
lobe looks like a mirror direction pointing into the surface), whose hint would mislead.

Their values for every check are rendered with the references (`references/diagnosis.npz`,
hints in `references/diagnosis.json`; no solution code is stored beside the exercise), and
live in hidden mode. Everything here runs without OpenGL.
"""

from __future__ import annotations

import difflib
import json
import re
import sys
from dataclasses import dataclass, replace
from pathlib import Path

from lab.glsl import label_of
from lab.grading import schema
from lab.grading.exercise import Exercise, ExerciseError
from lab.grading.headers import header_params

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

MISTAKES_FILE = "mistakes.toml"
VALUES = "diagnosis.npz"
HINTS = "diagnosis.json"
MAX_MUTANTS = 32  # per exercise: each one costs a compile when references are made
STUB = "stub"  # the key of the stub's variant (its code is stored with the hints)
MUTANT = "mutant."  # the prefix of generated single-edit variants' keys
STUB_HINT = (
    "it gives just what the exercise's unfinished file (the stub) gives: the steps its TODO "
    "comments ask for are not done yet, or what they add does not reach the result"
)


# How each name of a dot product or constant reads in a hint.
SPOKEN = {
    "NoL": "N·L",
    "NoV": "N·V",
    "NoH": "N·H",
    "VoH": "V·H",
    "LoH": "L·H",
    "RoV": "R·V",
    "LoV": "L·V",
    "INV_PI": "1/π",
    "PI": "π",
}
DOTS = ("NoL", "NoV", "NoH", "VoH", "LoH", "RoV")
CONSTANTS = {"2.0": "4.0", "4.0": "2.0", "0.5": "1.0", "8.0": "4.0", "0.25": "0.5"}


@dataclass(frozen=True)
class Variant:
    """A likely wrong program: the solution with `edits` applied, and its hint."""

    key: str  # mistake.N (from mistakes.toml), mutant.N (generated) or STUB
    hint: str
    edits: tuple[tuple[str, str], ...]
    code: str = ""  # a whole program instead of edits (the stub's)

    def apply(self, code: str) -> str:
        """The solution with the edits made below its comment header (never in it)."""
        if self.code:
            return self.code
        start = _code_start(code)
        head, body = code[:start], code[start:]
        for old, new in self.edits:
            if old not in body:
                raise ExerciseError(f"{self.key}: {old!r} is not in the solution")
            body = body.replace(old, new, 1)
        return head + body


def mistakes_file(exercise: Exercise) -> Path:
    return exercise.solution.parent / MISTAKES_FILE


def known_mistakes(exercise: Exercise) -> list[Variant]:
    """The instructor's list for an exercise (none when the file does not exist), validated
    against lab.grading.schema: each edit must apply to the solution where it is there."""
    path = mistakes_file(exercise)
    if not path.is_file():
        return []
    spec, lines = _read_list(path)
    where = str(path)
    try:
        solution = exercise.solution.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError):
        solution = None  # a student's copy: the grader reads the stored values instead
    found = []
    for number, raw in enumerate(spec.get("mistake", [])):
        line = lines.line("mistake", number)
        schema.check_keys(
            raw,
            list(schema.MISTAKE),
            where,
            f"mistake {number + 1}",
            lambda k, n=number: lines.line("mistake", n, k),
        )
        schema.require(raw, schema.MISTAKE, where, f"mistake {number + 1}", line)
        variant = Variant(
            f"mistake.{number}",
            str(raw["hint"]).strip(),
            tuple((old, new) for old, new in raw["edits"]),
        )
        if solution is not None:
            line = lines.line("mistake", number, "edits")
            _check_edits(variant, solution, f"{where}:{line}", label_of(exercise.solution))
        found.append(variant)
    return found


def _read_list(path: Path) -> tuple[dict, schema.Lines]:
    """mistakes.toml read and its top-level keys and terms checked."""
    try:
        text = path.read_text(encoding="utf-8")
        spec = tomllib.loads(text)
    except (tomllib.TOMLDecodeError, UnicodeDecodeError) as err:
        raise ExerciseError(f"{path}: {err}") from None
    lines = schema.Lines(text)
    schema.check_keys(
        spec, list(schema.MISTAKES_TOP), str(path), "mistakes.toml", lambda k: lines.line("", 0, k)
    )
    for name, term in spec.get("terms", {}).items():
        line = lines.line("terms", 0, name)
        if not isinstance(term, dict):
            raise ExerciseError(
                f"{path}:{line}: terms.{name} should be a table of parameter settings, e.g. "
                f"{name} = {{ ks = [0.0, 0.0, 0.0] }}"
            )
        for key in ("define", "within"):
            if key in term:
                schema.check_keys(
                    {key: term[key]},
                    list(schema.TERM),
                    str(path),
                    f"terms.{name}",
                    lambda k, ln=line: ln,
                )
    return spec, lines


def _check_edits(variant: Variant, solution: str, where: str, solution_label: str) -> None:
    """Each edit's old text occurs below the solution's header once the earlier edits are
    made; else the error shows the nearest line of the solution to copy from."""
    body = solution[_code_start(solution) :]
    for index, (old, new) in enumerate(variant.edits):
        if old not in body:
            near = difflib.get_close_matches(
                old.strip(), [ln.strip() for ln in body.splitlines()], 1, 0.4
            )
            hint = f"; the nearest line of the solution is {near[0]!r}" if near else ""
            raise ExerciseError(
                f"{where}: mistake {int(variant.key.split('.')[1]) + 1} "
                f"({variant.hint[:40]!r}...), "
                f"edit {index + 1}: {old!r} is not in {solution_label}"
                f"{' after the edits before it' if index else ''}{hint}; copy the old text from "
                "the solution exactly, spaces included"
            )
        body = body.replace(old, new, 1)


def validate(exercise: Exercise) -> None:
    """The exercise's mistakes.toml, where there is one: keys, types, edits that apply to
    the solution and [terms] that set the model's own parameters (ExerciseError)."""
    path = mistakes_file(exercise)
    if not path.is_file():
        return
    known_mistakes(exercise)
    header = header_params(exercise)
    if header is None:
        return
    spec, lines = _read_list(path)
    for name, term in spec.get("terms", {}).items():
        params = [k for k in term if k not in ("define", "within")]
        schema.check_param_names(
            params, header, str(path), lines.line("terms", 0, name), f"terms.{name}"
        )


def _code_start(code: str) -> int:
    """Offset of the first line that is not a comment: mutants never edit the header."""
    offset = 0
    for line in code.splitlines(keepends=True):
        if line.strip() and not line.lstrip().startswith("//"):
            return offset
        offset += len(line)
    return offset


def _single_edit(code: str, start: int, end: int, new: str) -> tuple[str, str]:
    """An edit as (old, new) text pairs that `Variant.apply` finds exactly once: the whole
    line it is on, so that the first occurrence of the line is the one meant."""
    line_start = code.rfind("\n", 0, start) + 1
    line_end = code.find("\n", end)
    line_end = len(code) if line_end < 0 else line_end
    old_line = code[line_start:line_end]
    new_line = code[line_start:start] + new + code[end:line_end]
    return old_line, new_line


def _in_divisor(code: str, at: int) -> bool:
    """Whether the factor at offset `at` divides (`x / PI`, `x / (4.0 * PI * a)`) rather than
    multiplies (`2.0 * PI * u`, `a / b * PI`): what its removal does to the term."""
    line = code[code.rfind("\n", 0, at) + 1 : at]
    depth = 0
    for i in range(len(line) - 1, -1, -1):
        c = line[i]
        if c == ")":
            depth += 1
        elif c == "(" and depth:
            depth -= 1
        elif c == "(":
            before = line[:i].rstrip()
            if before.endswith("/"):
                return True
            if before and (before[-1].isalnum() or before[-1] == "_"):
                return False  # a call's argument
        elif depth == 0 and c == "/":
            return not line[i + 1 :].strip()  # only the operand right after '/' divides
        elif depth == 0 and c in "+-,=;?:<>":
            return False
    return False


def mutants(code: str, limit: int = MAX_MUTANTS) -> list[Variant]:
    """Single-edit variants of the solution's code, each with a hint worded from the edit.

    Edits whose line occurs twice in the file are skipped (their place would be ambiguous);
    duplicates and variants equal to the solution are removed later, by their values.
    """
    start = _code_start(code)
    body = code[start:]
    seen_lines = {}
    for line in body.splitlines():
        seen_lines[line] = seen_lines.get(line, 0) + 1
    present = [d for d in DOTS if re.search(rf"\b{d}\b", body)]
    found: list[Variant] = []

    def add(match_start: int, match_end: int, new: str, hint: str) -> None:
        old_line, new_line = _single_edit(code, match_start, match_end, new)
        if seen_lines.get(old_line, 0) != 1 or old_line.lstrip().startswith("//"):
            return
        if old_line.lstrip().startswith(("float ", "vec3 ")) and "(" in old_line.split("=")[0]:
            return  # a function's signature: a compile error, not a mistake
        edits = ((old_line, new_line),)
        if all(v.edits != edits for v in found):
            found.append(Variant(f"{MUTANT}{len(found)}", hint, edits))

    for match in re.finditer(r"\b(" + "|".join(present) + r")\b", body) if present else []:
        name = match.group(1)
        if re.match(r"\s*=[^=]", body[match.end() :]):  # its own definition
            continue
        for other in present:
            if other != name:
                hint = (
                    f"a term behaves like {SPOKEN[other]} where {SPOKEN[name]} belongs: "
                    f"check which dot product each factor uses"
                )
                add(start + match.start(), start + match.end(), other, hint)
    for match in re.finditer(r"\s*\*\s*INV_PI\b|\bINV_PI\s*\*\s*", body):
        add(
            start + match.start(),
            start + match.end(),
            "",
            "a factor 1/π is missing: every value of that term is π times too large",
        )
    for match in re.finditer(r"\bPI\s*\*\s*", body):
        divides = _in_divisor(code, start + match.start())
        add(
            start + match.start(),
            start + match.end(),
            "",
            "a factor π is missing from a denominator: that term is π times too large"
            if divides
            # A product's own size says little about the result's (it may be a normaliser
            # that divides later): no direction, so never the wrong one.
            else "a factor π is missing from a product: check each product that should hold π",
        )
    for match in re.finditer(r"(?<![\w.])(\d+\.\d+)(?![\w.])", body):
        wrong = CONSTANTS.get(match.group(1))
        if wrong:
            add(
                start + match.start(),
                start + match.end(),
                wrong,
                f"a constant is off: the values behave as if {wrong.rstrip('0').rstrip('.')} "
                f"stood where {match.group(1).rstrip('0').rstrip('.')} belongs",
            )
    for match in re.finditer(r"\bdot\((\w+), (\w+)\)", body):
        a, b = match.groups()
        for x, y in (("L", "V"), ("V", "L"), ("L", "H"), ("V", "H")):
            if b == x:
                hint = (
                    f"a term behaves like {a}·{y} where {a}·{x} belongs: check which dot "
                    "product each factor uses"
                )
                add(start + match.start(), start + match.end(), f"dot({a}, {y})", hint)
    for match in re.finditer(r"max\((dot\([^()]*\)), (0\.0|EPS)\)", body):
        add(
            start + match.start(),
            start + match.end(),
            match.group(1),
            "a dot product is not clamped: it goes negative past 90° (use max(..., 0.0))",
        )
    for match in re.finditer(r"\b(pow|\w+_\w+)\((\w+), (\w+)([,)])", body):
        name, a, b, tail = match.groups()
        if name.startswith("lab_"):
            continue
        hint = f"two arguments of {name} behave as if swapped ({b}, {a} instead of {a}, {b})"
        add(start + match.start(), start + match.end(), f"{name}({b}, {a}{tail}", hint)
    for match in re.finditer(r"\b(cos|sin|tan)\((\w+)\)", body):
        trig, angle = match.groups()
        hint = (
            f"an angle is taken for degrees where it is in radians: {trig}({angle}) behaves "
            f"like {trig}(radians({angle}))"
        )
        add(start + match.start(), start + match.end(), f"{trig}(radians({angle}))", hint)
    return found[:limit]


def either(first: str, second: str) -> str:
    """One hint for two edits that behave alike: 'X, or Y: advice' when both end in the
    same advice."""
    if second in first:
        return first
    head, _, advice = first.rpartition(": ")
    other, _, other_advice = second.rpartition(": ")
    if head and advice == other_advice:
        return f"{head}, or {other}: {advice}"
    return f"{first}; or else {second}"


def variants(exercise: Exercise, code: str, stub: str | None = None) -> list[Variant]:
    """The stub first, then known mistakes (their hints are the better ones), then the
    generated mutants. `stub`: the unfinished file's text (when references are made); by
    default the one stored with the hints, since at grading time the exercise's file may be
    the student's own."""
    stub = _stored(exercise).get(STUB) if stub is None else stub
    first = [Variant(STUB, STUB_HINT, (), stub)] if isinstance(stub, str) and stub else []
    return first + known_mistakes(exercise) + mutants(code)


def term_parts(spec: dict) -> tuple[dict, tuple[str, ...], str]:
    """A declared term's (parameter settings, GLSL macros, the term it is part of).

    Settings switch other terms off (`kd = [0, 0, 0]`); `define` lists macros that make
    the wrapper's or library's other functions neutral (`"G_vgroove(a, b, c, d) 1.0"`), so a
    term such as D is seen alone through the code that calls it; `within` names the term
    it is a factor of (D, G and F within "specular").
    """
    params = {k: v for k, v in spec.items() if k not in ("define", "within")}
    return params, tuple(str(d) for d in spec.get("define", ())), str(spec.get("within", ""))


def with_defines(model, defines: tuple[str, ...]):
    """The model with `#define` lines in front of its code (after the library includes)."""
    if not defines:
        return model
    lines = "".join(f"#define {d}\n" for d in defines)
    return replace(model, code=lines + model.code)


def calls_all(code: str, defines: tuple[str, ...]) -> bool:
    """Does `code` call every function the macros replace? Else they would not isolate the
    term in it (a student who wrote G inline), and the term says nothing."""
    names = [d.split("(", 1)[0].strip() for d in defines]
    return all(re.search(rf"\b{re.escape(n)}\s*\(", code) for n in names)


def declared_terms(exercise: Exercise) -> dict[str, dict]:
    """The terms an exercise can show alone (`[terms]` in the list; see term_parts)."""
    path = mistakes_file(exercise)
    if not path.is_file():
        return {}
    spec = _read_list(path)[0]
    return {
        name: {k: tuple(v) if isinstance(v, list) else v for k, v in params.items()}
        for name, params in spec.get("terms", {}).items()
    }


def _stored(exercise: Exercise) -> dict:
    path = exercise.references / HINTS
    try:
        return json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return {}


def read_hints(exercise: Exercise) -> dict[str, str]:
    """The stored hints by variant key ({} when the references have none)."""
    hints = _stored(exercise).get("hints", {})
    return {str(k): str(v) for k, v in hints.items()} if isinstance(hints, dict) else {}


def read_terms(exercise: Exercise) -> dict[str, dict]:
    """The stored terms: name -> parameter settings that show that term alone."""
    terms = _stored(exercise).get("terms", {})
    return (
        {
            str(name): {k: tuple(v) if isinstance(v, list) else v for k, v in params.items()}
            for name, params in terms.items()
        }
        if isinstance(terms, dict)
        else {}
    )


def write_hints(
    exercise: Exercise, hints: dict[str, str], terms: dict[str, dict], stub: str = ""
) -> Path:
    path = exercise.references / HINTS
    data = {"hints": hints, "terms": terms}
    if stub:
        data[STUB] = stub
    path.write_text(json.dumps(data, indent=1, ensure_ascii=False) + "\n", "utf-8")
    return path

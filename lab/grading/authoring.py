"""`brdf-lab exercise check DIR`: everything an instructor's new exercise must pass.

The folder is validated (lab.grading.schema, with its mistakes.toml), its references are
rendered from the solution, and then the grader grades the solution (in practice and in
hidden mode: full marks expected), the stub (some check must fail) and each stored
mistake (some check must fail; the table says whether the grader names its hint).
"""

from __future__ import annotations

import tempfile
from dataclasses import dataclass
from pathlib import Path

from lab.errors import UsageError

GUIDE = "docs/authoring.md"


@dataclass
class Row:
    """One line of the table: a file graded, what was expected and what came out."""

    what: str
    expect_pass: bool
    task: object  # lab.grading.runner.Task
    hint: str = ""  # a mistake's hint: is it the one the grader gives?

    @property
    def compile_error(self) -> str:
        """The first compile error of this file ('' when it compiles)."""
        return next((r.errors[0] for r in self.task.checks() if r.errors), "")

    @property
    def ok(self) -> bool:
        return self.task.passed == self.expect_pass and not self.compile_error

    def named(self) -> str:
        if not self.hint:
            return ""
        said = " ".join(r.diagnosis for r in self.task.checks())
        return "hint named" if self.hint in said else "hint not named"


def _layout(folder: Path):
    """The exercise, validated, with what the check needs beside it (UsageError if not)."""
    from lab.grading import mistakes
    from lab.grading.exercise import ExerciseError, load_exercise

    try:
        exercise = load_exercise(folder)
        mistakes.validate(exercise)
    except ExerciseError as err:
        raise UsageError(str(err)) from None
    needed = {
        folder / "README.md": "the handout students read",
        exercise.stub: "the student's unfinished file (student_file)",
        exercise.solution: "the solution: solutions/ mirrors exercises/ path for path",
    }
    for path, what in needed.items():
        if not path.is_file():
            raise UsageError(f"{path} is missing: {what} (see {GUIDE})")
    return exercise


def rows_for(exercise, scratch: Path, seed: int) -> list[Row]:
    """The files to grade: solution (twice), stub, and each mistake written to `scratch`."""
    from lab.grading import mistakes
    from lab.grading.runner import Task

    solution = exercise.solution
    rows = [
        Row("solution", True, Task(exercise, solution)),
        Row(f"solution, hidden mode --seed {seed}", True, Task(exercise, solution, seed)),
        Row("stub", False, Task(exercise, exercise.stub)),
    ]
    code = solution.read_text(encoding="utf-8")
    for number, variant in enumerate(mistakes.known_mistakes(exercise), 1):
        path = scratch / f"mistake{number}" / exercise.student_file
        path.parent.mkdir()
        path.write_text(variant.apply(code), encoding="utf-8")
        rows.append(Row(f"mistake {number}", False, Task(exercise, path), variant.hint))
    return rows


def table(rows: list[Row]) -> str:
    """The results as an aligned text table (words, not colours, say what is wrong)."""
    head = ("graded", "score", "expected", "verdict", "diagnosis")
    lines = [head]
    for row in rows:
        score = f"{row.task.score:g}/{row.task.max_score:g}"
        expected = "full marks" if row.expect_pass else "a check fails"
        lines.append((row.what, score, expected, "ok" if row.ok else "WRONG", row.named()))
    widths = [max(len(line[i]) for line in lines) for i in range(len(head))]
    return "\n".join(
        "  ".join(cell.ljust(w) for cell, w in zip(line, widths, strict=True)).rstrip()
        for line in lines
    )


def problems(rows: list[Row]) -> list[str]:
    """What to fix, in words, for each row that came out wrong."""
    out = []
    for row in rows:
        if row.ok:
            continue
        if row.compile_error:
            out.append(
                f"{row.what} does not compile ({row.compile_error}): every file students "
                "start from or could be told about must compile; fix its edits"
            )
        elif row.expect_pass:
            failing = [r for r in row.task.checks() if not r.passed]
            first = failing[0] if failing else None
            why = f"{first.name}: {first.message}" if first else "no result"
            out.append(
                f"{row.what} does not get full marks ({why}): loosen that check's tolerance, "
                "narrow its `ranges`, or fix the solution"
            )
        elif row.what == "stub":
            out.append("the stub passes every check: leave the graded step undone (a TODO)")
        else:
            out.append(
                f"{row.what} passes every check: no check sees it; add a check that does "
                "(other parameters or lights) or drop the mistake"
            )
    return out


def check(folder: Path, seed: int = 1, timeout: float = 20.0) -> int:
    """Validate, render the references, grade; print the table. 0: as expected, 1: not."""
    from lab.grading.references import make_references
    from lab.grading.runner import Pool

    exercise = _layout(folder)
    print(f"{folder}: exercise.toml and mistakes.toml are valid ({len(exercise.checks)} checks)")
    from lab.grading.exercise import ExerciseError

    with Pool(1, timeout) as pool, tempfile.TemporaryDirectory() as tmp:
        try:
            written = make_references(folder)
        except ExerciseError as err:
            raise UsageError(str(err)) from None
        print(f"rendered {len(written)} reference files into {exercise.references}")
        rows = rows_for(exercise, Path(tmp), seed)
        pool.run([row.task for row in rows])
    print(table(rows))
    found = problems(rows)
    for problem in found:
        print(f"{folder}: {problem}")
    print(f"{folder}: " + ("ready for students" if not found else f"{len(found)} to fix"))
    return 1 if found else 0


def cmd_exercise(args) -> int:
    from lab.grading.installed import resolve

    folder = resolve(args.dir)
    if not (folder / "exercise.toml").is_file():
        raise UsageError(f"{folder}: not an exercise folder (no exercise.toml in it)")
    return check(folder, args.seed, args.timeout)


def register(sub) -> None:
    p = sub.add_parser("exercise", help="(instructor) check a new exercise folder")
    actions = p.add_subparsers(dest="action", metavar="ACTION", required=True)
    c = actions.add_parser(
        "check",
        help="validate, render references, grade the solution, stub and stored mistakes",
    )
    c.add_argument("dir", metavar="DIR", help="exercises/NN_topic, with solutions/NN_topic beside")
    c.add_argument("--seed", type=int, default=1, help="hidden-mode seed the solution must pass")
    c.add_argument("--timeout", type=float, default=20.0, help="seconds per check (default 20)")
    c.set_defaults(func=cmd_exercise)

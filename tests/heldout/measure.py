"""Measure the grader on the held-out submissions of tests/heldout (issue 22).

A benchmark, not a test: it grades every case of cases.toml with the grading Pool, in
reference mode and in hidden mode for a few seeds, and prints how many wrong submissions
lose points, how many hints name the mistake or point at its line, how many point the
wrong way, and which correct rewrites lose points.

    .venv/bin/python tests/heldout/measure.py [--seed 1 2 3] [--workers 2] [--verbose]

The cases are kept out of tuning: read the figures, not the files.
"""

from __future__ import annotations

import argparse
import re
import shutil
import sys
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path

try:
    import tomllib
except ModuleNotFoundError:  # Python 3.10
    import tomli as tomllib

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from lab.grading.runner import Task

HERE = Path(__file__).resolve().parent
CASES = HERE  # the folder of cases.toml and the case files (--cases)
ROOT = HERE.parent.parent  # the checkout whose grader and exercises grade (--root)

QUOTE_MIN = 12  # characters of the fault's line a hint must quote to count as citing it


@dataclass
class Case:
    """One held-out submission and what a good hint would say about it."""

    exercise: str
    file: str
    correct: bool
    what: str
    lines: list[int] = field(default_factory=list)
    names: list[str] = field(default_factory=list)
    wrong: list[str] = field(default_factory=list)

    @property
    def label(self) -> str:
        return self.file.removesuffix(".glsl")


@dataclass
class Outcome:
    """A case graded in one mode, and how its hints read."""

    score: float
    max_score: float
    failed: list[str]
    hints: list[str]
    named: bool = False
    localised: bool = False
    wrong_way: bool = False

    @property
    def lost(self) -> bool:
        return self.score < self.max_score - 1e-9

    def flag(self, correct: bool) -> str:
        """A few letters for the table: N named, L localised, W wrong way, - no hint."""
        if not self.lost:
            return "ok"
        if correct:
            return "LOST"
        letters = ("N" if self.named else "") + ("L" if self.localised else "")
        letters += "W" if self.wrong_way else ""
        return letters or ("-" if not self.hints else "?")


def load_cases(path: Path) -> list[Case]:
    """The manifest's cases, with `line` always a list."""
    data = tomllib.loads(path.read_text(encoding="utf-8"))
    cases = []
    for entry in data["case"]:
        line = entry.get("line", [])
        cases.append(
            Case(
                exercise=entry["exercise"],
                file=entry["file"],
                correct=bool(entry["correct"]),
                what=entry.get("what", ""),
                lines=[line] if isinstance(line, int) else list(line),
                names=[n.lower() for n in entry.get("names", [])],
                wrong=[w.lower() for w in entry.get("wrong", [])],
            )
        )
    return cases


def cites(hint: str, line: int, text: str) -> bool:
    """Does `hint` point at line `line` (":12", "line 12") or quote its code?"""
    if re.search(rf"(?:[:]|\bline\s|\blines\s(?:\d+\D+)*){line}(?!\d)", hint, re.I):
        return True
    code = " ".join(text.split("//")[0].split())
    return len(code) >= QUOTE_MIN and code in " ".join(hint.split())


def unquoted(hint: str, source: list[str]) -> str:
    """`hint` without the student's own code it quotes in backticks and without file
    paths: a quoted line localises, but its identifiers do not name anything."""
    code = " ".join(" ".join(source).split())

    def drop(match: re.Match) -> str:
        text = " ".join(match.group(1).split())
        return "`…`" if len(text) >= QUOTE_MIN and text in code else match.group(0)

    # Nor does the path of the file (a temporary folder's random letters: "kd", "cos").
    hint = re.sub(r"(?:[A-Za-z]:)?(?:[/\\][^\s/\\:`()]+)+\.glsl", "FILE", hint)
    return re.sub(r"`([^`]*)`", drop, hint)


def judge(case: Case, task: Task, source: list[str]) -> Outcome:
    """Score, failed checks and the reading of the hints of one graded task."""
    results = task.checks()
    hints = [r.diagnosis for r in results if r.diagnosis]
    low = [unquoted(h, source).lower() for h in hints]
    outcome = Outcome(
        score=task.score,
        max_score=task.max_score,
        failed=[r.name for r in results if not r.passed]
        + [c.name for c in task.exercise.checks if c.name not in task.results],
        hints=hints,
    )
    if not case.correct:
        outcome.named = any(n in h for n in case.names for h in low)
        outcome.wrong_way = any(w in h for w in case.wrong for h in low)
        outcome.localised = any(
            cites(h, n, source[n - 1]) for n in case.lines if 0 < n <= len(source) for h in hints
        )
    return outcome


def grade(
    cases: list[Case], modes: list[int | None], workers: int, timeout: float
) -> dict[tuple[str, int | None], Task]:
    """Every case in every mode, each copied under its exercise's file name."""
    if str(ROOT) not in sys.path:
        sys.path.insert(0, str(ROOT))
    from lab.grading.exercise import find_exercises
    from lab.grading.runner import Pool, Task

    exercises = {e.name: e for e in find_exercises(ROOT / "exercises")}
    tasks: dict[tuple[str, int | None], Task] = {}
    with tempfile.TemporaryDirectory(prefix="heldout-") as tmp:
        for number, case in enumerate(cases):
            exercise = exercises[case.exercise]
            folder = Path(tmp) / f"{number:03d}"
            folder.mkdir()
            path = folder / exercise.student_file
            shutil.copyfile(CASES / case.file, path)
            for mode in modes:
                tasks[case.file, mode] = Task(exercise, path, seed=mode, root=folder)
        with Pool(workers, timeout=timeout) as pool:
            pool.run(list(tasks.values()))
    return tasks


def mode_name(mode: int | None) -> str:
    return "reference" if mode is None else f"seed {mode}"


def share(part: int, whole: int) -> str:
    return f"{part}/{whole} ({100 * part / whole:.0f}%)" if whole else "0/0"


def summary(cases: list[Case], outcomes: dict, mode: int | None) -> list[str]:
    """The figures of one mode."""
    wrong = [c for c in cases if not c.correct]
    right = [c for c in cases if c.correct]
    got = [outcomes[c.file, mode] for c in wrong]
    lost = [o for o in got if o.lost]
    named = sum(o.lost and o.named for o in got)
    localised = sum(o.lost and o.localised for o in got)
    either = sum(o.lost and (o.named or o.localised) for o in got)
    out = [
        f"== {mode_name(mode)}",
        f"wrong cases losing points:      {share(len(lost), len(got))}",
        f"  hint names the mistake:       {share(named, len(got))}",
        f"  hint localises the fault:     {share(localised, len(got))}",
        f"  named or localised:           {share(either, len(got))}",
        f"  wrong-direction hints:        {sum(o.lost and o.wrong_way for o in got)}",
        f"  losing points with no hint:   {sum(not o.hints for o in lost)}",
    ]
    bad = [(c, outcomes[c.file, mode]) for c in right if outcomes[c.file, mode].lost]
    out.append(f"correct rewrites losing points: {len(bad)} of {len(right)}")
    for case, outcome in bad:
        out.append(
            f"  {case.label}: {outcome.score:g}/{outcome.max_score:g} ({', '.join(outcome.failed)})"
        )
    return out


def per_exercise(cases: list[Case], outcomes: dict, modes: list[int | None]) -> list[str]:
    """Per exercise and mode: wrong cases losing points / named or localised / pointing the
    wrong way, and correct rewrites losing points."""
    out = [
        "per exercise, each mode: wrong lose points / named or localised / wrong way; "
        "correct rewrites losing points"
    ]
    for name in sorted({c.exercise for c in cases}):
        mine = [c for c in cases if c.exercise == name]
        cells = []
        for mode in modes:
            got = [outcomes[c.file, mode] for c in mine if not c.correct]
            lost = sum(o.lost for o in got)
            helped = sum(o.lost and (o.named or o.localised) for o in got)
            misled = sum(o.lost and o.wrong_way for o in got)
            right = sum(outcomes[c.file, mode].lost for c in mine if c.correct)
            cells.append(f"{lost}/{len(got)} {helped} {misled}; {right}")
        out.append(f"  {name[:24]:24s} " + " | ".join(f"{c:>14s}" for c in cells))
    return out


def table(cases: list[Case], outcomes: dict, modes: list[int | None]) -> list[str]:
    """One row per case: score and flags per mode."""
    width = max(len(c.label) for c in cases) + 4
    head = "case".ljust(width) + "".join(f"{mode_name(m):>16}" for m in modes)
    out = [head, "-" * len(head)]
    for case in cases:
        row = (case.label + (" *" if case.correct else "")).ljust(width)
        for mode in modes:
            o = outcomes[case.file, mode]
            row += f"{o.score:g}/{o.max_score:g} {o.flag(case.correct)}".rjust(16)
        out.append(row)
    out.append(
        "* correct rewrite.  Flags: ok full marks; N hint names the mistake; L hint cites "
        "its line; W a hint points the wrong way; - no hint; ? a hint that does none of "
        "these; LOST a correct rewrite loses points."
    )
    return out


def details(cases: list[Case], outcomes: dict, modes: list[int | None]) -> list[str]:
    """Per case and mode: the failed checks and every distinct hint (--verbose)."""
    out = []
    for case in cases:
        kind = "correct" if case.correct else f"wrong, line {case.lines}"
        out.append(f"\n# {case.label} ({kind}): {case.what}")
        for mode in modes:
            o = outcomes[case.file, mode]
            out.append(
                f"  [{mode_name(mode)}] {o.score:g}/{o.max_score:g} {o.flag(case.correct)}"
                + (f" failed: {', '.join(o.failed)}" if o.failed else "")
            )
            for hint in dict.fromkeys(o.hints):
                out.append(f"      {hint}")
    return out


def main(argv: list[str] | None = None) -> int:
    """Grade the held-out cases and print the table and the figures."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument(
        "--seed",
        type=int,
        nargs="*",
        default=[1, 2, 3],
        help="hidden-mode seeds (default 1 2 3; none: reference mode only)",
    )
    parser.add_argument("--workers", type=int, default=2, help="grading processes (1-2)")
    parser.add_argument("--timeout", type=float, default=30.0, help="seconds per check")
    parser.add_argument("--exercise", nargs="*", default=[], help="only these exercises")
    parser.add_argument("--verbose", action="store_true", help="print every case's hints")
    parser.add_argument(
        "--root",
        type=Path,
        default=None,
        help="grade with another checkout's lab/ and exercises/ (e.g. an older commit "
        "unpacked with git archive); default: this one",
    )
    parser.add_argument(
        "--cases",
        type=Path,
        default=None,
        help="another folder of held-out cases (its own cases.toml); default: this one",
    )
    args = parser.parse_args(argv)
    if args.cases is not None:
        global CASES
        CASES = args.cases.resolve()
    if args.root is not None:
        global ROOT
        ROOT = args.root.resolve()

    cases = load_cases(CASES / "cases.toml")
    if args.exercise:
        cases = [c for c in cases if any(c.exercise.startswith(e) for e in args.exercise)]
    modes: list[int | None] = [None, *args.seed]
    start = time.monotonic()
    tasks = grade(cases, modes, args.workers, args.timeout)
    outcomes = {}
    for case in cases:
        source = (CASES / case.file).read_text(encoding="utf-8").split("\n")
        for mode in modes:
            outcomes[case.file, mode] = judge(case, tasks[case.file, mode], source)

    wrong = sum(not c.correct for c in cases)
    per = {}
    for case in cases:
        per.setdefault(case.exercise, [0, 0])[case.correct] += 1
    lines = [
        f"grader: {Path(sys.modules['lab'].__file__).parent.parent} (exercises: {ROOT})",
        f"held-out cases: {len(cases)} ({wrong} wrong, {len(cases) - wrong} correct); "
        f"modes: {', '.join(mode_name(m) for m in modes)}",
        "per exercise (wrong + correct): "
        + ", ".join(f"{name[:2]} {w}+{c}" for name, (w, c) in sorted(per.items())),
        "",
        *table(cases, outcomes, modes),
    ]
    if args.verbose:
        lines += details(cases, outcomes, modes)
    lines.append("")
    lines += per_exercise(cases, outcomes, modes)
    lines.append("")
    for mode in modes:
        lines += summary(cases, outcomes, mode)
    lost_all = [c for c in cases if not c.correct and not outcomes[c.file, None].lost]
    if lost_all:
        lines.append(
            "wrong cases with full marks in reference mode: " + ", ".join(c.label for c in lost_all)
        )
    lines.append(f"graded {len(tasks)} tasks in {time.monotonic() - start:.0f} s")
    print("\n".join(lines))
    return 0


if __name__ == "__main__":
    sys.exit(main())

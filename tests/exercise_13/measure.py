"""Exercise 13's wrong and correct submissions graded (reference mode and hidden seed 1):
score and diagnosis per file, the figures of tests/exercise_13/BEFORE.txt and AFTER.txt.
The same measurement as tests/exercise_11/measure.py, for this exercise's folders.

    python tests/exercise_13/measure.py > tests/exercise_13/AFTER.txt
"""

from __future__ import annotations

import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
HERE = Path(__file__).resolve().parent
EXERCISE = ROOT / "exercises" / "13_svbrdf"
FILE = "svbrdf.glsl"
MODES = (None, 1)


def submissions() -> dict[str, Path]:
    """label -> file: the wrong ones (wrong/: written before the tuning; heldout/: after it,
    never tuned on), the solution, its correct rewrites and the stub."""
    solution = ROOT / "solutions" / EXERCISE.name
    files = {f"wrong/{p.stem}": p for p in sorted((HERE / "wrong").glob("*.glsl"))}
    files.update({f"heldout/{p.stem}": p for p in sorted((HERE / "heldout").glob("*.glsl"))})
    files.update({f"correct/{p.stem}": p for p in sorted((solution / "correct").glob("*.glsl"))})
    files["solution"] = solution / FILE
    files["stub"] = EXERCISE / FILE
    return files


def grade(workers: int = 2, timeout: float = 120.0) -> dict[tuple[str, int | None], object]:
    from lab.grading.exercise import load_exercise
    from lab.grading.runner import Pool, Task

    exercise = load_exercise(EXERCISE)
    tasks = {
        (label, mode): Task(exercise, path, mode)
        for label, path in submissions().items()
        for mode in MODES
    }
    with Pool(workers, timeout=timeout) as pool:
        pool.run(list(tasks.values()))
    return tasks


def named(label: str, task) -> bool:
    """Does some failed check's diagnosis carry the hint meant for this mistake (the file's
    `// HINT: words` line names words the hint must hold)?"""
    lines = submissions()[label].read_text(encoding="utf-8").splitlines()
    words = [ln.split("HINT:", 1)[1].strip() for ln in lines if "HINT:" in ln]
    said = " ".join(r.diagnosis for r in task.checks() if not r.passed)
    return bool(words) and all(w.lower() in said.lower() for w in words)


def main() -> int:
    tasks = grade()
    for (label, mode), task in sorted(tasks.items(), key=lambda kv: (kv[0][0], str(kv[0][1]))):
        hints = sorted({r.diagnosis for r in task.checks() if not r.passed and r.diagnosis})
        where = "reference" if mode is None else f"seed {mode}"
        flag = "named" if named(label, task) else "-"
        print(
            f"{label:28s} {where:9s} {task.score:4.1f}/{task.max_score:.0f} {flag:5s} "
            f"{' | '.join(h[:110] for h in hints) or 'no hint'}"
        )
    return 0


if __name__ == "__main__":
    sys.path.insert(0, str(ROOT))
    sys.exit(main())

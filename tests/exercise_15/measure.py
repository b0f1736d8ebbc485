"""Exercise 15's wrong and correct submissions graded (reference mode and hidden seed 1):
score and diagnosis per file, the figures of tests/exercise_15/BEFORE.txt and AFTER.txt.

    python tests/exercise_15/measure.py > tests/exercise_15/AFTER.txt
"""

from __future__ import annotations

import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
HERE = Path(__file__).resolve().parent
EXERCISE = ROOT / "exercises" / "15_spherical_harmonics"
MODES = (None, 1)


def submissions() -> dict[str, Path]:
    """label -> file: the wrong ones here (wrong/: written before the tuning; heldout/: after
    it, never tuned on), the solution, its correct rewrites and the stub."""
    solution = ROOT / "solutions" / EXERCISE.name
    files = {f"wrong/{p.stem}": p for p in sorted((HERE / "wrong").glob("*.glsl"))}
    # Written after the tuning and graded as they came: the held-out figure.
    files.update({f"heldout/{p.stem}": p for p in sorted((HERE / "heldout").glob("*.glsl"))})
    files.update({f"correct/{p.stem}": p for p in sorted((solution / "correct").glob("*.glsl"))})
    files["solution"] = solution / "sh_projection.glsl"
    files["stub"] = EXERCISE / "sh_projection.glsl"
    return files


def grade(workers: int = 2, timeout: float = 60.0) -> dict[tuple[str, int | None], object]:
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
    first line names the mistake; a `// HINT: words` line names words the hint must hold)?"""
    path = submissions()[label]
    lines = path.read_text(encoding="utf-8").splitlines()
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

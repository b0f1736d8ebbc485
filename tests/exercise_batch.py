"""The batch runner shared by tests/exercise_11..15/measure.py: one exercise's wrong and
correct submissions graded in reference mode and at hidden seed 1, score and diagnosis per
file (the figures of each folder's BEFORE.txt and AFTER.txt).

Each folder's measure.py names its exercise with `Batch(...)` and exposes the batch's
`submissions`, `named`, `grade` and `main`; its command stays
`python tests/exercise_NN/measure.py > tests/exercise_NN/AFTER.txt`.
"""

from __future__ import annotations

import sys
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from lab.grading.runner import Task

ROOT = Path(__file__).resolve().parents[1]
MODES: tuple[int | None, ...] = (None, 1)  # reference mode, then hidden seed 1


@dataclass(frozen=True)
class Batch:
    """One exercise's batch: its folder under tests/, its exercise, the file students write."""

    here: Path  # tests/exercise_NN: wrong/ (before tuning) and heldout/ (after it)
    exercise: str  # the folder under exercises/ and solutions/
    file: str  # the submission's file name (stub and solution)
    timeout: float = 60.0  # seconds per submission in the grading pool
    noise: bool = False  # print each check's noise ratio (estimator exercises)

    def submissions(self) -> dict[str, Path]:
        """label -> file: the wrong ones (wrong/: written before the tuning; heldout/: after
        it, never tuned on), the solution, its correct rewrites and the stub."""
        solution = ROOT / "solutions" / self.exercise
        files = {f"wrong/{p.stem}": p for p in sorted((self.here / "wrong").glob("*.glsl"))}
        # Written after the tuning and graded as they came: the held-out figure.
        held = sorted((self.here / "heldout").glob("*.glsl"))
        files.update({f"heldout/{p.stem}": p for p in held})
        correct = sorted((solution / "correct").glob("*.glsl"))
        files.update({f"correct/{p.stem}": p for p in correct})
        files["solution"] = solution / self.file
        files["stub"] = ROOT / "exercises" / self.exercise / self.file
        return files

    def grade(self, workers: int = 2) -> dict[tuple[str, int | None], Task]:
        """Every submission in every mode, graded by the grading pool."""
        from lab.grading.exercise import load_exercise
        from lab.grading.runner import Pool, Task

        exercise = load_exercise(ROOT / "exercises" / self.exercise)
        tasks = {
            (label, mode): Task(exercise, path, mode)
            for label, path in self.submissions().items()
            for mode in MODES
        }
        with Pool(workers, timeout=self.timeout) as pool:
            pool.run(list(tasks.values()))
        return tasks

    def named(self, label: str, task: Task) -> bool:
        """Does some failed check's diagnosis carry the hint meant for this mistake (a
        `// HINT: words` line in the file names words the hint must hold)?"""
        lines = self.submissions()[label].read_text(encoding="utf-8").splitlines()
        words = [ln.split("HINT:", 1)[1].strip() for ln in lines if "HINT:" in ln]
        said = " ".join(r.diagnosis for r in task.checks() if not r.passed)
        return bool(words) and all(w.lower() in said.lower() for w in words)

    def row(self, label: str, mode: int | None, task: Task) -> str:
        """One line of the table: label, mode, score, named flag, (noise,) hints."""
        hints = sorted({r.diagnosis for r in task.checks() if not r.passed and r.diagnosis})
        where = "reference" if mode is None else f"seed {mode}"
        flag = "named" if self.named(label, task) else "-"
        head = f"{task.score:4.1f}/{task.max_score:.0f} {flag:5s}"
        if not self.noise:
            said = " | ".join(h[:110] for h in hints) or "no hint"
            return f"{label:28s} {where:9s} {head} {said}"
        ratios = [r.extra.get("noise_ratio") for r in task.checks()]
        noise = "/".join(f"{x:.2f}" if x is not None else "-" for x in ratios)
        said = " | ".join(h[:100] for h in hints) or "no hint"
        return f"{label:34s} {where:9s} {head} noise {noise:11s} {said}"

    def main(self) -> int:
        """Grade the batch and print one line per file and mode."""
        sys.path.insert(0, str(ROOT))
        tasks = self.grade()
        for (label, mode), task in sorted(tasks.items(), key=lambda kv: (kv[0][0], str(kv[0][1]))):
            print(self.row(label, mode, task))
        return 0

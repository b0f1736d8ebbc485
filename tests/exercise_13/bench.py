"""grade-bench's per-exercise line for exercise 13 alone (grade-bench's own loop runs every
exercise): one wrong file graded warm, without and with the diagnosis, in reference mode and
hidden mode (seed 7), best of 5.

    python tests/exercise_13/bench.py
"""

from __future__ import annotations

import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def main() -> int:
    from lab.grading.bench import _best
    from lab.grading.checks import Grader
    from lab.grading.exercise import load_exercise
    from lab.grading.explain import Explainer

    exercise = load_exercise(ROOT / "exercises" / "13_svbrdf")
    plain, diagnosing = Grader(), Grader()
    diagnosing.explainer = Explainer(diagnosing)
    for name in ("mask_inverted", "world_axes", "no_sqrt"):
        with tempfile.TemporaryDirectory() as tmp:
            path = Path(tmp) / exercise.student_file
            path.write_text((Path(__file__).parent / "wrong" / f"{name}.glsl").read_text())
            plain_s, _ = _best(plain, exercise, path, None, 5)
            diagnosed_s, results = _best(diagnosing, exercise, path, None, 5)
            hidden_plain_s, _ = _best(plain, exercise, path, 7, 5)
            start = time.perf_counter()
            list(diagnosing.run(exercise, path, 7))
            cold_s = time.perf_counter() - start
            hidden_s, _ = _best(diagnosing, exercise, path, 7, 5)
        failed = [r for r in results if not r.passed]
        said = sum(1 for r in failed if r.diagnosis)
        print(
            f"wrong 13 {name:14s} {plain_s:5.3f} s, diagnosed {diagnosed_s:5.3f} s "
            f"({diagnosed_s - plain_s:+.3f} s, {said} of {len(failed)} failed checks named), "
            f"hidden mode {hidden_plain_s:5.3f} s, diagnosed {hidden_s:5.3f} s "
            f"({hidden_s - hidden_plain_s:+.3f} s; first in a worker {cold_s:5.3f} s)"
        )
    return 0


if __name__ == "__main__":
    sys.path.insert(0, str(ROOT))
    sys.exit(main())

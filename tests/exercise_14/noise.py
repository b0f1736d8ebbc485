"""The noise ratios behind exercise 14's `factor = 3.0`: each correct rewrite's RMS error at
32 samples per pixel over the solution's (uniform hemisphere sampling), and that of the
estimator that draws its random numbers once per pass (wrong/same_numbers, unbiased but
sqrt(32) times noisier), in reference mode and at 30 hidden seeds.

    python tests/exercise_14/noise.py > tests/exercise_14/NOISE.txt
"""

from __future__ import annotations

import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
SEEDS = 30


def main() -> int:
    from lab.grading.checks import Grader, hidden_variant, prepare
    from lab.grading.exercise import load_exercise

    exercise = load_exercise(ROOT / "exercises" / "14_reflection_equation")
    grader = Grader()
    correct = exercise.solution.parent / "correct"
    files = {p.stem: p for p in sorted(correct.glob("*.glsl"))}
    files["same_numbers"] = Path(__file__).parent / "wrong" / "same_numbers.glsl"
    readings = {name: prepare(exercise, path) for name, path in files.items()}
    solution = grader.solution_model(exercise)
    ratios: dict[tuple[str, str], list[float]] = {}
    for seed in [None, *range(SEEDS)]:
        for index, check in enumerate(exercise.checks):
            drawn = hidden_variant(check, solution, seed, index) if seed is not None else check
            expected = grader.expected(exercise, drawn, live=seed is not None)
            for name, reading in readings.items():
                result = grader.grade(exercise, drawn, reading.model, reading.code, expected)
                ratios.setdefault((name, check.name), []).append(result.extra["noise_ratio"])
    print(f"# noise ratio to the solution's, reference mode and hidden seeds 0-{SEEDS - 1}")
    for (name, check), values in ratios.items():
        values.sort()
        print(
            f"{name:22s} {check:22s} min {values[0]:.2f} median "
            f"{values[len(values) // 2]:.2f} max {values[-1]:.2f}"
        )
    return 0


if __name__ == "__main__":
    sys.path.insert(0, str(ROOT))
    sys.exit(main())

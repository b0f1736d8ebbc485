"""Reference images and values for the exercises, rendered from solutions/.

python -m lab.grading.references [EXERCISES_DIR]     (or brdf-lab grade --make-references)
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

from lab.grading.checks import VALUES_FILE, Grader, expected_value, render
from lab.grading.exercise import find_exercises
from lab.grading.explain import make_diagnosis
from lab.grading.kinds import kind_of
from lab.resources import data_dir


def make_references(root: str | Path, grader: Grader | None = None) -> list[Path]:
    """Write references/<check>.png and references/values.npz for each exercise under root."""
    grader = grader or Grader()
    written = []
    for exercise in find_exercises(root):
        model = grader.solution_model(exercise)
        folder = exercise.references
        folder.mkdir(exist_ok=True)
        values = {}
        for check in exercise.checks:
            reference = expected_value(render(grader.renderer, model, check), check)
            written += kind_of(check).save_reference(exercise, check, reference, values)
        stale = {p.name for p in folder.glob("*.png")} - {f"{c.name}.png" for c in exercise.checks}
        for name in stale:
            (folder / name).unlink()
        np.savez_compressed(folder / VALUES_FILE, **values)
        written.append(folder / VALUES_FILE)
        written += make_diagnosis(exercise, grader)
    return written


def main(argv: list[str] | None = None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    root = Path(argv[0]) if argv else data_dir("exercises")
    for path in make_references(root):
        print(f"wrote {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())

"""The exercises as the page's practice mode reads them (exercises.json).

Everything the grader decides from is computed here by the grader's own code, so the page
cannot drift from it: each check's kind (lab.grading.kinds) gives its inputs (the direction
pairs of probe and polar checks) and committed reference values or images; tolerances,
points and the stub come from exercise.toml. The page renders the student's file in WebGL
and compares as the probe, polar and sphere kinds do; a kind it cannot run is left out.
"""

from __future__ import annotations

from dataclasses import asdict

import numpy as np

from lab.grading.exercise import Exercise, ExerciseError, find_exercises
from lab.grading.kinds import VALUES_FILE, kind_of
from lab.resources import data_dir


def check_entry(exercise: Exercise, check, values) -> dict | None:
    """One check: its settings, inputs and committed reference (None: the page cannot
    run this kind of check; its kind says so)."""
    practice = kind_of(check).practice(exercise, check, values)
    if practice is None:
        return None
    entry = asdict(check)
    entry["lights"] = [[lt.theta, lt.phi, list(lt.rgb)] for lt in check.lights]
    entry["params"] = {k: list(v) if isinstance(v, tuple) else v for k, v in check.params.items()}
    return {**entry, **practice}


def exercise_entry(exercise: Exercise) -> dict:
    with np.load(exercise.references / VALUES_FILE) as values:
        entries = [check_entry(exercise, c, values) for c in exercise.checks]
    checks = [entry for entry in entries if entry is not None]
    return {
        "name": exercise.name,
        "title": exercise.title,
        "student_file": exercise.student_file,
        "stub": exercise.stub.read_text(encoding="utf-8"),
        "functions": exercise.functions,
        "wrapper": exercise.wrapper,
        "replaces": exercise.replaces,
        "checks": checks,
        "max_points": sum(entry["points"] for entry in checks),
    }


def exercises_manifest() -> dict:
    """Every shipped exercise; one that cannot be read is named with its error."""
    try:
        found = find_exercises(data_dir("exercises"))
    except ExerciseError as err:
        return {"exercises": [], "errors": [str(err)]}
    out, errors = [], []
    for exercise in found:
        try:
            out.append(exercise_entry(exercise))
        except (OSError, KeyError, ExerciseError) as err:
            errors.append(f"{exercise.name}: {err}")
    return {"exercises": out, "errors": errors}

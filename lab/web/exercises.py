"""The exercises as the page's practice mode reads them (exercises.json).

Everything the grader decides from is computed here by the grader's own code, so the page
cannot drift from it: the direction pairs of each probe and polar check (probe_angles,
polar_angles), the committed reference values and images, tolerances, points and the
stub. The page renders the student's file in WebGL and compares as compare_values and
compare_image do.
"""

from __future__ import annotations

import base64
from dataclasses import asdict

import numpy as np

from lab.grading.checks import VALUES_FILE, polar_angles, probe_angles, read_png
from lab.grading.exercise import Exercise, ExerciseError, find_exercises
from lab.resources import data_dir

WHAT = {"probe": "direction pairs", "polar": "points of the polar curve"}


def _floats(array: np.ndarray) -> str:
    return base64.b64encode(np.ascontiguousarray(array, dtype="<f4").tobytes()).decode()


def check_entry(exercise: Exercise, check, values) -> dict:
    """One check: its settings, inputs and committed reference."""
    entry = asdict(check)
    entry["lights"] = [[lt.theta, lt.phi, list(lt.rgb)] for lt in check.lights]
    entry["params"] = {k: list(v) if isinstance(v, tuple) else v for k, v in check.params.items()}
    if check.kind == "sphere":
        image = read_png(exercise.references / f"{check.name}.png")
        entry["reference"] = base64.b64encode(np.ascontiguousarray(image).tobytes()).decode()
        return entry
    angles = probe_angles(check) if check.kind == "probe" else polar_angles(check)
    entry["what"] = WHAT[check.kind]
    entry["angles"] = _floats(angles)  # degrees: theta_i, phi_i, theta_o, phi_o
    entry["expected"] = _floats(values[check.name][:, :3])
    entry["count"] = len(angles)
    return entry


def exercise_entry(exercise: Exercise) -> dict:
    with np.load(exercise.references / VALUES_FILE) as values:
        checks = [check_entry(exercise, c, values) for c in exercise.checks]
    return {
        "name": exercise.name,
        "title": exercise.title,
        "student_file": exercise.student_file,
        "stub": exercise.stub.read_text(encoding="utf-8"),
        "functions": exercise.functions,
        "wrapper": exercise.wrapper,
        "replaces": exercise.replaces,
        "checks": checks,
        "max_points": exercise.max_points,
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

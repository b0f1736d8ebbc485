"""The exercises as the page's practice mode reads them (exercises.json).

Everything the grader decides from is computed here by the grader's own code, so the page
cannot drift from it: each check's kind (lab.grading.kinds) gives its inputs (the direction
pairs of probe and polar checks) and committed reference values or images; tolerances,
points and the stub come from exercise.toml. The page renders the student's file in WebGL
and compares as the probe, polar and sphere kinds do, runs a sampler's chi-square and pdf
integral checks (static/sampling.js) and IBL render checks (static/iblcheck.js), and links
exercise 11's tests with their models (static/properties.js), draws exercise 13's textured
object with the check's textures (static/objectcheck.js), makes exercise 12's tables on
its GPU (static/tables.js) and runs exercise 15's harmonics against the lab's values
(static/shcheck.js); a kind it cannot run (its
`practice` gives None) is listed as the grader's alone.
"""

from __future__ import annotations

import base64
import zlib
from dataclasses import asdict

import numpy as np

from lab.grading import diagnosis, mistakes
from lab.grading.exercise import Exercise, ExerciseError, find_exercises
from lab.grading.kinds import VALUES_FILE, kind_of
from lab.ibl.integrator import ESTIMATOR_HOST, ESTIMATOR_LINE
from lab.resources import data_dir


def _packed(array: np.ndarray) -> str:
    """Little-endian bytes (float32 or uint8), zlib-compressed, base64: the page inflates
    them with DecompressionStream("deflate")."""
    dtype = "<u1" if array.dtype == np.uint8 else "<f4"
    raw = np.ascontiguousarray(array, dtype=dtype).tobytes()
    return base64.b64encode(zlib.compress(raw, 9)).decode()


def diagnosis_entry(check, stored: dict, hints: dict) -> dict:
    """What the grader's explainer reads for this check in practice mode (stored, not live):
    each known mistake's or mutant's values ("candidates", uint8 RGBA images for spheres)
    and the solution's values with each declared term alone ("terms")."""
    prefix = f"{check.name}|"
    candidates, terms = {}, {}
    for key, value in stored.items():
        if not key.startswith(prefix):
            continue
        name = key[len(prefix) :]
        if name.startswith("term."):
            terms[name[len("term.") :]] = _packed(value[..., :3])
        elif name in hints and check.kind == "sh":  # its values alone: row 1 is the truth
            candidates[name] = _packed(kind_of(check).shipped(check, value, 0))
        elif name in hints:
            candidates[name] = _packed(value)
    return {"candidates": candidates, "terms": terms}


def check_entry(exercise: Exercise, check, values, stored=None, hints=None) -> dict | None:
    """One check: its settings, inputs, committed reference and the stored values its
    diagnosis reads (None: the page cannot run this kind of check; its kind says so)."""
    kind = kind_of(check)
    practice = kind.practice(exercise, check, values)
    if practice is None:
        return None
    entry = asdict(check)
    entry["lights"] = [[lt.theta, lt.phi, list(lt.rgb)] for lt in check.lights]
    entry["params"] = {k: list(v) if isinstance(v, tuple) else v for k, v in check.params.items()}
    entry["diagnosis"] = diagnosis_entry(check, stored or {}, hints or {})
    seam = diagnosis.seam_rows(check, kind.angles(check)) if check.table else None
    if seam is not None:  # the rows across the table's periodic seam (diagnosis._seam)
        entry["diagnosis"]["seam"] = np.flatnonzero(seam).tolist()
    if check.kind == "polar":  # the lobe's angle in the plot (negative: the light's side)
        angles = kind.angles(check)
        theta = np.where(angles[:, 3] == check.phi_i % 360.0, -angles[:, 2], angles[:, 2])
        entry["lobe_theta"] = theta.tolist()
        entry["lobe_fit"] = lobe_fit(exercise, check, theta)
    return {**entry, **practice}


def grader_only(exercise: Exercise, values) -> list[dict]:
    """The checks the page cannot run, with why: the page lists them under its own."""
    out = []
    for check in exercise.checks:
        if kind_of(check).practice(exercise, check, values) is None:
            why = f"the page cannot run {check.kind} checks"
            if check.table:
                why = "the page lacks this check's table (no OpenGL where exercises.json was made)"
            out.append({"name": check.name, "kind": check.kind, "points": check.points, "why": why})
    return out


def lobe_fit(exercise: Exercise, check, theta: np.ndarray) -> dict:
    """The grader's width tables (diagnosis.width_table) for this polar check's lobe and
    for each term the page judges alone: the page fits the exponent or roughness of a
    lobe of the wrong width from the very numbers the grader fits it from."""
    settings = {"": {}}
    settings.update(
        (name, params)
        for name, spec in mistakes.read_terms(exercise).items()
        for params, defines, _ in [mistakes.term_parts(spec)]
        if not defines
    )
    side = theta[theta >= 0.0]
    return {
        name: diagnosis.width_table(exercise.model_name, {**check.params, **params}, check, side)
        for name, params in settings.items()
    }


def exercise_entry(exercise: Exercise) -> dict:
    hints = mistakes.read_hints(exercise)
    try:
        with np.load(exercise.references / mistakes.VALUES) as data:
            stored = {k: data[k] for k in data.files}
    except (OSError, ValueError):
        stored = {}  # no diagnosis references: the page names no likely mistake
    with np.load(exercise.references / VALUES_FILE) as values:
        entries = [check_entry(exercise, c, values, stored, hints) for c in exercise.checks]
        only_graded = grader_only(exercise, values)
    checks = [entry for entry in entries if entry is not None]
    return {
        "name": exercise.name,
        "title": exercise.title,
        "student_file": exercise.student_file,
        "stub": exercise.stub.read_text(encoding="utf-8"),
        "functions": exercise.functions,
        "wrapper": exercise.wrapper,
        "replaces": exercise.replaces,
        "sampler_for": exercise.sampler_for,  # a sampler exercise: the model it samples
        # With sampler_for: the file is the estimate itself, put between `line` and `host`
        # as the grader does (lab.ibl.integrator); `stand_in` gives the page's views without
        # an environment map (all but IBL) the map's function, which they never call.
        "estimator": {
            "line": ESTIMATOR_LINE,
            "host": ESTIMATOR_HOST,
            "stand_in": "vec3 environment(vec3 d) { return vec3(0.0); }\n",
        }
        if exercise.estimator
        else None,
        "loop_limit": exercise.loop_limit,  # the loop guard's limit for the student's loops
        # The library names the handout gives: the grader refuses others (scope.py), which
        # the page does not check and therefore names (static/exercise.js).
        "api": list(exercise.api),
        "checks": checks,
        "max_points": sum(entry["points"] for entry in checks),
        "grader_only": only_graded,
        "hints": hints,  # the grader's hint of each stored mistake (references/diagnosis.json)
        # Terms seen through macros (09's D, G, F) need a recompile the page does not do:
        # it judges the terms that parameter settings alone show.
        "terms": {
            k: {n: list(v) if isinstance(v, tuple) else v for n, v in t.items()}
            for k, t in mistakes.read_terms(exercise).items()
            if "define" not in t
        },
    }


def diagnosis_rules() -> dict:
    """lab/grading/diagnosis.py's words and thresholds, for the page's diagnosis.js (which
    carries the tests, not the sentences: header.js fill() fills the templates)."""
    from lab.grading import diagnosis

    return {
        "constants": [list(entry) for entry in diagnosis.CONSTANTS],
        "channels": list(diagnosis.CHANNELS),
        "match_share": diagnosis.MATCH_SHARE,
        "grazing": diagnosis.GRAZING,
        "words": diagnosis.WORDS,  # the sentences, str.format templates (lab/grading/words.py)
    }


def exercises_manifest() -> dict:
    """Every shipped exercise and the diagnosis' rules; one exercise that cannot be read is
    named with its error."""
    rules = diagnosis_rules()
    try:
        found = find_exercises(data_dir("exercises"))
    except ExerciseError as err:
        return {"exercises": [], "errors": [str(err)], "diagnosis": rules}
    out, errors = [], []
    for exercise in found:
        try:
            out.append(exercise_entry(exercise))
        except (OSError, KeyError, ExerciseError) as err:
            errors.append(f"{exercise.name}: {err}")
    return {"exercises": out, "errors": errors, "diagnosis": rules}

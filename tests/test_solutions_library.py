"""Each solution behaves exactly like the library code it re-implements.

The references students are graded against are rendered from solutions/, while the
views run shaders/. This ties the two: every solution, at the parameters of every one of
its checks, gives the library model's values on a dense set of direction pairs.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from lab.grading.checks import Grader
from lab.grading.exercise import find_exercises
from lab.models import MODEL_DIR, load_model

ROOT = Path(__file__).resolve().parent.parent
# A solution that is a BRDF (not a sampler, nor exercise 11's tests of a linked model, nor
# exercise 13's textured blend of two: tests/test_exercise_13_svbrdf.py ties its ends to
# the library's lambert and ward; nor exercise 12's lookup of a table the grader binds:
# tests/test_exercise_12_tabulated.py ties it to the lab's measured model on that table;
# nor exercise 15's harmonics, held to lab/measured/sh.py by tests/test_exercise_15_sh.py).
EXERCISES = [
    e
    for e in find_exercises(ROOT / "exercises")
    if not e.sampler_for
    and {c.kind for c in e.checks} not in ({"properties"}, {"object"}, {"sh"})
    and not any(getattr(c, "table", ()) for c in e.checks)
]
SAMPLERS = [e for e in find_exercises(ROOT / "exercises") if e.sampler_for and not e.estimator]


def library_model(exercise):
    """The library model a solution stands in for: its wrapper, or the model of that name."""
    name = exercise.wrapper or Path(exercise.student_file).stem
    assert (MODEL_DIR / f"{name}.glsl").is_file(), f"{exercise.name}: no library model {name}"
    return load_model(name)


def direction_pairs(count: int = 2000, seed: int = 7) -> np.ndarray:
    """(θi, φi, θo, φo) in degrees, uniform over the hemisphere up to 88°, plus the plane."""
    rng = np.random.default_rng(seed)
    theta = np.degrees(np.arccos(rng.uniform(np.cos(np.radians(88.0)), 1.0, (count, 2))))
    phi = rng.uniform(0.0, 360.0, (count, 2))
    pairs = np.stack([theta[:, 0], phi[:, 0], theta[:, 1], phi[:, 1]], axis=1)
    plane = np.array([[t, 0.0, o, 180.0] for t in (0, 30, 60, 80) for o in range(0, 89, 4)])
    return np.concatenate([pairs, plane])


@pytest.fixture(scope="module")
def grader():
    return Grader()


@pytest.mark.parametrize("exercise", EXERCISES, ids=[e.name for e in EXERCISES])
def test_solution_matches_library(exercise, grader):
    solution = grader.solution_model(exercise)
    library = library_model(exercise)
    angles = direction_pairs()
    settings = [check.params for check in exercise.checks] + [{}]
    defaults = {p.name: p.default for p in solution.params.values()}
    extra = set(library.params) - set(solution.params)
    assert not extra, f"{exercise.name}: the solution lacks the library's parameters {extra}"
    for params in settings:
        values = {**defaults, **params}  # the solution's own defaults, as graded
        ours = np.asarray(grader.renderer.eval_angles(solution, values, angles))
        theirs = np.asarray(grader.renderer.eval_angles(library, values, angles))
        assert np.isfinite(theirs).all()
        bad = ~np.isclose(ours, theirs, rtol=1e-4, atol=1e-6)
        if bad.any():
            row = int(np.argwhere(bad)[0][0])
            pytest.fail(
                f"{exercise.name} with {params}: {int(bad.any(axis=1).sum())} of {len(angles)} "
                f"pairs differ from shaders/brdfs/{library.name}.glsl; first at "
                f"(θi, φi, θo, φo) = {angles[row].round(2).tolist()}: solution "
                f"{ours[row].tolist()}, library {theirs[row].tolist()}"
            )


@pytest.mark.parametrize("exercise", SAMPLERS, ids=[e.name for e in SAMPLERS])
def test_sampler_solution_matches_library(exercise, grader):
    """A sampling exercise's solution has the pdf of the library's sampler for that model
    (shaders/samplers/, the lobe alone at the checks' kd = 0) and draws like it."""
    from lab.geometry import direction
    from lab.ibl.chisquare import pdf_integral
    from lab.ibl.integrator import IBLRenderer

    ibl = IBLRenderer(grader.renderer.ctx)
    solution = grader.solution_model(exercise)
    library = load_model(exercise.sampler_for)
    angles = direction_pairs(500)
    L = np.array([direction(t, p) for t, p in angles[:, :2]])
    V = np.array([direction(t, p) for t, p in angles[:, 2:]])
    for params in [check.params for check in exercise.checks]:
        ours = ibl.brdf_pdf(solution, params, L, V)
        theirs = ibl.brdf_pdf(library, params, L, V)
        assert np.allclose(ours, theirs, rtol=1e-4, atol=1e-6), params
        assert pdf_integral(ibl, solution, params, 40.0) == pytest.approx(
            pdf_integral(ibl, library, params, 40.0), abs=1e-4
        )

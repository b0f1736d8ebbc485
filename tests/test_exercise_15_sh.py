"""Exercise 15 (a BRDF lobe in spherical harmonics) and its check kind, `sh`.

The lab's values against closed forms; the solution full and the stub 0 in reference mode
and for 25 hidden seeds; the correct rewrites full on 10 seeds; each stored mistake loses
points with its own hint; the wrong submissions (tests/exercise_15/wrong, written before
the tuning) all lose points and the correct rewrites none; bad settings get words.
"""

from __future__ import annotations

import importlib.util
import math
import sys
from pathlib import Path

import numpy as np
import pytest

from lab.grading.checks import Grader, hidden_variant, prepare
from lab.grading.exercise import load_exercise
from lab.grading.kinds import kind_of
from lab.grading.kinds import properties as P
from lab.grading.spec import ExerciseError

ROOT = Path(__file__).resolve().parents[1]
EXERCISE = load_exercise(ROOT / "exercises" / "15_spherical_harmonics")
SEEDS = 25
HERE = ROOT / "tests" / "exercise_15"
# Loaded under its own name: each exercise folder of tests/ has a measure.py.
_spec = importlib.util.spec_from_file_location("exercise_15_measure", HERE / "measure.py")
measure = importlib.util.module_from_spec(_spec)
sys.modules["exercise_15_measure"] = measure
_spec.loader.exec_module(measure)


@pytest.fixture(scope="module")
def grader() -> Grader:
    return Grader()  # no explainer: scores only


def check_named(name: str):
    return next(c for c in EXERCISE.checks if c.name == name)


def test_the_labs_basis_has_the_textbook_low_bands():
    """Y_00 = 1/(2 sqrt(pi)); band 1 is sqrt(3/(4 pi)) (y, z, x) with the Condon-Shortley
    sign on m = +-1; the basis is orthonormal on a fine sphere quadrature."""
    from lab.measured import sh

    rng = np.random.default_rng(5)
    theta, phi = np.arccos(rng.uniform(-1, 1, 40)), rng.uniform(0, 2 * np.pi, 40)
    x, y, z = np.sin(theta) * np.cos(phi), np.sin(theta) * np.sin(phi), np.cos(theta)
    Y = sh.real_sh(1, theta, phi)
    c = math.sqrt(3.0 / (4.0 * math.pi))
    np.testing.assert_allclose(Y[:, 0], 0.5 / math.sqrt(math.pi))
    np.testing.assert_allclose(Y[:, 1:], np.stack([-c * y, c * z, -c * x], 1), atol=1e-12)
    grid = sh.hemisphere_grid(48, 96)
    both = np.concatenate([grid.theta, np.pi - grid.theta])
    basis = sh.real_sh(4, both, np.concatenate([grid.phi, grid.phi]))
    gram = basis.T @ (basis * np.concatenate([grid.weight, grid.weight])[:, None])
    np.testing.assert_allclose(gram, np.eye(25), atol=1e-9)


def test_the_labs_lambert_coefficients_match_the_closed_form(grader):
    """Lambert's odd-extended lobe (albedo / pi) z is (albedo / pi) sqrt(4 pi / 3) Y_10:
    that coefficient, every other one 0, at every light above the horizon."""
    check = check_named("lambert")
    kind = kind_of(check)
    truth = kind.truth(grader.renderer, P.target_model("lambert"), check)
    rows = kind.rows(check)
    albedo = np.array(check.params["albedo"])
    want = np.zeros_like(truth)
    want[(rows[:, 0] == 1) & (rows[:, 1] == 0)] = albedo / math.pi * math.sqrt(4 * math.pi / 3)
    np.testing.assert_allclose(truth, want, atol=2e-4)


def _scores(grader, files: dict[str, Path], seed: int | None) -> dict[str, tuple[float, list]]:
    """Each file's score at one setting (None: reference mode) and its failed checks."""
    out = {name: (0.0, []) for name in files}
    readings = {name: prepare(EXERCISE, path) for name, path in files.items()}
    solution = grader.solution_model(EXERCISE)
    for index, check in enumerate(EXERCISE.checks):
        drawn = hidden_variant(check, solution, seed, index) if seed is not None else check
        expected = grader.expected(EXERCISE, drawn, live=seed is not None)
        for name, reading in readings.items():
            assert not reading.error, (name, reading.error)
            result = grader.grade(EXERCISE, drawn, reading.model, reading.code, expected)
            score, failed = out[name]
            out[name] = (score + result.points, failed + ([] if result.passed else [check.name]))
    return out


def test_solution_full_and_stub_zero_in_every_mode(grader):
    files = {"solution": EXERCISE.solution, "stub": EXERCISE.stub}
    problems = []
    for seed in [None, *range(SEEDS)]:
        scores = _scores(grader, files, seed)
        if scores["solution"][0] != EXERCISE.max_points:
            problems.append(f"seed {seed}: solution fails {scores['solution'][1]}")
        if scores["stub"][0] != 0.0:
            problems.append(f"seed {seed}: stub scores {scores['stub'][0]}")
    assert not problems, "\n".join(problems)


def test_correct_rewrites_full_marks_on_ten_seeds(grader):
    files = {p.stem: p for p in sorted((EXERCISE.solution.parent / "correct").glob("*.glsl"))}
    assert len(files) >= 2
    for seed in [None, *range(10)]:
        for name, (score, failed) in _scores(grader, files, seed).items():
            assert score == EXERCISE.max_points, (seed, name, failed)


def test_hidden_mode_draws_new_directions_lights_and_parameters(grader):
    solution = grader.solution_model(EXERCISE)
    for index, check in enumerate(EXERCISE.checks):
        kind = kind_of(check)
        drawn = [hidden_variant(check, solution, seed, index) for seed in range(3)]
        rows = [kind.rows(d) for d in drawn]
        assert not np.array_equal(rows[0][:, 2:], rows[1][:, 2:]), check.name
        if kind.projects(check):
            assert drawn[0].params != drawn[1].params, check.name
            low, high = 10.0, 75.0
            assert all(((r[:, 2] >= low) & (r[:, 2] <= high)).all() for r in rows), check.name


@pytest.fixture(scope="module")
def graded(tmp_path_factory) -> dict:
    """With the diagnosis: each stored mistake (reference mode) and the wrong submissions
    with the correct rewrites (reference mode and hidden seed 1), in one pool."""
    from lab.grading.mistakes import known_mistakes
    from lab.grading.runner import Pool, Task

    tmp = tmp_path_factory.mktemp("mistakes15")
    solution = EXERCISE.solution.read_text(encoding="utf-8")
    tasks = {}
    for variant in known_mistakes(EXERCISE):
        path = tmp / variant.key / EXERCISE.student_file
        path.parent.mkdir()
        path.write_text(variant.apply(solution), encoding="utf-8")
        tasks["mistake", variant.key] = (Task(EXERCISE, path), variant.hint)
    for label, path in measure.submissions().items():
        for mode in measure.MODES:
            tasks["batch", label, mode] = (Task(EXERCISE, path, mode), "")
    with Pool(2, timeout=60.0) as pool:
        pool.run([task for task, _ in tasks.values()])
    return tasks


def test_each_stored_mistake_loses_points_with_its_own_hint(graded):
    missing, count = [], 0
    for key, (task, hint) in graded.items():
        if key[0] != "mistake":
            continue
        count += 1
        assert task.score < task.max_score, f"{key[1]} scores full marks"
        said = [r.diagnosis for r in task.checks() if not r.passed]
        if not any(hint[:40] in s for s in said):
            missing.append(f"{key[1]} ({hint[:50]}...): {said}")
    assert count >= 4 and not missing, "\n".join(missing)


def test_every_wrong_submission_loses_points_and_no_correct_one_does(graded):
    for key, (task, _) in graded.items():
        if key[0] != "batch":
            continue
        label = key[1]
        if label.startswith(("wrong/", "heldout/")):
            assert task.score < task.max_score, key
        elif label != "stub":
            assert task.score == task.max_score, (key, [r.message for r in task.checks()])


def test_the_wrong_submissions_are_named(graded):
    """The AFTER figure: every one of the 12 named in reference mode (BEFORE: 0)."""
    wrong = [k for k in graded if k[0] == "batch" and k[1].startswith("wrong/") and k[2] is None]
    named = [k[1] for k in wrong if measure.named(k[1], graded[k][0])]
    assert len(wrong) >= 8 and len(named) == len(wrong), sorted(set(wrong) - set(named))


def test_a_sign_or_a_factor_off_is_said_without_a_stored_mistake(grader):
    """explain(): the lab's values up to a sign on odd m, or up to one factor, are said in
    words; the lab's own values and unrelated ones say nothing."""
    check = check_named("basis.low_bands")
    kind = kind_of(check)
    truth = kind.truth(grader.renderer, P.target_model("lambert"), check)
    rows = kind.rows(check)

    def said(mine):
        return kind.explain(None, EXERCISE, check, None, None, np.stack([mine, truth]), False)

    assert said(truth) == ""
    flipped = np.where((rows[:, 1] % 2 != 0)[:, None], -truth, truth)
    assert "opposite sign wherever m is odd" in said(flipped)
    assert "times 3" in said(3.0 * truth)
    assert said(np.random.default_rng(1).normal(size=truth.shape)) == ""


def test_bad_settings_and_a_brdf_of_ones_own_get_words(tmp_path):
    """An unknown target, an order past 8; a file that defines BRDF itself is refused at its
    own line, before anything renders."""
    kind = kind_of(EXERCISE.checks[0])
    table = {"name": "x", "points": 1, "target": "no_such_model"}
    with pytest.raises(ExerciseError, match="no library model"):
        kind.parse(table, str(EXERCISE.folder / "exercise.toml"))
    with pytest.raises(ExerciseError, match="order must be 0 to 8"):
        kind.parse({"name": "x", "points": 1, "order": 9}, str(EXERCISE.folder / "exercise.toml"))
    path = tmp_path / EXERCISE.student_file
    code = EXERCISE.solution.read_text(encoding="utf-8")
    own = "vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) { return vec3(0.5); }\n"
    path.write_text(code + own, encoding="utf-8")
    error = prepare(EXERCISE, path).error
    assert f"sh_projection.glsl:{len(code.splitlines()) + 1}: remove your definition" in error


def test_a_loop_that_never_ends_is_named_at_its_line_in_both_parts(grader, tmp_path):
    """The lab's values are computed before the student's program runs, so the loop guard
    the grader reads after the render is the student's (a projection check too)."""
    path = tmp_path / EXERCISE.student_file
    code = EXERCISE.solution.read_text(encoding="utf-8")
    loop = "for (int k = 1; k <= m; ++k) {"
    path.write_text(code.replace(loop, "for (int k = 1; k >= 0; ++k) {"), encoding="utf-8")
    line = code[: code.index(loop)].count("\n") + 1
    reading = prepare(EXERCISE, path)
    from lab.grading.kinds import sh

    for name in ("basis.low_bands", "phong"):
        check = check_named(name)
        sh._TRUTHS.clear()  # the lab's values rendered anew, as for a first grade
        result = grader.grade(EXERCISE, check, reading.model, reading.code, None)
        assert f"sh_projection.glsl:{line}: the loop at line {line} did not end" in result.message

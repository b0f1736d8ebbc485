"""Exercise 11 (BRDF properties as code) and its check kind, `properties`.

The grader's own measurement against closed forms; the solution full and the stub (and a
test that always says "pass") 0 in reference mode and for 50 hidden seeds; the broken
subjects found at every seed; each stored mistake loses points with its own hint; the
held-out wrong submissions (tests/exercise_11/wrong, written before the tuning) all lose
points and the correct rewrites none.
"""

from __future__ import annotations

import importlib.util
import shutil
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
EXERCISE = load_exercise(ROOT / "exercises" / "11_brdf_properties")
SEEDS = 50
HERE = ROOT / "tests" / "exercise_11"
# Loaded under its own name: tests/heldout and tests/exercise_11 each have a measure.py.
_spec = importlib.util.spec_from_file_location("exercise_11_measure", HERE / "measure.py")
measure = importlib.util.module_from_spec(
    _spec
)  # the batch's own reader (also prints BEFORE/AFTER figures)
sys.modules["exercise_11_measure"] = measure  # its dataclasses look their module up
_spec.loader.exec_module(measure)


@pytest.fixture(scope="module")
def grader() -> Grader:
    return Grader()  # no explainer: scores only


def test_the_graders_measurement_matches_closed_forms(grader):
    """Lambert's albedo is its albedo at every view; Lambert with the cosine inside has
    albedo 2 kd / 3 and reciprocity error |cos L − cos V| / max(cos L, cos V): per channel."""
    renderer = grader.renderer
    views = np.array([[0.0, 0.0], [40.0, 30.0], [75.0, 200.0], [88.0, 10.0]])
    lambert = P.target_model("lambert")
    got = P.albedo_truth(renderer, lambert, {"albedo": (0.8, 0.5, 0.2)}, views)
    np.testing.assert_allclose(got, np.tile([0.8, 0.5, 0.2], (len(views), 1)), atol=2e-3)
    inside = P.target_model(str(EXERCISE.folder / "subjects" / "cosine_inside.glsl"))
    got = P.albedo_truth(renderer, inside, {"kd": (0.9, 0.3, 0.3)}, views)
    np.testing.assert_allclose(got, np.tile([0.6, 0.2, 0.2], (len(views), 1)), atol=2e-3)
    pairs = np.array([[20.0, 0.0, 60.0, 90.0], [70.0, 10.0, 10.0, 300.0], [30.0, 5.0, 30.0, 50.0]])
    err = P.reciprocity_truth(renderer, inside, {"kd": (0.9, 0.3, 0.3)}, pairs)
    cl, cv = np.cos(np.radians(pairs[:, 0])), np.cos(np.radians(pairs[:, 2]))
    want = np.abs(cl - cv) / np.maximum(cl, cv)
    np.testing.assert_allclose(err, np.repeat(want[:, None], 3, axis=1), atol=1e-5)


def test_the_measurement_matches_the_numpy_oracle_for_a_reciprocal_model(grader):
    """For a reciprocal model the albedo over L at V is lab.reference's albedo over V at L."""
    from lab import reference

    params = {"kd": (0.3, 0.3, 0.3), "ks": (0.5, 0.5, 0.5), "ke": 30.0}
    views = np.array([[10.0, 0.0], [60.0, 0.0], [85.0, 0.0]])
    got = P.albedo_truth(grader.renderer, P.target_model("phong"), params, views)
    for (theta, _), value in zip(views, got, strict=True):
        want = reference.directional_albedo("phong", params, float(theta))
        assert value == pytest.approx(np.asarray(want, float), rel=3e-3), theta


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


def test_solution_full_stub_and_always_pass_zero_in_every_mode(grader):
    files = {
        "solution": EXERCISE.solution,
        "stub": EXERCISE.stub,
        "always_pass": HERE / "wrong" / "always_pass.glsl",
    }
    problems = []
    for seed in [None, *range(SEEDS)]:
        scores = _scores(grader, files, seed)
        if scores["solution"][0] != EXERCISE.max_points:
            problems.append(f"seed {seed}: solution fails {scores['solution'][1]}")
        for name in ("stub", "always_pass"):
            if scores[name][0] != 0.0:
                problems.append(f"seed {seed}: {name} scores {scores[name][0]}")
    assert not problems, "\n".join(problems)


def test_correct_rewrites_full_marks_on_ten_seeds(grader):
    files = {p.stem: p for p in sorted((EXERCISE.solution.parent / "correct").glob("*.glsl"))}
    assert len(files) >= 2
    for seed in [None, *range(10)]:
        for name, (score, failed) in _scores(grader, files, seed).items():
            assert score == EXERCISE.max_points, (seed, name, failed)


def test_the_broken_subjects_are_broken_at_every_seed(grader):
    """What the checks on them are for: at every hidden setting the grader's measurement
    of gains_at_grazing passes 1 at a grazing view (well clear of the tolerance) and that
    of cosine_inside shows a large reciprocity error; the others stay reciprocal."""
    solution = grader.solution_model(EXERCISE)
    kind = kind_of(EXERCISE.checks[0])
    for seed in range(SEEDS):
        for index, check in enumerate(EXERCISE.checks):
            drawn = hidden_variant(check, solution, seed, index)
            target = P.target_model(drawn.options["target"])
            truth = kind.truth(grader.renderer, target, drawn)
            energy, reciprocal = kind.verdicts(drawn, truth, truth)
            n = kind.albedo_count(drawn)
            if check.name == "gains_at_grazing":
                assert truth[n - 1] > 1.2 and energy == "gains energy", (seed, truth[:n])
            if check.name == "cosine_inside":
                assert truth[n:].max() > 0.5 and reciprocal == "not reciprocal", seed
            if check.name in ("lambert", "phong", "ward", "no_horizon"):
                assert reciprocal == "reciprocal" and truth[n:].max() < 1e-3, (seed, check.name)


def test_hidden_mode_draws_the_targets_parameters_rows_and_frame(grader):
    solution = grader.solution_model(EXERCISE)
    index, check = next((i, c) for i, c in enumerate(EXERCISE.checks) if c.name == "phong")
    kind = kind_of(check)
    drawn = [hidden_variant(check, solution, seed, index) for seed in range(5)]
    assert len({d.params["ke"] for d in drawn}) == 5
    assert all(2.0 <= d.params["ke"] <= 60.0 for d in drawn)
    assert len({kind.rows(d)[0, 2] for d in drawn}) == 5
    assert len({tuple(kind.frame(d)[2]) for d in drawn}) == 5
    rows = kind.rows(drawn[0])
    assert (rows[:6, 0] == -1.0).all() and 80.0 <= rows[5, 2] <= 88.0
    assert (rows[6:, [0, 2]] < 90.0).all()


def test_a_check_names_a_target_that_exists(tmp_path):
    folder = tmp_path / "11_x"
    shutil.copytree(EXERCISE.folder / "subjects", folder / "subjects")
    text = (EXERCISE.folder / "exercise.toml").read_text(encoding="utf-8")
    wrong = text.replace('target = "phong"', 'target = "phongg"')
    (folder / "exercise.toml").write_text(wrong, "utf-8")
    with pytest.raises(ExerciseError, match="phongg.*neither a library model"):
        load_exercise(folder)
    text = text.replace('"subjects/cosine_inside.glsl"', '"subjects/missing.glsl"')
    (folder / "exercise.toml").write_text(text, "utf-8")
    with pytest.raises(ExerciseError, match="missing.glsl: no such file"):
        load_exercise(folder)


def test_the_page_gets_the_graders_rows_frame_and_measurement():
    """Practice mode (static/properties.js) runs what the grader runs: its rows and frame,
    the linked model's file, and the committed measurement it judges against."""
    with np.load(EXERCISE.references / "values.npz") as values:
        for check in EXERCISE.checks:
            kind = kind_of(check)
            entry = kind.practice(EXERCISE, check, values)
            np.testing.assert_array_equal(entry["rows"], kind.rows(check))
            np.testing.assert_array_equal(entry["frame"], kind.frame(check))
            np.testing.assert_array_equal(entry["truth"], values[check.name][1])
            linked = entry["linked_with"]
            if "source" in linked:
                assert linked["source"] == Path(check.options["target"]).read_text("utf-8")
                assert linked["path"].startswith("exercises/11_brdf_properties/subjects/")


@pytest.fixture(scope="module")
def graded(tmp_path_factory) -> dict:
    """With the diagnosis: each stored mistake (reference mode) and the held-out batch with
    the correct rewrites (reference mode and hidden seed 1), in one pool."""
    from lab.grading.mistakes import known_mistakes
    from lab.grading.runner import Pool, Task

    tmp = tmp_path_factory.mktemp("mistakes11")
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
    missing = []
    for key, (task, hint) in graded.items():
        if key[0] != "mistake":
            continue
        assert task.score < task.max_score, f"{key[1]} scores full marks"
        said = [r.diagnosis for r in task.checks() if not r.passed]
        if not any(hint[:40] in s for s in said):
            missing.append(f"{key[1]} ({hint[:50]}...): {said}")
    assert not missing, "\n".join(missing)


def test_every_held_out_wrong_submission_loses_points_and_no_correct_one_does(graded):
    for key, (task, _) in graded.items():
        if key[0] != "batch":
            continue
        label = key[1]
        if label.startswith(("wrong/", "heldout/")):
            assert task.score < task.max_score, key
        elif label != "stub":
            assert task.score == task.max_score, (key, [r.message for r in task.checks()])


def test_most_held_out_mistakes_are_named(graded):
    """The AFTER figure: at least 10 of the 14 named in reference mode (BEFORE: 0)."""
    named = [
        key[1]
        for key, (task, _) in graded.items()
        if key[0] == "batch" and key[1].startswith("wrong/") and key[2] is None
        if measure.named(key[1], task)
    ]
    assert len(named) >= 10, named


def test_a_brdf_of_the_students_own_is_refused(tmp_path):
    """A file that defines BRDF itself (to answer for the model) is refused before anything
    renders, at its own line, with or without the stub's include line."""
    path = tmp_path / EXERCISE.student_file
    code = EXERCISE.solution.read_text(encoding="utf-8")
    own = "vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) { return vec3(0.5); }\n"
    for text in (code, code.replace("// @include terms/brdf_stand_in.glsl\n", "")):
        path.write_text(text + own, encoding="utf-8")
        line = len(text.splitlines()) + 1
        error = prepare(EXERCISE, path).error
        assert f"properties.glsl:{line}: remove your definition of BRDF" in error, error


def test_a_clash_with_the_linked_model_is_reported_in_the_models_file(grader, tmp_path):
    """A helper named like one of the linked model's own functions clashes there: the
    compile error names the model's file and line, not a line past the student's file."""
    path = tmp_path / EXERCISE.student_file
    code = EXERCISE.solution.read_text(encoding="utf-8")
    path.write_text(code + "float microfacet_D(float x) { return x; }\n", encoding="utf-8")
    reading = prepare(EXERCISE, path)
    assert not reading.error, reading.error
    check = next(c for c in EXERCISE.checks if c.name == "cook_torrance")
    result = grader.grade(EXERCISE, check, reading.model, reading.code, None)
    assert not result.passed and "does not compile" in result.message
    assert result.errors[0].startswith("shaders/brdfs/cook_torrance.glsl:21:"), result.errors
    assert "rename your function" in result.errors[0]
    lambert = next(c for c in EXERCISE.checks if c.name == "lambert")  # no clash there
    assert grader.grade(EXERCISE, lambert, reading.model, reading.code, None).passed


def test_values_the_definitions_rule_out_are_named(grader):
    """Without a stored mistake to match: a constant test, a negative or above-1 reciprocity
    error and a negative albedo are each said in words; right-looking values say nothing."""
    check = next(c for c in EXERCISE.checks if c.name == "cosine_inside")
    kind = kind_of(check)
    target = P.target_model(check.options["target"])
    truth = kind.truth(grader.renderer, target, check)
    n = kind.albedo_count(check)

    def said(mine):
        return kind.explain(None, EXERCISE, check, None, None, np.stack([mine, truth]), False)

    assert said(truth) == ""
    constant = np.concatenate([np.ones(n), np.zeros(len(truth) - n)])
    assert "same value, 0, for every input" in said(constant)
    assert "negative at some pairs" in said(np.concatenate([truth[:n], -truth[n:]]))
    assert "above 1" in said(np.concatenate([truth[:n], 3.0 * truth[n:] + 0.5]))
    assert "albedo is negative" in said(np.concatenate([-truth[:n], truth[n:]]))
    # The channels reduced otherwise than by the largest, whatever the code: named by which.
    per = kind.channels(grader.renderer, target, check)
    mean = said(np.concatenate([per[:n].mean(axis=1), truth[n:]]))
    assert "directional_albedo returns the mean of the channels" in mean
    assert "reciprocity_error" not in mean and "largest channel" in mean
    assert said(np.concatenate([1.5 * truth[:n], truth[n:]])) == ""  # a factor is none
    # A model whose channels break reciprocity unequally (cosine_inside's do alike).
    check = next(c for c in EXERCISE.checks if c.name == "phong_illumination")
    per = kind.channels(grader.renderer, P.target_model(check.options["target"]), check)
    top = per.max(axis=1)
    mine = np.concatenate([top[:n], per[n:].min(axis=1)])
    smallest = kind.explain(None, EXERCISE, check, None, None, np.stack([mine, top]), False)
    assert "reciprocity_error returns the smallest channel" in smallest


def test_a_loop_that_never_ends_is_named_at_its_line(grader, tmp_path):
    """The measurement is made before the student's tests run, so the loop guard the grader
    reads after the render is theirs, at a first grade too (it read the measurement's)."""
    path = tmp_path / EXERCISE.student_file
    code = EXERCISE.solution.read_text(encoding="utf-8")
    loop = "for (int j = 0; j < N_PHI; ++j) {"
    path.write_text(code.replace(loop, "for (int j = 0; j >= 0; ++j) {"), encoding="utf-8")
    line = code[: code.index(loop)].count("\n") + 1
    reading = prepare(EXERCISE, path)
    check = next(c for c in EXERCISE.checks if c.name == "phong")
    P._TRUTHS.clear()  # measured anew, as for a first grade
    result = grader.grade(EXERCISE, check, reading.model, reading.code, None)
    assert f"properties.glsl:{line}: the loop at line {line} did not end" in result.message


def test_a_finer_grid_passes_and_a_stopped_loop_is_named_at_its_line(grader, tmp_path):
    """The guard counts every pass of a nested loop: a correct rule on a finer grid than the
    handout's (128 x 480 = 61,440 inner passes; 20,000 once stopped a 96-step rule) gets
    full marks, and a loop the guard does stop is named at its line, not as values that
    differ (the grader's own measurement used to render after the student's program; and
    llvmpipe ends loops past 65,535 passes silently, so the limit stays under that)."""
    path = tmp_path / EXERCISE.student_file
    code = EXERCISE.solution.read_text(encoding="utf-8")
    check = next(c for c in EXERCISE.checks if c.name == "phong")
    finer = code.replace("N_THETA = 64;", "N_THETA = 128;").replace("N_PHI = 256;", "N_PHI = 480;")
    path.write_text(finer, encoding="utf-8")
    reading = prepare(EXERCISE, path)
    assert grader.grade(EXERCISE, check, reading.model, reading.code, None).passed
    endless = code.replace("N_PHI = 256;", "N_PHI = 1100;")  # 64 x 1,100 = 70,400
    path.write_text(endless, encoding="utf-8")
    reading = prepare(EXERCISE, path)
    result = grader.grade(EXERCISE, check, reading.model, reading.code, None)
    line = next(n for n, t in enumerate(endless.splitlines(), 1) if "j < N_PHI" in t)
    assert not result.passed
    assert f"properties.glsl:{line}: the loop at line {line} did not end within" in result.message
    assert "every pass of the loops around it" in result.message, result.message

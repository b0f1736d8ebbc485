"""Exercise 14 (the reflection equation under an environment): the student's estimate
itself, run by the IBL view's pass (`estimator = true`), graded by ibl_render.

The solution full and the stub 0 in reference mode and for 50 hidden seeds; every correct
rewrite (cosine-weighted, Malley's method with a running mean, the whole sphere) full at
ten seeds, with its noise well inside the check's factor; hidden mode draws the model's
parameters and turns the studio; each stored mistake loses points with its own hint; the
wrong submissions written before the tuning (tests/exercise_14) all lose points; bad files
get a clear message, never a traceback.
"""

from __future__ import annotations

import importlib.util
import shutil
import sys
from pathlib import Path

import numpy as np
import pytest

from lab.grading import sampling
from lab.grading.checks import Grader, hidden_variant, prepare
from lab.grading.exercise import load_exercise
from lab.grading.spec import ExerciseError

ROOT = Path(__file__).resolve().parents[1]
EXERCISE = load_exercise(ROOT / "exercises" / "14_reflection_equation")
SEEDS = 50
HERE = ROOT / "tests" / "exercise_14"
# Loaded under its own name: other batches have a measure.py too.
_spec = importlib.util.spec_from_file_location("exercise_14_measure", HERE / "measure.py")
measure = importlib.util.module_from_spec(_spec)
sys.modules["exercise_14_measure"] = measure
_spec.loader.exec_module(measure)
CORRECT = {p.stem: p for p in sorted((EXERCISE.solution.parent / "correct").glob("*.glsl"))}


@pytest.fixture(scope="module")
def grader() -> Grader:
    return Grader()  # no explainer: scores only


def _graded(grader, files: dict[str, Path], seed: int | None) -> dict[str, list]:
    """Each file's results at one setting (None: reference mode), in the checks' order."""
    out: dict[str, list] = {name: [] for name in files}
    readings = {name: prepare(EXERCISE, path) for name, path in files.items()}
    solution = grader.solution_model(EXERCISE)
    for index, check in enumerate(EXERCISE.checks):
        drawn = hidden_variant(check, solution, seed, index) if seed is not None else check
        expected = grader.expected(EXERCISE, drawn, live=seed is not None)
        for name, reading in readings.items():
            assert not reading.error, (name, reading.error)
            out[name].append(grader.grade(EXERCISE, drawn, reading.model, reading.code, expected))
    return out


def test_solution_full_and_stub_zero_in_every_mode(grader, tmp_path):
    """The solution's own text replays the reference's random numbers (sampling.program_seed);
    the same code with a variable renamed draws others: a real test of the z-test's and the
    noise bound's false alarms, 100 grades at alpha = 1e-5 each."""
    renamed = tmp_path / EXERCISE.student_file
    renamed.write_text(EXERCISE.solution.read_text("utf-8").replace("sum", "total"), "utf-8")
    files = {"solution": EXERCISE.solution, "renamed": renamed, "stub": EXERCISE.stub}
    problems = []
    for seed in [None, *range(SEEDS)]:
        results = _graded(grader, files, seed)
        for name in ("solution", "renamed"):
            if sum(r.points for r in results[name]) != EXERCISE.max_points:
                problems.append(f"seed {seed}: {name} {[r.message for r in results[name]]}")
        if sum(r.points for r in results["stub"]) != 0.0:
            problems.append(f"seed {seed}: the stub scores")
    assert not problems, "\n".join(problems)


def test_any_unbiased_estimator_earns_full_marks_on_ten_seeds(grader):
    """Cosine-weighted sampling is less noisy than the solution's uniform sampling, the
    whole sphere noisier: all pass, the noisiest well inside the check's factor (3)."""
    assert len(CORRECT) >= 3
    ratios = []
    for seed in [None, *range(10)]:
        for name, results in _graded(grader, CORRECT, seed).items():
            assert all(r.passed for r in results), (seed, name, [r.message for r in results])
            ratios += [r.extra["noise_ratio"] for r in results]
    assert max(ratios) < 0.8 * min(c.options["factor"] for c in EXERCISE.checks), max(ratios)


def test_hidden_mode_draws_the_parameters_and_turns_the_studio(grader):
    solution = grader.solution_model(EXERCISE)
    index, studio = next((i, c) for i, c in enumerate(EXERCISE.checks) if "studio" in c.name)
    drawn = [hidden_variant(studio, solution, seed, index) for seed in range(5)]
    assert len({d.params["ke"] for d in drawn}) == 5
    assert all(1.0 <= d.params["ke"] <= 12.0 for d in drawn)
    assert len({round(d.phi_i, 3) for d in drawn}) == 5
    # The turn shows: the studio's softboxes light the sphere from elsewhere.
    images = [
        sampling.render_raw(grader.renderer, solution, studio.params, "studio", 16, 16, 4, 1, turn)
        for turn in (40.0, 160.0)
    ]
    lum = [sampling._luminance(im[1]) for im in images]
    assert np.abs(lum[0] - lum[1]).max() > 0.5 * lum[0].max()


@pytest.fixture(scope="module")
def graded(tmp_path_factory) -> dict:
    """With the diagnosis: each stored mistake (reference mode) and the batch with the
    correct rewrites (reference mode and hidden seed 1), in one pool."""
    from lab.grading.mistakes import known_mistakes
    from lab.grading.runner import Pool, Task

    tmp = tmp_path_factory.mktemp("mistakes14")
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
    with Pool(2, timeout=120.0) as pool:
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


def test_every_wrong_submission_loses_points_and_no_correct_one_does(graded):
    for key, (task, _) in graded.items():
        if key[0] != "batch":
            continue
        label = key[1]
        if label.startswith(("wrong/", "heldout/")) or label == "stub":
            assert task.score < task.max_score, key
        else:
            assert task.score == task.max_score, (key, [r.message for r in task.checks()])


def test_the_wrong_submissions_are_named(graded):
    """The AFTER figures: of the 13 written before the tuning, all named in reference mode
    and 12 at hidden seed 1 (BEFORE: 1 and 0)."""
    for mode, least in ((None, 13), (1, 12)):
        named = [
            key[1]
            for key, (task, _) in graded.items()
            if key[0] == "batch" and key[1].startswith("wrong/") and key[2] == mode
            if measure.named(key[1], task)
        ]
        assert len(named) >= least, (mode, named)


def _prepared(tmp_path, text: str):
    path = tmp_path / EXERCISE.student_file
    path.write_text(text, encoding="utf-8")
    return prepare(EXERCISE, path)


def test_bad_files_are_refused_with_what_to_do(tmp_path):
    code = EXERCISE.solution.read_text(encoding="utf-8")
    error = _prepared(tmp_path, code.replace("estimate_radiance", "estimate_radiant")).error
    assert "function estimate_radiance is missing" in error, error
    own = code + "vec2 random2() { return vec2(0.5); }\n"
    error = _prepared(tmp_path, own).error
    assert "random2" in error and f"{EXERCISE.student_file}:" in error, error
    library = code.replace("float cos_t = u.x;", "float cos_t = sample_cosine(u, N, X, Y).z;")
    error = _prepared(tmp_path, library).error
    assert "sample_cosine" in error, error


def test_a_broken_estimate_fails_in_words(grader, tmp_path):
    """NaN, an endless loop and a compile error each fail the checks with a message."""
    code = EXERCISE.solution.read_text(encoding="utf-8")
    broken = {
        "nan": code.replace("return sum / float(n);", "return sum * sqrt(V.z - 2.0);"),
        "endless": code.replace("for (int i = 0; i < n; ++i)", "for (int i = 0; i >= 0; ++i)"),
        "typo": code.replace("return sum / float(n);", "return sum / float(n)"),
    }
    said = {}
    for name, text in broken.items():
        reading = _prepared(tmp_path, text)
        assert not reading.error, (name, reading.error)
        for check in EXERCISE.checks:
            expected = grader.expected(EXERCISE, check, live=False)
            result = grader.grade(EXERCISE, check, reading.model, reading.code, expected)
            assert not result.passed and result.message, (name, result.message)
            said[name] = result.message + " ".join(result.errors)
    assert "NaN" in said["nan"], said["nan"]
    assert "loop" in said["endless"], said["endless"]
    assert f"{EXERCISE.student_file}:" in said["typo"], said["typo"]


def test_an_estimator_exercise_is_graded_by_renders_only(tmp_path):
    folder = tmp_path / "14_x"
    shutil.copytree(EXERCISE.folder, folder)
    text = (folder / "exercise.toml").read_text(encoding="utf-8")
    (folder / "exercise.toml").write_text(text.replace('sampler_for = "blinn_phong"\n', ""))
    with pytest.raises(ExerciseError, match="estimator = true needs sampler_for"):
        load_exercise(folder)
    extra = '\n[[checks]]\nname = "x"\nkind = "pdf_integral"\npoints = 1\n'
    (folder / "exercise.toml").write_text(text + extra, encoding="utf-8")
    with pytest.raises(ExerciseError, match='pdf_integral.*use kind = "ibl_render"'):
        load_exercise(folder)

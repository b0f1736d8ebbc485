"""The registry of check kinds: a new kind is its module alone.

`extra_kinds` (in tests/) adds a kind the grader has never heard of (reciprocity, with its
own exercise.toml key, render, comparison and report figure). Once its package is
registered, exercise.toml can use it, references are made for it, the grader grades it in
its workers, and the reports show its section, with no other edit.
"""

from __future__ import annotations

import shutil
from pathlib import Path

import numpy as np
import pytest

from lab.grading import kinds
from lab.grading.exercise import ExerciseError, load_exercise

ROOT = Path(__file__).resolve().parent.parent
PHONG = ROOT / "solutions" / "02_phong" / "phong.glsl"
TOML = """title = "Reciprocity"
student_file = "phong.glsl"
functions = ["vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y)"]

[[checks]]
name = "helmholtz"
kind = "reciprocity"
points = 4
seed = 7
samples = {samples}
params = {{ ke = 20.0 }}
"""


@pytest.fixture
def extra_kinds():
    kinds.add_package("extra_kinds")
    yield kinds.find("reciprocity")
    kinds.remove_package("extra_kinds")


def course(tmp: Path, samples: object = 48) -> Path:
    """exercises/01_recip and solutions/01_recip, the stub and solution of 02_phong."""
    folder = tmp / "exercises" / "01_recip"
    folder.mkdir(parents=True)
    (tmp / "solutions" / "01_recip").mkdir(parents=True)
    shutil.copy(ROOT / "exercises" / "02_phong" / "phong.glsl", folder / "phong.glsl")
    shutil.copy(PHONG, tmp / "solutions" / "01_recip" / "phong.glsl")
    (folder / "exercise.toml").write_text(TOML.format(samples=samples), encoding="utf-8")
    return folder


def test_the_lab_kinds_are_registered():
    assert kinds.names() == (
        "probe",
        "sphere",
        "polar",
        "chi_square",
        "pdf_integral",
        "ibl_render",
        "properties",  # exercise 11's tests of a linked model
        "bin_edges",  # exercise 12's pairs on a table's bin grid
        "object",  # exercise 13's spatially varying BRDF on the textured object
        "sh",  # exercise 15's real harmonics and a linked model's lobe coefficients
    )


def test_an_unregistered_kind_is_named_in_a_clear_error(tmp_path):
    with pytest.raises(ExerciseError, match=r"check kind 'reciprocity' is not one of probe, "):
        load_exercise(course(tmp_path))


def test_a_kind_parses_and_checks_its_own_keys(extra_kinds, tmp_path):
    check = load_exercise(course(tmp_path)).checks[0]
    assert (check.kind, check.options, check.points) == ("reciprocity", {"samples": 48}, 4)
    assert check.params == {"ke": 20.0}
    with pytest.raises(ExerciseError, match=r"samples = 'many' should be a whole number"):
        load_exercise(course(tmp_path / "words", samples='"many"'))
    with pytest.raises(ExerciseError, match="samples must be at least 1"):
        load_exercise(course(tmp_path / "zero", samples=0))


def test_a_new_kind_is_graded_and_reported_with_no_other_edit(extra_kinds, tmp_path):
    from lab.grading import report
    from lab.grading.references import make_references
    from lab.grading.runner import Pool, Task
    from lab.web.exercises import exercise_entry

    exercise = load_exercise(course(tmp_path))
    written = make_references(tmp_path / "exercises")
    assert exercise.references / "values.npz" in written
    with np.load(exercise.references / "values.npz") as data:
        stored = data["helmholtz"]
    assert stored.shape == (2, 48, 3)  # f(L, V) and f(V, L) of the solution: reciprocal
    assert np.allclose(stored[0], stored[1], rtol=1e-4, atol=1e-6) and stored.max() > 0.05

    code = PHONG.read_text(encoding="utf-8")
    lopsided = tmp_path / "lopsided" / "phong.glsl"  # times N.L: not reciprocal
    lopsided.parent.mkdir()
    lopsided.write_text(
        code.replace("return kd", "return NoL * (kd").replace("ke);", "ke));"), encoding="utf-8"
    )
    brighter = tmp_path / "brighter" / "phong.glsl"  # reciprocal, but not the solution
    brighter.parent.mkdir()
    brighter.write_text(code.replace("kd * INV_PI", "kd * 0.5"), encoding="utf-8")
    tasks = [
        Task(exercise, exercise.solution),
        Task(exercise, lopsided),
        Task(exercise, brighter),
        Task(exercise, exercise.solution, seed=5),  # hidden mode: the solution rendered live
    ]
    with Pool(1, timeout=20.0) as pool:
        pool.run(tasks)
    good, bad, off, hidden = (t.checks()[0] for t in tasks)
    assert good.passed and good.points == 4 and good.message == "f(L, V) = f(V, L) on all 48 pairs"
    assert bad.status == "failed" and bad.points == 0
    assert bad.message.split(". Where: ")[0].endswith("of 48 pairs break reciprocity")
    assert int(bad.message.split()[0]) > 40
    assert off.message.split(". Where: ")[0] == "48 of 48 pairs differ from the solution"
    assert hidden.passed and hidden.setting["seed"] == 5

    page = report.html_report(tasks[:2])
    forward, backward = bad.extra["worst"]
    assert forward != pytest.approx(backward, rel=1e-3)
    assert f"worst pair: f(L, V) = {forward:.4g}, f(V, L) = {backward:.4g}" in page
    assert page.count('<figure class="reciprocity">') == 2
    results = report.gradescope(tasks[:2], 1.0)
    assert [t["name"] for t in results["tests"]] == ["01_recip.helmholtz"] * 2
    assert exercise_entry(exercise)["checks"] == []  # the web page cannot run it: left out

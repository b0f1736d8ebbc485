"""The exercise format: one table (lab.grading.schema) validates every exercise when it is
loaded and writes docs/exercise-format.md; each broken file stops with file:line and what to
write, never a traceback or lost points."""

from __future__ import annotations

import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from lab.grading import kinds, mistakes, schema
from lab.grading.exercise import ExerciseError, find_exercises, load_exercise

ROOT = Path(__file__).resolve().parents[1]
DOC = ROOT / "docs" / "exercise-format.md"


def test_format_reference_is_generated_from_the_schema():
    """The committed doc is what the schema writes now, and names every key of both files."""
    text = DOC.read_text(encoding="utf-8")
    assert text == schema.reference_markdown(), (
        "docs/exercise-format.md is stale: python -m lab.grading.schema > docs/exercise-format.md"
    )
    builtin = [k for k in kinds.all_kinds().values() if k.__module__.startswith("lab.grading.")]
    keys = [*schema.EXERCISE, *schema.CHECK, *schema.MISTAKE, *schema.TERM, *schema.MISTAKES_TOP]
    keys += [key for kind in builtin for key in schema.kind_keys(kind)]
    for key in keys:
        assert f"| `{key.name}` |" in text, key.name
    for kind in builtin:
        assert kind.name in text


def test_every_committed_exercise_and_mistake_list_is_valid():
    for exercise in find_exercises(ROOT / "exercises"):
        mistakes.validate(exercise)  # edits apply to the solution, terms name parameters


def test_check_defaults_in_the_schema_are_the_graders():
    """The reference documents the defaults the grader really uses (spec.Check's)."""
    from lab.grading.spec import Check

    for key in schema.CHECK:
        if key.name in ("name", "kind", "points", "params", "ranges", "purpose", "lights"):
            continue
        default = getattr(Check("x", "probe", 1.0), key.name)
        assert default == key.default or list(default) == key.default, key.name


@pytest.fixture
def phong(tmp_path) -> Path:
    """A copy of exercise 02 with its solution, to break."""
    for top in ("exercises", "solutions"):
        shutil.copytree(ROOT / top / "02_phong", tmp_path / top / "02_phong")
    return tmp_path / "exercises" / "02_phong"


def edit(path: Path, old: str, new: str) -> None:
    text = path.read_text(encoding="utf-8")
    assert old in text, old
    path.write_text(text.replace(old, new, 1), encoding="utf-8")


def line_of(path: Path, text: str) -> int:
    """The last line holding `text` (a repeated name is reported where it repeats)."""
    return [n for n, ln in enumerate(path.read_text().splitlines(), 1) if text in ln][-1]


BROKEN_EXERCISE = [
    # (old, new, the line holding this text, words the message must hold)
    ("ke = 50.0 }", "kee = 50.0 }", "kee = 50.0", ["'kee'", "did you mean 'ke'", "kd, ks, ke"]),
    ("points = 3\nseed = 201", "pointz = 3\nseed = 201", "pointz", ["'pointz'", "'points'"]),
    ("points = 3\nseed = 201", 'points = "3"\nseed = 201', 'points = "3"', ["a number"]),
    (
        "theta_i = 40.0",
        "theta_i = 40.0\nlights = [[1.0, 2.0]]",
        "lights = [[1.0",
        ["polar", "remove"],
    ),
    ('kind = "probe"', 'kind = "prob"', 'kind = "prob"', ["'prob'", "probe, sphere"]),
    ("ke = [20.0, 1000.0]", "ke = [20.0, 5000.0]", "ke = [20.0, 5000.0]", ["[1, 1000]", "narrow"]),
    ("ke = 50.0 }", "ke = [1, 2, 3] }", "ke = [1, 2, 3]", ["params.ke", "a number"]),
    ('title = "', 'titel = "', "titel", ["'titel'", "did you mean 'title'"]),
    ('name = "probe.broad"', 'name = "probe.sharp"', 'name = "probe.sharp"', ["two checks"]),
    ('vec3 Y)"]', 'vec3 Y"]', "functions", ["not a GLSL signature"]),
    ("seed = 201", 'seed = 201\nsame = [["kd", "kdd"]]', "same = ", ["same names 'kdd'"]),
    ('student_file = "phong.glsl"', 'student_file = "../phong.glsl"', "student_file", [".glsl"]),
]


@pytest.mark.parametrize("old,new,where,words", BROKEN_EXERCISE)
def test_a_broken_exercise_toml_stops_with_its_line(phong, old, new, where, words):
    spec = phong / "exercise.toml"
    edit(spec, old, new)
    with pytest.raises(ExerciseError) as caught:
        load_exercise(phong)
    message = str(caught.value)
    assert message.startswith(f"{spec}:{line_of(spec, where)}: "), message
    for word in words:
        assert word in message, (word, message)


def test_a_misspelt_parameter_stops_the_grade_command_not_the_student(phong):
    """Before, a misspelt parameter was dropped and students lost points; now `grade` exits
    with status 2 and one line naming the file and line."""
    spec = phong / "exercise.toml"
    edit(spec, "ke = 50.0 }", "kee = 50.0 }")
    done = subprocess.run(
        [sys.executable, "-m", "lab.cli", "grade", str(phong)], capture_output=True, text=True
    )
    assert done.returncode == 2, done.stderr
    assert f"{spec}:{line_of(spec, 'kee')}:" in done.stderr
    assert "internal error" not in done.stderr and "Traceback" not in done.stderr


BROKEN_MISTAKES = [
    (
        "'2.0 * NoL * N - L', 'reflect(L, N)'",
        "'2.0 * NoL * N -  L', 'reflect(L, N)'",
        "-  L",
        ["mistake 3", "is not in", "phong.glsl", "'vec3 R = 2.0 * NoL * N - L;'"],
    ),
    ('hint = "the diffuse', 'hintt = "the diffuse', "hintt", ["'hintt'", "did you mean 'hint'"]),
    ("specular = { kd", "specular = { kdd", "specular = { kdd", ["terms.specular", "'kdd'"]),
    ("edits = [['kd * INV_PI', 'kd']]", "edits = ['kd * INV_PI']", "edits = ['kd", ["pairs"]),
]


@pytest.mark.parametrize("old,new,where,words", BROKEN_MISTAKES)
def test_a_broken_mistakes_toml_stops_with_its_line(phong, old, new, where, words):
    path = phong.parent.parent / "solutions" / "02_phong" / "mistakes.toml"
    edit(path, old, new)
    with pytest.raises(ExerciseError) as caught:
        mistakes.validate(load_exercise(phong))
    message = str(caught.value)
    assert message.startswith(f"{path}:{line_of(path, where)}: "), message
    for word in words:
        assert word in message, (word, message)


def test_make_references_with_a_bad_edit_is_a_usage_error(phong):
    path = phong.parent.parent / "solutions" / "02_phong" / "mistakes.toml"
    edit(path, "'kd * INV_PI', 'kd'", "'kd * INVPI', 'kd'")
    done = subprocess.run(
        [sys.executable, "-m", "lab.cli", "grade", str(phong), "--make-references"],
        capture_output=True,
        text=True,
    )
    assert done.returncode == 2, done.stderr
    assert "is not in" in done.stderr and "internal error" not in done.stderr

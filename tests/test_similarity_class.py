"""The similarity report on a whole class (tests/similarity_class.py): pairs are listed for
what two students share beyond every reference, weighted by rarity in the class.

Measured (27 students, seeds 1 to 3; SPIR-V one operand level deep): the author of an
idiosyncratic file and two disguised copies share weight 14.0 to 15.1 (Blinn-Phong) and
20.3 (Cook-Torrance), 94 to 100 % of the smaller remainder; every other pair (correct
answers written differently, two students with the same common mistake) at most 9.9."""

from __future__ import annotations

from pathlib import Path

import pytest
from similarity_class import TEMPLATES, disguise, make_class

from lab.grading import similarity, spirv
from lab.grading.exercise import load_exercise

ROOT = Path(__file__).resolve().parent.parent
needs_tools = pytest.mark.skipif(not spirv.available(), reason="spirv-tools not installed")


def report(exercise, files: dict[str, str]) -> list[similarity.Match]:
    return similarity.compare_class(
        {n: {exercise.name: (t, None)} for n, t in files.items()}, [exercise]
    )


@needs_tools
@pytest.mark.parametrize("name", sorted(TEMPLATES))
def test_only_the_copies_of_an_idiosyncratic_file_are_listed_as_pairs(name):
    exercise = load_exercise(ROOT / "exercises" / name)
    files, copies = make_class(exercise, 27, seed=1)
    matches = report(exercise, files)
    pairs = {tuple(sorted((m.a.owner, m.b.owner))) for m in matches if m.pair}
    assert pairs == copies
    weights = [m.shared for m in matches if m.pair]
    assert min(weights) >= 1.2 * similarity.MIN_SHARED, weights  # a margin, not a knife edge
    listed = [m.a.owner for m in matches if not m.pair]
    assert len(listed) == len(set(listed)), "a student is listed against a reference once"
    assert not {"author", "copier_a", "copier_b"} & set(listed)


@needs_tools
def test_a_class_of_correct_answers_equal_to_the_solution_lists_no_pair(tmp_path):
    """Lambert: every correct answer compiles to the solution's code. Twelve students who
    hand in the solution disguised are listed once each against it, never in pairs, and
    the page says why."""
    import random

    exercise = load_exercise(ROOT / "exercises" / "01_lambert")
    solution = exercise.solution.read_text(encoding="utf-8")
    rng = random.Random(3)
    files = {f"s{n:02d}": disguise(solution, rng) for n in range(12)}
    matches = report(exercise, files)
    assert not [m for m in matches if m.pair]
    assert sorted(m.a.owner for m in matches) == sorted(files)
    assert {m.b.owner for m in matches} <= {"solution", "library"}
    similarity.write_html(matches, tmp_path / "s.html")
    page = (tmp_path / "s.html").read_text(encoding="utf-8")
    assert "No pair of students shares enough code beyond the references" in page
    assert page.count("<tr><td>01_lambert</td>") == 12


def test_only_wrong_values_that_no_third_student_has_count():
    """A common mistake gives many students the same wrong values: no copying signal."""
    wrong = {
        "a": {"values": "x", "grazing": "q"},
        "b": {"values": "x", "grazing": "q"},
        "c": {"values": "x"},
        "d": {"grazing": "r"},
    }
    rare = similarity._rare_wrongs(wrong)
    assert rare["a"] == {"grazing": "q"} and rare["b"] == {"grazing": "q"}
    assert rare["c"] == {} and rare["d"] == {}


def test_a_mark_two_students_have_weighs_one_and_a_common_one_little():
    students = [{"x", "common"}, {"x", "common"}, *({"common", str(n)} for n in range(18))]
    rarity = similarity.Rarity.of(students, [{"ref"}])
    assert rarity.weight["x"] == pytest.approx(1.0)
    assert rarity.weight["common"] < 0.05
    assert rarity.mass({"x", "ref"}) == pytest.approx(1.0)

"""Exercise 10 (importance sampling) and its check kinds chi_square, pdf_integral and
ibl_render: the stub scores 0, the solution full marks, a wrong half (sampler or pdf) is
named, a broken exercise.toml is reported, and the reports carry the new checks."""

from __future__ import annotations

import json
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from lab.grading.checks import Grader
from lab.grading.exercise import ExerciseError, load_exercise
from lab.grading.explain import Explainer

ROOT = Path(__file__).resolve().parent.parent
EXERCISE = load_exercise(ROOT / "exercises" / "10_importance_sampling")
MAIN = "import sys; from lab.cli import main; sys.exit(main(sys.argv[1:]))"


@pytest.fixture(scope="module")
def grader(ctx):
    grader = Grader()
    grader.explainer = Explainer(grader)
    return grader


def edited(tmp_path: Path, edits: list[tuple[str, str]]) -> Path:
    text = EXERCISE.solution.read_text(encoding="utf-8")
    for old, new in edits:
        assert old in text, old
        text = text.replace(old, new, 1)
    path = tmp_path / EXERCISE.student_file
    path.write_text(text, encoding="utf-8")
    return path


def grade(grader, path: Path, seed: int | None = None) -> dict:
    return {r.name: r for r in grader.run(EXERCISE, path, seed)}


def test_stub_scores_zero_and_the_solution_full_marks(grader):
    stub = grade(grader, EXERCISE.stub)
    assert all(r.points == 0 and r.status == "failed" for r in stub.values()), stub
    assert "integrates to 0.000" in stub["chi_square.glossy"].message
    solution = grade(grader, EXERCISE.solution)
    assert sum(r.points for r in solution.values()) == EXERCISE.max_points == 10
    hidden = grade(grader, EXERCISE.solution, seed=123)
    assert all(r.passed for r in hidden.values()), [r.message for r in hidden.values()]
    chi = hidden["chi_square.glossy"]
    assert chi.setting["params"]["ke"] != 20.0  # hidden mode drew another exponent


def test_the_chi_square_names_the_wrong_half(grader, tmp_path):
    """Mistakes in no list: a pdf of the wrong power (the samples are the solution's), and
    a sampler of the wrong shape (the pdf is the solution's)."""
    pdf = grade(grader, edited(tmp_path, [("pow(NoH, ke)", "pow(NoH, ke + 1.0)")]))
    chi = pdf["chi_square.glossy"]
    assert not chi.passed and "the pdf is what is wrong" in chi.diagnosis, chi.message
    assert not pdf["pdf_integral.views"].passed
    sampler = grade(
        grader, edited(tmp_path, [("pow(max(u.x, 1e-30), 1.0 / (ke + 1.0))", "sqrt(u.x)")])
    )
    chi = sampler["chi_square.glossy"]
    assert not chi.passed and "the sampler is what is wrong" in chi.diagnosis, chi.message
    # The pdf is the solution's, but not the density of this sampler's draws: more of them
    # fail (a wider lobe of half vectors), so the integral misses their share.
    integral = sampler["pdf_integral.views"]
    assert not integral.passed and "the pdf does not describe the sampler" in integral.message
    assert set(chi.images) == {"your pdf", "your samples", "solution's pdf"}


def test_a_compile_error_points_at_the_students_line(grader, tmp_path):
    path = edited(tmp_path, [("float phi = 2.0 * PI * u.y;", "float phi = 2.0 * PI * u.w;")])
    results = grade(grader, path)
    line = path.read_text().splitlines().index("    float phi = 2.0 * PI * u.w;") + 1
    for result in results.values():
        assert "does not compile" in result.message and f":{line}:" in result.message


def test_an_endless_loop_in_the_sampler_is_named_not_graded(grader, tmp_path):
    """llvmpipe ends any loop after 65,535 iterations, so without the guard this sampler
    would draw the right samples and earn full marks; on a real GPU it freezes the screen."""
    loop = "    float x = 1.0;\n    while (x < 2.0) { x += 1e-30 * x; }\n"
    path = edited(
        tmp_path,
        [("    float phi = 2.0 * PI * u.y;\n", "    float phi = 2.0 * PI * u.y;\n" + loop)],
    )
    line = path.read_text().splitlines().index("    while (x < 2.0) { x += 1e-30 * x; }") + 1
    results = grade(grader, path)
    for name, result in results.items():  # every check runs the sampler (pdf_integral too)
        assert result.points == 0 and result.loop_line == line, (name, result.message)
        assert f"{path.name}:{line}: the loop at line {line} did not end" in result.message
    assert all(r.passed for r in grade(grader, EXERCISE.solution).values())  # nothing sticks


@pytest.mark.parametrize(
    "old,new,words",
    [
        ("views = [[10.0, 0.0], [70.0, 130.0]]", "views = [[95.0, 0.0]]", "0 <= theta < 90"),
        (
            "samples = 100000\nalpha = 0.002\nranges = { ke = [8.0, 400.0] }",
            "samples = 10\nalpha = 0.002\nranges = { ke = [8.0, 400.0] }",
            "samples must",
        ),
        ('environment = "grey_room"', 'environment = "moon"', "is not one of"),
        ("tolerance = 0.005", 'tolerance = "small"', "should be a number"),
    ],
)
def test_a_broken_check_table_is_reported(tmp_path, old, new, words):
    folder = tmp_path / "10_importance_sampling"
    shutil.copytree(EXERCISE.folder, folder)
    spec = folder / "exercise.toml"
    text = spec.read_text()
    assert old in text
    spec.write_text(text.replace(old, new, 1))
    with pytest.raises(ExerciseError, match=words) as info:
        load_exercise(folder)
    assert "exercise.toml" in str(info.value)


def test_json_and_html_reports_carry_the_sampling_checks(tmp_path):
    """`brdf-lab grade` with the stub: results.json (Gradescope's format) lists the four
    checks at 0 points; the HTML report shows the histograms and the renders."""
    out, page = tmp_path / "results.json", tmp_path / "report.html"
    args = ["grade", str(EXERCISE.folder), "--json", str(out), "--html", str(page)]
    done = subprocess.run([sys.executable, "-c", MAIN, *args], capture_output=True, text=True)
    assert done.returncode in (0, 1), done.stderr
    results = json.loads(out.read_text())
    tests = {t["name"]: t for t in results["tests"]}
    assert set(tests) == {f"{EXERCISE.name}.{c.name}" for c in EXERCISE.checks}
    assert all(t["score"] == 0 and t["status"] == "failed" for t in tests.values())
    assert results["score"] == 0
    html = page.read_text()
    for caption in ("your samples", "your pdf", "converged"):
        assert caption in html

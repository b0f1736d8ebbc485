"""`brdf-lab watch`: the GLFW viewer compiles, reports errors with lines, finds references."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from lab.app.watch import ExerciseView
from lab.app.watch_sampler import SamplerView
from lab.grading.checks import Grader, read_png
from lab.grading.exercise import load_exercise
from lab.models import MODEL_DIR

ROOT = Path(__file__).parent.parent

if sys.platform.startswith("linux") and not os.environ.get("DISPLAY"):
    pytest.skip("needs a display: run under xvfb-run -a", allow_module_level=True)


def run_watch(path: Path) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-m", "lab.cli", "watch", str(path), "--frames", "2"],
        capture_output=True,
        text=True,
        timeout=120,
        cwd=Path(__file__).parent.parent,
    )


def test_watch_compiles_and_reports_errors_with_lines(tmp_path):
    good = (MODEL_DIR / "phong.glsl").read_text().replace("@model phong", "@model student")
    path = tmp_path / "student.glsl"
    path.write_text(good)
    result = run_watch(path)
    assert result.returncode == 0, result.stderr
    assert "compiled student.glsl: OK" in result.stdout
    lines = good.splitlines()
    line = next(i for i, text in enumerate(lines, 1) if "return kd" in text)
    lines[line - 1] = lines[line - 1].replace("return kd", "return kd +")
    path.write_text("\n".join(lines) + "\n")
    result = run_watch(path)
    assert result.returncode == 0
    assert f"student.glsl:{line}:" in result.stdout
    assert "Traceback" not in result.stderr


def copy_exercise(tmp_path: Path, name: str, solved: bool) -> Path:
    folder = tmp_path / name
    shutil.copytree(ROOT / "exercises" / name, folder)
    exercise = load_exercise(folder)
    if solved:
        shutil.copy(ROOT / "solutions" / name / exercise.student_file, folder)
    return folder / exercise.student_file


@pytest.mark.parametrize("name", ["02_phong", "06_microfacet_distributions"])
def test_exercise_file_is_shown_as_the_grader_renders_it(tmp_path, renderer, name):
    """Solved: the sphere matches the reference; the stub: it visibly does not."""
    solved = ExerciseView.find(copy_exercise(tmp_path / "a", name, solved=True))
    stub_path = copy_exercise(tmp_path / "b", name, solved=False)
    stub = ExerciseView.find(stub_path)
    assert solved and stub
    reference = read_png(solved.reference_path).astype(int)
    mine = solved.sphere(
        renderer, solved.load(solved.exercise.folder / solved.exercise.student_file)
    )
    assert np.abs(mine.astype(int) - reference).max() <= 5
    theirs = stub.sphere(renderer, stub.load(stub_path))
    assert (np.abs(theirs.astype(int) - reference) > 5).mean() > 0.01
    result = run_watch(stub_path)
    assert result.returncode == 0, result.stderr
    assert f"exercise {name}: showing check" in result.stdout


def test_a_sampler_file_is_judged_as_the_grader_judges_it(tmp_path, renderer):
    """Exercise 10: the watched file is the student's sampler. The checks it reruns at each
    save give the grader's verdicts and messages, and the samples' histogram is shown."""
    name = "10_importance_sampling"
    assert ExerciseView.find(copy_exercise(tmp_path / "s", name, solved=True)) is None
    for solved in (True, False):
        path = copy_exercise(tmp_path / str(solved), name, solved=solved)
        view = SamplerView.find(path)
        assert view is not None and {c.kind for c in view.checks} == {"chi_square", "pdf_integral"}
        lines, panels = view.judge(renderer, view.load(path))
        graded = {r.name: r for r in Grader().run(view.exercise, path)}
        for check, line in zip(view.checks, lines, strict=False):
            result = graded[check.name]
            assert (
                line
                == f"  {check.name}: {'passed' if result.passed else 'FAILED'}: {result.message}"
            )
        assert all(graded[c.name].passed == solved for c in view.checks)
        assert "ibl_render.grey_room" in lines[-1]  # named as left to the grader
        samples = panels[0][..., :3].astype(int)
        histogram = samples[90:230, 10:310]  # inside the caption and the margins
        # Solved: the samples fill the histogram's top rows; the stub draws none.
        assert (histogram.max(axis=2) > 100).mean() > 0.05 if solved else histogram.max() < 10
    result = run_watch(path)
    assert result.returncode == 0, result.stderr
    assert "judged by the grader's checks" in result.stdout
    assert "chi_square.glossy: FAILED" in result.stdout


def test_an_estimator_file_is_judged_by_its_renders(tmp_path, renderer):
    """Exercise 14: the watched file is the student's estimate. Its ibl_render checks (a
    fraction of a second each) rerun at each save with the grader's verdicts, and the window
    shows the render run long beside the reference."""
    name = "14_reflection_equation"
    for solved in (True, False):
        path = copy_exercise(tmp_path / str(solved), name, solved=solved)
        view = SamplerView.find(path)
        assert view is not None and {c.kind for c in view.checks} == {"ibl_render"}
        lines, panels = view.judge(renderer, view.load(path))
        graded = {r.name: r for r in Grader().run(view.exercise, path)}
        for check, line in zip(view.checks, lines, strict=True):
            result = graded[check.name]
            verdict = "passed" if result.passed else "FAILED"
            assert line == f"  {check.name}: {verdict}: {result.message}"
            assert result.passed == solved
        assert len(panels) == 3
    result = run_watch(path)
    assert result.returncode == 0, result.stderr
    assert "your estimator, judged by the checks" in result.stdout
    assert "ibl_render.grey_room: FAILED" in result.stdout

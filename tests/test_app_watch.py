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
from lab.grading.checks import read_png
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

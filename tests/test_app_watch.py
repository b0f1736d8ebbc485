"""`brdf-lab watch`: the GLFW viewer compiles, reports errors with lines, finds references."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from lab.models import MODEL_DIR

if sys.platform.startswith("linux") and not os.environ.get("DISPLAY"):
    pytest.skip("needs a display: run under xvfb-run -a", allow_module_level=True)


def run_watch(path: Path) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-m", "lab.cli", "watch", str(path), "--frames", "2"],
        capture_output=True, text=True, timeout=120, cwd=Path(__file__).parent.parent,
    )


def test_watch_compiles_and_reports_errors_with_lines(tmp_path):
    exercise = tmp_path / "exercises" / "01_phong"
    (exercise / "references").mkdir(parents=True)
    from PIL import Image

    Image.fromarray(np.zeros((64, 64, 4), np.uint8)).save(exercise / "references" / "sphere.png")
    good = (MODEL_DIR / "phong.glsl").read_text().replace("@model phong", "@model student")
    path = exercise / "student.glsl"
    path.write_text(good)
    result = run_watch(path)
    assert result.returncode == 0, result.stderr
    assert "compiled student.glsl: OK" in result.stdout
    assert "reference image:" in result.stdout
    lines = good.splitlines()
    line = next(i for i, text in enumerate(lines, 1) if "return kd" in text)
    lines[line - 1] = lines[line - 1].replace("return kd", "return kd +")
    path.write_text("\n".join(lines) + "\n")
    result = run_watch(path)
    assert result.returncode == 0
    assert f"student.glsl:{line}:" in result.stdout
    assert "Traceback" not in result.stderr

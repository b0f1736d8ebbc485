"""The hidden-mode seed line tells a student what they can run (practice mode: hidden mode
needs solutions/, which students do not have) and that the instructor can rerun the exact
grade; `grade --seed` without solutions/ says so in one line instead of failing."""

from __future__ import annotations

import re
import shutil
import subprocess
import sys
from pathlib import Path

from lab.grading import seed

ROOT = Path(__file__).resolve().parent.parent


def student_checkout(tmp_path: Path) -> Path:
    """A student's copy of the lab: the exercise with their file in it, no solutions/."""
    home = tmp_path / "home"
    shutil.copytree(ROOT / "exercises" / "02_phong", home / "exercises" / "02_phong")
    return home


def brdf_lab(home: Path, *args: str) -> subprocess.CompletedProcess:
    command = [sys.executable, "-m", "lab.cli", *args]
    return subprocess.run(command, cwd=home, capture_output=True, text=True, timeout=300)


def test_the_seed_line_gives_a_command_a_student_can_run(tmp_path):
    line = seed.reproduce_line(4242, ["02_phong"])
    assert "seed 4242" in line and "instructor" in line and "--seed 4242" in line
    command = re.search(r"(brdf-lab grade [^()]*?--from exercises)", line)
    assert command, line
    assert "--seed" not in command.group(1)  # what the student runs needs no solutions
    home = student_checkout(tmp_path)
    done = brdf_lab(home, *command.group(1).split()[1:])
    assert done.returncode in (0, 1), done.stderr  # 1: the stub fails checks
    assert "total 0/10" in done.stdout and "Traceback" not in done.stderr


def test_hidden_mode_without_solutions_is_one_clear_line(tmp_path):
    home = student_checkout(tmp_path)
    done = brdf_lab(home, "grade", "exercises/02_phong", "--seed", "4242")
    assert done.returncode == 2 and "Traceback" not in done.stderr
    lines = done.stderr.strip().splitlines()
    assert len(lines) == 1, done.stderr
    assert "--seed (hidden mode) renders the solutions live" in lines[0]
    assert "solutions/02_phong/phong.glsl is not there" in lines[0]
    assert "practice mode" in lines[0] and "--submission YOUR_FILE" in lines[0]


def test_the_reproduce_command_prints_the_line():
    done = subprocess.run(
        [sys.executable, "-m", "lab.grading.seed", "reproduce", "7", "01_lambert", "02_phong"],
        capture_output=True,
        text=True,
    )
    assert done.stdout.strip() == seed.reproduce_line(7, ["01_lambert", "02_phong"])

"""`brdf-lab course init/check` and the Classroom workflow it writes: the workflow grades
with the instructor's pinned definitions in hidden mode, so editing the student's copy of
the checks changes nothing.
"""

from __future__ import annotations

import hashlib
import json
import os
import re
import shutil
import subprocess
import sys
import tarfile
import textwrap
from pathlib import Path

import pytest
from setuptools import build_meta
from wheel_helpers import ROOT

from lab.cli import main
from lab.grading import course

VENV_BIN = Path(sys.executable).parent
COMMIT = "3f2a9c1d" + "0" * 32
PUBLISHED = "https://github.com/example/course/releases/download/v1/definitions.tar.gz"
TAMPER = "\nrtol = 1e9\natol = 1e9\nthreshold = 1000.0\nmax_fraction = 1.0\n"


@pytest.fixture(scope="module")
def sdist(tmp_path_factory) -> Path:
    """This checkout's sdist: the pinned release archive the workflow grades with."""
    out = tmp_path_factory.mktemp("sdist")
    cwd = os.getcwd()
    os.chdir(ROOT)
    try:
        name = build_meta.build_sdist(str(out))
    finally:
        os.chdir(cwd)
    with tarfile.open(out / name) as archive:
        names = archive.getnames()
    for needed in ("shaders/brdfs/phong.glsl", "solutions/02_phong/phong.glsl", "LICENSE"):
        assert any(n.endswith(needed) for n in names), needed
    assert not any("node_modules" in n or "__pycache__" in n for n in names)
    return out / name


def grade_step(workflow: Path) -> str:
    """The shell script of the workflow's grading step, as GitHub runs it."""
    text = workflow.read_text()
    block = text.split("- name: Grade the exercises", 1)[1].split("run: |\n", 1)[1]
    lines = []
    for line in block.splitlines():
        if line.strip() and not line.startswith(" " * 10):
            break
        lines.append(line)
    return textwrap.dedent("\n".join(lines))


def run_workflow(repo: Path, tmp: Path, archive: Path) -> dict:
    """Run the grading step in `repo` as GitHub Actions would; returns the Classroom result."""
    settings = course.workflow_settings((repo / course.WORKFLOW).read_text())
    runner_temp = tmp / "runner"
    runner_temp.mkdir(exist_ok=True)
    env = {
        **{k: v for k, v in os.environ.items() if k != "PYTHONPATH"},
        **settings,
        "DEFINITIONS_URL": archive.as_uri(),  # the published copy: the same bytes, offline
        "GITHUB_SHA": COMMIT,
        "RUNNER_TEMP": str(runner_temp),
        "PATH": f"{VENV_BIN}{os.pathsep}{os.environ['PATH']}",
    }
    (repo / "classroom-result.json").unlink(missing_ok=True)
    done = subprocess.run(
        ["bash", "-e", "-c", grade_step(repo / course.WORKFLOW)],
        cwd=repo,
        env=env,
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert done.returncode == 0, done.stderr[-3000:]
    assert f"seed {int(COMMIT[:7], 16)}" in done.stdout
    return json.loads((repo / "classroom-result.json").read_text())


def scores(result: dict) -> dict[str, float]:
    return {t["name"]: t["score"] for t in result["tests"]}


@pytest.fixture(scope="module")
def repo(sdist, tmp_path_factory) -> Path:
    target = tmp_path_factory.mktemp("course") / "template"
    assert main(["course", "init", str(target), "--exercises", "01", "02_phong",
                 "--definitions", str(sdist), "--definitions-url", PUBLISHED]) == 0  # fmt: skip
    return target


def test_init_writes_a_complete_template_without_solutions(repo, sdist, capsys):
    assert main(["course", "check", str(repo)]) == 0
    assert "complete" in capsys.readouterr().out
    assert sorted(p.name for p in (repo / "exercises").iterdir()) == ["01_lambert", "02_phong"]
    assert not list(repo.rglob("solutions"))
    stub = (repo / "exercises" / "02_phong" / "phong.glsl").read_bytes()
    assert stub == (ROOT / "exercises" / "02_phong" / "phong.glsl").read_bytes()
    settings = course.workflow_settings((repo / course.WORKFLOW).read_text())
    assert settings["DEFINITIONS_SHA256"] == hashlib.sha256(sdist.read_bytes()).hexdigest()
    assert settings["EXERCISES"] == "01_lambert 02_phong"
    assert settings["DEFINITIONS_URL"] == PUBLISHED
    assert "exercises/01_lambert" in (repo / "README.md").read_text()


def test_check_names_what_is_missing_or_leaked(repo, tmp_path, capsys):
    broken = tmp_path / "broken"
    shutil.copytree(repo, broken)
    (broken / "exercises" / "02_phong" / "README.md").unlink()
    shutil.copy(
        ROOT / "solutions" / "01_lambert" / "lambert.glsl", broken / "exercises" / "01_lambert"
    )
    (broken / "solutions").mkdir()
    workflow = broken / course.WORKFLOW
    workflow.write_text(re.sub(r"[0-9a-f]{64}", "none", workflow.read_text()))
    assert main(["course", "check", str(broken)]) == 1
    out = capsys.readouterr().out
    assert "exercises/02_phong/README.md is missing" in out
    assert "exercises/01_lambert/lambert.glsl is the solution" in out
    assert "solutions/ is in the repository" in out
    assert "DEFINITIONS_SHA256 is not a SHA-256 checksum" in out


def test_check_refuses_a_local_definitions_address(tmp_path, sdist, capsys):
    target = tmp_path / "local"
    assert (
        main(["course", "init", str(target), "--exercises", "02", "--definitions", str(sdist)]) == 0
    )
    assert main(["course", "check", str(target)]) == 1
    assert "is not a web address GitHub's runners can download" in capsys.readouterr().out


def test_a_changed_archive_fails_the_checksum(repo, tmp_path):
    student = tmp_path / "student"
    shutil.copytree(repo, student)
    other = tmp_path / "other.tar.gz"
    shutil.make_archive(str(tmp_path / "other"), "gztar", ROOT, "exercises")
    settings = course.workflow_settings((student / course.WORKFLOW).read_text())
    path = f"{VENV_BIN}{os.pathsep}{os.environ['PATH']}"
    env = {**os.environ, **settings, "DEFINITIONS_URL": other.as_uri(), "GITHUB_SHA": COMMIT,
           "RUNNER_TEMP": str(tmp_path), "PATH": path}  # fmt: skip
    done = subprocess.run(
        ["bash", "-e", "-c", grade_step(student / course.WORKFLOW)],
        cwd=student, env=env, capture_output=True, text=True, timeout=120,
    )  # fmt: skip
    assert done.returncode != 0 and "FAILED" in done.stdout + done.stderr
    assert not (student / "classroom-result.json").exists()


def test_init_refuses_an_archive_without_the_definitions(tmp_path, capsys):
    fake = tmp_path / "fake.tar.gz"
    shutil.make_archive(str(tmp_path / "fake"), "gztar", ROOT / "shaders")
    assert main(["course", "init", str(tmp_path / "t"), "--definitions", str(fake)]) == 2
    assert "lacks exercises/01_lambert/exercise.toml" in capsys.readouterr().err


def test_editing_the_students_copy_does_not_change_the_grade(repo, sdist, tmp_path):
    student = tmp_path / "student"
    shutil.copytree(repo, student)
    shutil.copy(ROOT / "solutions" / "02_phong" / "phong.glsl", student / "exercises" / "02_phong")
    honest = run_workflow(student, tmp_path, sdist)
    phong = [n for n in scores(honest) if "02_phong" in n]
    lambert = [n for n in scores(honest) if "01_lambert" in n]
    assert phong and lambert
    assert all(scores(honest)[n] > 0 for n in phong)  # the solved exercise passes
    assert all(scores(honest)[n] == 0 for n in lambert)  # the stub does not

    # The cheat: tolerances widened, and a "solution" for hidden mode that is the stub.
    toml = student / "exercises" / "01_lambert" / "exercise.toml"
    toml.write_text(re.sub(r'(kind = "\w+")', lambda m: m.group(1) + TAMPER, toml.read_text()))
    fake = student / "solutions" / "01_lambert"
    fake.mkdir(parents=True)
    shutil.copy(student / "exercises" / "01_lambert" / "lambert.glsl", fake)
    # ... which would pay off if the student's copy were used, in either mode:
    for mode in ([], ["--seed", "5"]):
        cheat = subprocess.run(
            [str(VENV_BIN / "brdf-lab"), "grade", str(student / "exercises" / "01_lambert"), *mode],
            capture_output=True,
            text=True,
        )
        assert cheat.returncode == 0, cheat.stdout  # full marks with the unchanged stub
    assert scores(run_workflow(student, tmp_path, sdist)) == scores(honest)

"""The Gradescope package end to end: setup.sh and run_autograder in an /autograder-like
tree, the lean install (no Qt, no plotting), hidden mode seeded by the submission, and
the Dockerfile that runs the same setup.sh.
"""

from __future__ import annotations

import json
import math
import os
import re
import shutil
import subprocess
import sys
import time
import zipfile
from pathlib import Path

import pytest
from wheel_helpers import ROOT, build_wheel, wheelhouse

from lab.grading import seed as seeds
from lab.grading.exercise import load_exercise
from lab.grading.package import gradescope_zip, unpack

DESKTOP_MODULES = {"PyQt6", "pyqtgraph", "glfw", "matplotlib", "scipy"}
LEAN_LEFT_OUT = {"pyqt6", "pyqt6-qt6", "pyqtgraph", "glfw", "matplotlib", "scipy"}
EXERCISES = ["01_lambert", "02_phong"]


@pytest.fixture(scope="module")
def autograder(tmp_path_factory):
    """An /autograder tree after Gradescope's set-up: (root, environment, set-up seconds)."""
    base = tmp_path_factory.mktemp("gradescope")
    wheel = build_wheel(base / "dist")
    archive = gradescope_zip(
        [load_exercise(ROOT / "exercises" / n) for n in EXERCISES], base / "ag.zip", wheel=wheel
    )
    root = base / "autograder"
    unpack(archive, root / "source")
    house = base / "wheelhouse"
    wheelhouse(ROOT / "lab" / "requirements-core.txt", house)
    env = {
        **{k: v for k, v in os.environ.items() if k != "PYTHONPATH"},
        "AUTOGRADER_ROOT": str(root),
        "PIP_NO_INDEX": "1",  # offline: only the wheelhouse, which holds no Qt
        "PIP_FIND_LINKS": str(house),
        # the venv is made by the python3 on PATH: the one whose packages fill the wheelhouse
        "PATH": f"{Path(sys.base_prefix) / 'bin'}{os.pathsep}{os.environ['PATH']}",
    }
    start = time.monotonic()
    done = subprocess.run(
        ["bash", str(root / "source" / "setup.sh")], env=env, capture_output=True, text=True
    )
    assert done.returncode == 0, done.stdout[-2000:] + done.stderr[-2000:]
    return root, env, time.monotonic() - start


def submit(root: Path, env: dict, files: dict[str, Path], submission_id: int | None) -> dict:
    submission = root / "submission"
    shutil.rmtree(submission, ignore_errors=True)
    submission.mkdir()
    for name, source in files.items():
        shutil.copy(source, submission / name)
    metadata = root / "submission_metadata.json"
    metadata.unlink(missing_ok=True)
    if submission_id is not None:
        metadata.write_text(json.dumps({"id": submission_id, "created_at": "2026-11-29"}))
    done = subprocess.run(
        [str(root / "source" / "run_autograder")], env=env, capture_output=True, text=True
    )
    assert done.returncode == 0, done.stderr
    return json.loads((root / "results" / "results.json").read_text())


def installed_names(root: Path) -> set[str]:
    python = root / "venv" / "bin" / "python"
    listing = subprocess.run(
        [str(python), "-m", "pip", "list", "--format=json"], capture_output=True, text=True
    )
    return {p["name"].lower() for p in json.loads(listing.stdout)}


def test_setup_installs_the_wheel_with_the_lean_set_only(autograder):
    root, _, seconds = autograder
    names = installed_names(root)
    assert "brdf-lab" in names and {"moderngl", "numpy", "pillow", "flip-evaluator"} <= names
    assert not names & LEAN_LEFT_OUT
    site = next((root / "venv" / "lib").glob("python*/site-packages"))
    assert (site / "lab" / "_data" / "shaders" / "brdfs" / "phong.glsl").is_file()
    assert not (site / "lab" / "__editable__").exists() and not list(site.glob("__editable__*"))
    size = sum(p.stat().st_size for p in site.rglob("*") if p.is_file()) / 2**20
    print(f"\nlean install: {size:.0f} MiB in {seconds:.1f} s (offline wheelhouse)")


def test_a_solution_gets_full_marks_in_hidden_mode_seeded_by_the_submission(autograder):
    root, env, _ = autograder
    files = {
        "lambert.glsl": ROOT / "solutions" / "01_lambert" / "lambert.glsl",
        "phong.glsl": ROOT / "solutions" / "02_phong" / "phong.glsl",
    }
    results = submit(root, env, files, submission_id=123456789)
    assert results["score"] == sum(t["max_score"] for t in results["tests"]) > 0
    assert len({t["name"].split(":")[0].split()[0] for t in results["tests"]}) >= 1
    line = seeds.reproduce_line(123456789, EXERCISES)
    assert results["output"].startswith(line)
    assert "--seed 123456789" in line and "exercises/02_phong" in line


def test_the_stub_loses_points_and_the_seed_differs_per_submission(autograder):
    root, env, _ = autograder
    files = {"phong.glsl": ROOT / "exercises" / "02_phong" / "phong.glsl"}
    results = submit(root, env, files, submission_id=None)  # no metadata: a hash of the files
    assert results["score"] < sum(t["max_score"] for t in results["tests"])
    seed = seeds.from_files(root / "submission")
    assert f"seed {seed}." in results["output"]
    assert seed != seeds.from_gradescope(root / "nothing.json", ROOT / "exercises" / "01_lambert")


def test_grading_imports_no_desktop_packages(tmp_path):
    """In this (full) environment too: grading never imports Qt, glfw, matplotlib or scipy."""
    blocker = tmp_path / "blocker"
    blocker.mkdir()
    (blocker / "sitecustomize.py").write_text(
        "import sys\n"
        "class Block:\n"
        "    def find_spec(self, name, path=None, target=None):\n"
        f"        if name.split('.')[0] in {sorted(DESKTOP_MODULES)!r}:\n"
        "            raise ImportError('grading imported ' + name)\n"
        "sys.meta_path.insert(0, Block())\n"
    )
    env = {**os.environ, "PYTHONPATH": str(blocker)}
    control = subprocess.run(
        [sys.executable, "-c", "import matplotlib"], env=env, capture_output=True
    )
    assert b"grading imported matplotlib" in control.stderr  # the blocker works
    solution = ROOT / "solutions" / "02_phong" / "phong.glsl"
    out = tmp_path / "r.json"
    done = subprocess.run(
        [
            sys.executable,
            "-m",
            "lab.cli",
            "grade",
            str(ROOT / "exercises" / "02_phong"),
            "--submission",
            str(solution),
            "--seed",
            "5",
            "--json",
            str(out),
        ],
        env=env,
        capture_output=True,
        text=True,
    )
    results = json.loads(out.read_text())
    assert done.returncode == 0, done.stderr
    assert results["score"] == sum(t["max_score"] for t in results["tests"])


def test_dockerfile_runs_the_setup_script_and_nothing_else():
    """No Docker daemon here: the Dockerfile's steps must be setup.sh's, not a second copy."""
    text = (ROOT / "lab" / "grading" / "templates" / "Dockerfile").read_text()
    steps = [ln for ln in text.splitlines() if ln and not ln.startswith("#")]
    runs = [ln.split(None, 1)[1] for ln in steps if ln.startswith("RUN ")]
    assert runs[0] == "bash /autograder/source/setup.sh"
    assert all(not re.search(r"apt-get|pip|venv", r) for r in runs[1:])
    assert "COPY . /autograder/source" in steps  # the unpacked zip: everything setup.sh reads
    assert steps[0].startswith("FROM debian:") and "slim" in steps[0]
    assert steps[-2:] == ['ENTRYPOINT ["brdf-lab", "grade"]', 'CMD ["--help"]']
    setup = (ROOT / "lab" / "grading" / "templates" / "setup.sh").read_text()
    read = set(re.findall(r'\$SOURCE"?/([\w.*-]+)', setup))
    assert read == {"brdf_lab-*.whl", "requirements-core.txt", "constraints-core.txt"}


def test_the_zip_holds_wheel_scripts_dockerfile_and_definitions(autograder):
    root, _, _ = autograder
    source = root / "source"
    names = {p.relative_to(source).as_posix() for p in source.rglob("*") if p.is_file()}
    assert {"setup.sh", "run_autograder", "Dockerfile", "requirements-core.txt"} <= names
    assert any(re.fullmatch(r"brdf_lab-[\d.]+-py3-none-any\.whl", n) for n in names)
    assert "exercises/02_phong/exercise.toml" in names and "solutions/02_phong/phong.glsl" in names
    assert not any(n.startswith(("lab/", "shaders/")) for n in names)  # no source tree
    assert os.access(source / "run_autograder", os.X_OK) and os.access(source / "setup.sh", os.X_OK)
    assert (source / "requirements-core.txt").read_text() == (
        ROOT / "lab" / "requirements-core.txt"
    ).read_text()


def test_the_grading_venv_has_the_pinned_versions(autograder):
    """setup.sh installs with constraints-core.txt: each pinned package at its version."""
    from lab.grading.lock import pinned

    root, env, _ = autograder
    frozen = subprocess.run(
        [str(root / "venv" / "bin" / "python"), "-m", "pip", "freeze"],
        env=env, capture_output=True, text=True, check=True,
    ).stdout  # fmt: skip
    have = pinned(frozen)
    pins = pinned((root / "source" / "constraints-core.txt").read_text())
    assert pins and pins == {name: have[name] for name in pins}


def test_reference_mode_zip_leaves_the_solutions_out(tmp_path):
    wheel = build_wheel(tmp_path / "dist")
    out = gradescope_zip(
        [load_exercise(ROOT / "exercises" / "02_phong")],
        tmp_path / "a.zip",
        hidden=False,
        wheel=wheel,
    )
    with zipfile.ZipFile(out) as archive:
        names = archive.namelist()
        run = archive.read("run_autograder").decode()
    assert not any(n.startswith("solutions/") for n in names)
    assert "MODE=reference" in run


def test_commit_seeds_are_the_short_sha():
    assert seeds.from_commit("00000ff" + "0" * 33) == 255
    with pytest.raises(ValueError, match="not a commit SHA"):
        seeds.from_commit("main")


def test_gradescope_zip_command_builds_the_wheel_itself(tmp_path, capsys):
    from lab.cli import main

    out = tmp_path / "autograder.zip"
    assert main(["gradescope-zip", str(ROOT / "exercises" / "02_phong"), "-o", str(out)]) == 0
    with zipfile.ZipFile(out) as archive:
        names = archive.namelist()
        run = archive.read("run_autograder").decode()
    assert any(n.startswith("brdf_lab-") and n.endswith(".whl") for n in names)
    assert "MODE=hidden" in run and "solutions/02_phong/phong.glsl" in names
    assert main(["gradescope-zip", str(ROOT / "exercises" / "02_phong"), "-o", str(out),
                 "--wheel", str(tmp_path / "nothing.whl")]) == 2  # fmt: skip
    assert "not a brdf_lab-*.whl file" in capsys.readouterr().err


@pytest.mark.parametrize(
    "command",
    [["app"], ["watch", "exercises/02_phong/phong.glsl"], ["gallery", "g"]],
    ids=["app", "watch", "gallery"],
)
def test_the_lean_install_names_what_the_desktop_commands_need(autograder, command, tmp_path):
    root, env, _ = autograder
    shutil.copytree(ROOT / "exercises" / "02_phong", tmp_path / "exercises" / "02_phong")
    done = subprocess.run(
        [str(root / "venv" / "bin" / "brdf-lab"), *command],
        cwd=tmp_path,
        env={**env, "QT_QPA_PLATFORM": "offscreen"},
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert done.returncode == 2, done.stdout + done.stderr
    lines = done.stderr.splitlines()
    assert len(lines) == 1 and "leaves out: install the whole lab" in lines[0], done.stderr


def test_gradescope_and_classroom_install_the_same_system_packages():
    """The grader needs Mesa (EGL, llvmpipe) and glslang's preprocessor wherever it runs."""
    templates = ROOT / "lab" / "grading" / "templates"
    setup = re.search(r'^PACKAGES="([^"]+)"', (templates / "setup.sh").read_text(), re.M)
    workflow = re.search(r"apt-get install -y --no-install-recommends (.+)$",
                         (templates / "classroom.yml").read_text(), re.M)  # fmt: skip
    assert setup and workflow
    needed = {"libegl1", "libgl1-mesa-dri", "glslang-tools"}
    assert needed <= set(setup.group(1).split())
    assert set(workflow.group(1).split()) == needed


def _serve_exercise_list(brdf_lab: Path, env: dict, cwd: Path) -> None:
    """`serve` answers the practice mode's exercises.json with every shipped exercise."""
    import urllib.request

    server = subprocess.Popen(
        [str(brdf_lab), "serve", "--port", "0", "--no-browser"],
        cwd=cwd, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
    )  # fmt: skip
    try:
        first = server.stdout.readline()
        address = re.search(r"http://[\d.]+:\d+/", first).group(0)
        with urllib.request.urlopen(address + "exercises.json", timeout=60) as answer:
            listed = [e["name"] for e in json.loads(answer.read())["exercises"]]
    finally:
        server.terminate()
        server.communicate(timeout=30)
    assert listed == sorted(p.parent.name for p in (ROOT / "exercises").glob("*/exercise.toml"))


def test_the_readmes_lean_install_list_runs_in_the_lean_install(autograder, tmp_path):
    """Each command the README says works in a lean install runs there (this venv is
    Gradescope's: the wheel and requirements-core.txt only) and gives real output."""
    root, env, _ = autograder
    brdf_lab = root / "venv" / "bin" / "brdf-lab"
    readme = (ROOT / "README.md").read_text()
    sentence = re.search(r"In a lean install (.*?) work\b", readme, re.S).group(1)
    claimed = re.findall(r"`([\w-]+)`", sentence)
    (tmp_path / "pairs.csv").write_text("theta_i,phi_i,theta_o,phi_o\n30,0,30,180\n")

    def run(*args: str) -> subprocess.CompletedProcess:
        return subprocess.run(
            [str(brdf_lab), *args], cwd=tmp_path, env=env, capture_output=True, text=True,
            timeout=300,
        )  # fmt: skip

    def grade() -> None:
        done = run("grade", "02", "--submission", str(ROOT / "solutions/02_phong/phong.glsl"))
        assert done.returncode == 0 and done.stdout.splitlines()[-1] == "total 10/10"

    def render() -> None:
        assert run("render", "phong", "-o", "p.png").returncode == 0
        assert (tmp_path / "p.png").stat().st_size > 1000

    def evaluate() -> None:
        done = run("eval", "lambert", "--in", "pairs.csv", "--set", "albedo=0.5,0.5,0.5")
        values = [float(v) for v in done.stdout.splitlines()[1].split(",")]
        assert done.returncode == 0 and values == pytest.approx([0.5 / math.pi] * 3, rel=1e-4)

    def models() -> None:
        assert "cook_torrance" in run("models").stdout

    def web_export() -> None:
        assert run("web-export", "site").returncode == 0
        assert (tmp_path / "site" / "index.html").is_file()
        assert len(json.loads((tmp_path / "site" / "exercises.json").read_text())["exercises"]) > 0

    def exercises() -> None:
        listing = run("exercises", "list")
        assert listing.returncode == 0 and "02_phong" in listing.stdout

    checks = {
        "exercises": exercises,
        "grade": grade,
        "render": render,
        "eval": evaluate,
        "models": models,
        "serve": lambda: _serve_exercise_list(brdf_lab, env, tmp_path),
        "web-export": web_export,
    }
    assert claimed and set(claimed) <= set(checks), claimed  # the README claims no more
    for name in claimed:
        checks[name]()
    polar = run("render", "phong", "--view", "polar", "-o", "q.png")  # a plot: matplotlib
    assert polar.returncode == 2 and "needs matplotlib" in polar.stderr, polar.stderr

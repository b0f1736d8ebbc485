"""The built wheel works outside a clone: every command from a folder that is not one.

Each check compares with what this checkout computes (the same shaders, so the same
pixels and values) or with the numpy reference, never just that a command ran.
"""

from __future__ import annotations

import csv
import json
import os
import re
import shutil
import subprocess
import sys
import urllib.request
from pathlib import Path

import numpy as np
import pytest
from PIL import Image
from wheel_helpers import ROOT, build_wheel, install_wheel, wheel_names

from lab import __version__, reference
from lab.models import model_names


@pytest.fixture(scope="module")
def installed(tmp_path_factory):
    """(brdf-lab script of a venv holding the wheel, the wheel, an empty working folder)."""
    base = tmp_path_factory.mktemp("wheel")
    wheel = build_wheel(base / "dist")
    script = install_wheel(wheel, base / "venv")
    work = base / "elsewhere"
    work.mkdir()
    return script, wheel, work


def run(script: Path, *args: str, cwd: Path, timeout: float = 120, **kw):
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    return subprocess.run(
        [str(script), *args],
        cwd=cwd,
        capture_output=True,
        text=True,
        timeout=timeout,
        env=env,
        **kw,
    )


def ok(result) -> str:
    assert result.returncode == 0, result.stderr
    return result.stdout


def test_wheel_carries_the_data_the_lab_reads(installed):
    _, wheel, _ = installed
    names = wheel_names(wheel)
    tracked = subprocess.run(
        ["git", "ls-files", "shaders", "slides", "exercises", "lab/web/static", "lab/app/presets"],
        cwd=ROOT,
        capture_output=True,
        text=True,
        check=True,
    ).stdout.split()
    for path in tracked:
        inside = path if path.startswith("lab/") else f"lab/_data/{path}"
        assert inside in names, f"{path} is not in the wheel"
    assert not any("solutions" in n or "node_modules" in n for n in names)
    assert f"brdf_lab-{__version__}.dist-info/licenses/LICENSE" in names
    assert "lab/grading/templates/setup.sh" in names and "lab/measured/measured.glsl" in names


def test_metadata_names_version_urls_classifiers_and_license(installed):
    script, _, work = installed
    assert ok(run(script, "--version", cwd=work)).strip() == f"brdf-lab {__version__}"
    python = script.parent / "python"
    meta = ok(
        subprocess.run(
            [str(python), "-c", "import importlib.metadata as m; print(m.metadata('brdf-lab'))"],
            capture_output=True,
            text=True,
        )
    )
    assert "Project-URL: Source," in meta and "Classifier: Topic :: Education" in meta
    assert "License-Expression: MIT" in meta and "License-File: LICENSE" in meta
    assert "Requires-Dist: PyQt6" in meta  # `pip install brdf-lab` is the whole lab


def test_models_lists_the_library_from_the_installed_package(installed):
    script, _, work = installed
    out = ok(run(script, "models", cwd=work))
    listed = [line.split()[0] for line in out.splitlines() if line and not line[0].isspace()]
    assert [n for n in listed if n != "measured"] == model_names()
    lib = script.parent.parent / "lib"
    assert "_data/shaders" not in out or str(lib) in out  # files named from the install


def test_render_gives_the_same_pixels_as_the_clone(installed, tmp_path):
    script, _, work = installed
    args = ["render", "phong", "--set", "ke=40", "--light", "30,0", "--size", "128"]
    ok(run(script, *args, "-o", "p.png", cwd=work))
    ok(
        run(
            Path(sys.executable).parent / "brdf-lab", *args, "-o", str(tmp_path / "c.png"), cwd=ROOT
        )
    )
    mine, clone = np.asarray(Image.open(work / "p.png")), np.asarray(Image.open(tmp_path / "c.png"))
    assert mine.shape[:2] == (128, 128) and mine.max() > 200 and mine[0, 0, :3].max() < 10
    np.testing.assert_array_equal(mine, clone)


def test_eval_matches_the_numpy_reference(installed):
    script, _, work = installed
    rng = np.random.default_rng(7)
    rows = np.column_stack(
        [
            rng.uniform(0, 80, 20),
            rng.uniform(0, 360, 20),
            rng.uniform(0, 80, 20),
            rng.uniform(0, 360, 20),
        ]
    ).round(3)
    with open(work / "pairs.csv", "w", newline="") as f:
        csv.writer(f).writerows([["theta_i", "phi_i", "theta_o", "phi_o"], *rows.tolist()])
    ok(
        run(
            script,
            "eval",
            "ggx",
            "--set",
            "alpha=0.3",
            "--in",
            "pairs.csv",
            "--out",
            "v.csv",
            cwd=work,
        )
    )
    with open(work / "v.csv") as f:
        values = np.array([[float(x) for x in r] for r in list(csv.reader(f))[1:]])
    expected = reference.brdf_angles("ggx", {"alpha": 0.3}, rows)
    np.testing.assert_allclose(values, expected, rtol=1e-3, atol=1e-6)


def test_app_starts_under_xvfb_with_the_shipped_presets(installed):
    script, _, work = installed
    assert os.environ.get("DISPLAY"), "run the suite under xvfb-run"
    out = ok(run(script, "app", "--preset", "06_ward_anisotropy", "--bench", cwd=work, timeout=240))
    assert "ms" in out


def test_serve_answers_with_the_page_and_the_installed_shaders(installed):
    script, _, work = installed
    env = {k: v for k, v in os.environ.items() if k not in ("DISPLAY", "WAYLAND_DISPLAY")}
    server = subprocess.Popen(
        [str(script), "serve", "--port", "0", "--no-browser"],
        cwd=work,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        env=env,
    )
    try:
        line = server.stdout.readline()
        url = line.split(" at ")[1].split()[0]
        page = urllib.request.urlopen(url, timeout=30).read().decode()
        shader = urllib.request.urlopen(url + "shaders/brdfs/phong.glsl", timeout=30).read()
    finally:
        server.terminate()
        server.communicate(timeout=30)  # also closes the pipes
    assert "<html" in page.lower()
    assert shader == (ROOT / "shaders" / "brdfs" / "phong.glsl").read_bytes()


def test_web_export_writes_a_complete_site(installed):
    script, _, work = installed
    ok(run(script, "web-export", "site", cwd=work))
    manifest = json.loads((work / "site" / "manifest.json").read_text())
    assert manifest["models"] == model_names()
    assert manifest["files"] == sorted(
        p.relative_to(ROOT / "shaders").as_posix() for p in (ROOT / "shaders").rglob("*.glsl")
    )
    for name in model_names():
        assert (work / "site" / "shaders" / "brdfs" / f"{name}.glsl").is_file()
    assert (work / "site" / "index.html").is_file()


def test_grade_an_exercise_folder_given_by_path(installed, tmp_path):
    script, _, work = installed
    folder = tmp_path / "my course" / "02_phong"
    shutil.copytree(ROOT / "exercises" / "02_phong", folder)
    solution = ROOT / "solutions" / "02_phong" / "phong.glsl"
    ok(
        run(
            script,
            "grade",
            str(folder),
            "--submission",
            str(solution),
            "--json",
            "r.json",
            cwd=work,
        )
    )
    results = json.loads((work / "r.json").read_text())
    assert results["score"] == sum(t["max_score"] for t in results["tests"]) > 0
    stub = run(script, "grade", str(folder), "--json", "s.json", cwd=work)
    assert stub.returncode != 0
    assert json.loads((work / "s.json").read_text())["score"] < results["score"]


def test_gallery_renders_every_model(installed):
    script, _, work = installed
    ok(run(script, "gallery", "g", cwd=work, timeout=300))
    for name in model_names():
        image = np.asarray(Image.open(work / "g" / f"{name}_sphere.png"))
        assert image.max() > 0, name
        assert (work / "g" / f"{name}_polar.png").is_file()


def test_a_missing_resource_is_one_line_naming_the_repair(installed, tmp_path):
    script, _, _ = installed
    lib = next(script.parent.parent.glob("lib/python*/site-packages/lab/_data"))
    moved = tmp_path / "moved"
    shutil.move(lib / "shaders", moved)
    try:
        result = run(script, "render", "phong", "-o", "p.png", cwd=tmp_path)
    finally:
        shutil.move(moved, lib / "shaders")
    assert result.returncode == 2
    lines = result.stderr.splitlines()
    assert len(lines) == 1 and result.stderr.endswith("\n"), result.stderr
    assert str(lib / "shaders") in lines[0] and "reinstall" in lines[0]


def test_slides_build_from_a_writable_copy_of_the_installed_sources(installed, tmp_path):
    """site-packages may be read-only: npm and build.mjs run in a copy in the user's cache."""
    script, _, work = installed
    code = "from lab.web import slides; print(slides.SLIDES_DIR); print(slides.workdir())"
    env = {**os.environ, "XDG_CACHE_HOME": str(tmp_path)}
    env.pop("PYTHONPATH", None)
    python = script.parent / "python"
    shipped, workdir = ok(
        subprocess.run([str(python), "-c", code], cwd=work, capture_output=True, text=True, env=env)
    ).split()
    assert Path(shipped).parts[-2:] == ("_data", "slides")
    assert Path(workdir).is_relative_to(tmp_path)
    for name in ("lecture.md", "build.mjs", "package-lock.json"):
        assert (Path(workdir) / name).read_bytes() == (ROOT / "slides" / name).read_bytes()


def test_exercises_from_the_install_by_number_and_name(installed, tmp_path):
    """An install has no exercises/ folder: `exercises list` shows what it carries,
    `exercises copy` makes a working folder, `grade` finds an exercise by its number, its
    topic or the README's `exercises/NN_topic`, and grades the same as from a path."""
    script, _, work = installed
    listing = ok(run(script, "exercises", "list", cwd=work))
    shipped = sorted(p.parent.name for p in (ROOT / "exercises").glob("*/exercise.toml"))
    assert [ln.split()[0] for ln in listing.splitlines()[1:-1]] == shipped
    mine = tmp_path / "my work"
    ok(run(script, "exercises", "copy", "02", "blinn_phong", str(mine), cwd=work))
    assert (mine / "02_phong" / "phong.glsl").read_bytes() == (
        ROOT / "exercises" / "02_phong" / "phong.glsl"
    ).read_bytes()
    assert (mine / "03_blinn_phong" / "references" / "values.npz").is_file()
    again = run(script, "exercises", "copy", "02", str(mine), cwd=work)
    assert again.returncode == 2 and "exists already" in again.stderr
    solution = ROOT / "solutions" / "02_phong" / "phong.glsl"
    shutil.copy(solution, mine / "02_phong" / "phong.glsl")
    for name in ("02", "phong", "exercises/02_phong"):
        graded = run(script, "grade", name, "--submission", str(solution), cwd=work)
        assert ok(graded).splitlines()[-1] == "total 10/10", name
    assert ok(run(script, "grade", str(mine / "02_phong"), cwd=work)).endswith("total 10/10\n")
    # in the working folder, `grade 02` grades the student's copy, not the install's stub
    assert ok(run(script, "grade", "02", cwd=mine)).endswith("total 10/10\n")
    assert run(script, "grade", "03", cwd=mine).stdout.endswith("total 0/10\n")
    stub = run(script, "grade", "phong", cwd=work)
    assert stub.returncode == 1 and stub.stdout.splitlines()[-1] == "total 0/10"
    unknown = run(script, "grade", "phongg", cwd=work)
    assert unknown.returncode == 2 and "exercises list" in unknown.stderr


def test_commands_that_need_the_solutions_say_so_in_an_install(installed):
    script, _, work = installed
    for args in (["grade", "02", "--seed", "3"], ["grade-bench"], ["exercise", "check", "02"]):
        result = run(script, *args, cwd=work)
        assert result.returncode == 2, (args, result.stderr)
        assert "internal error" not in result.stderr and "solution" in result.stderr, args


def test_every_command_the_readme_names_exists_in_the_install(installed):
    """Each `brdf-lab COMMAND [ACTION]` of the README is a command of the installed lab
    (its --help answers), so the README cannot name a command the install lacks."""
    script, _, work = installed
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    found = set(
        re.findall(r"brdf-lab ([a-z][a-z-]+)(?: (pack|init|check|list|copy|pdf|build))?", readme)
    )
    found = {tuple(w for w in pair if w) for pair in found if pair[0] != "is"}
    assert {("grade",), ("exercises", "copy"), ("course", "pack"), ("exercise", "check")} <= found
    for words in sorted(found):
        done = run(script, *words, "--help", cwd=work)
        assert done.returncode == 0 and "usage: brdf-lab" in done.stdout, (words, done.stderr)

"""The release workflow (.github/workflows/release.yml): builds and checks the sdist and
wheel, runs the install tests against the built wheel in a clean venv, and publishes by
trusted publishing on a version tag only."""

from __future__ import annotations

import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
RELEASE = ROOT / ".github" / "workflows" / "release.yml"


def test_the_release_workflow_passes_actionlint():
    tool = shutil.which("actionlint") or shutil.which(
        "actionlint", path=str(Path(sys.executable).parent)
    )
    if tool is None:
        pytest.skip("actionlint is not installed (python3 -m lab test installs it with Go)")
    done = subprocess.run([tool, str(RELEASE)], capture_output=True, text=True)
    assert done.returncode == 0, done.stdout + done.stderr


def test_release_builds_checks_tests_then_publishes_on_tags_only():
    text = RELEASE.read_text()
    jobs = text.split("\njobs:\n", 1)[1]
    job = {}
    for block in jobs.split("\n\n"):
        name = block.strip().split(":", 1)[0]
        job[name] = block
    assert list(job) == ["build", "install-tests", "publish-pypi", "github-release"]
    assert "python -m build" in job["build"] and "twine check --strict dist/*" in job["build"]
    assert 'BRDF_LAB_WHEEL="$PWD/$wheel"' in job["install-tests"]
    assert "tests/test_install.py" in job["install-tests"]
    assert "python -m venv" in job["install-tests"]  # a clean venv, not the build's
    assert "b.RUN_PACKAGES" in job["install-tests"]  # bootstrap's system packages, not a copy
    for name in ("publish-pypi", "github-release"):
        assert "needs: [build, install-tests]" in job[name]
        assert "if: startsWith(github.ref, 'refs/tags/v')" in job[name]
    publish = job["publish-pypi"]
    assert "id-token: write" in publish and "pypa/gh-action-pypi-publish@release/v1" in publish
    assert "password" not in publish and "secrets." not in publish  # trusted publishing
    assert (
        "gh release upload" in job["github-release"] and "contents: write" in job["github-release"]
    )
    assert "permissions:\n  contents: read" in text  # the default for every other job


def test_the_install_tests_can_take_the_released_wheel(tmp_path, monkeypatch):
    from wheel_helpers import build_wheel

    given = tmp_path / "brdf_lab-0.1.0-py3-none-any.whl"
    given.write_bytes(b"the file released")
    monkeypatch.setenv("BRDF_LAB_WHEEL", str(given))
    got = build_wheel(tmp_path / "dist")
    assert got.parent == tmp_path / "dist" and got.read_bytes() == b"the file released"

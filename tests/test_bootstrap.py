"""The set-up step behind the README's two commands."""

from __future__ import annotations

import shutil

import pytest

from lab import bootstrap


@pytest.mark.skipif(not shutil.which("dpkg-query"), reason="Debian/Ubuntu only")
def test_without_root_prints_the_exact_apt_line(monkeypatch, capsys):
    monkeypatch.setattr(bootstrap.os, "geteuid", lambda: 1000)
    missing = "brdf-lab-no-such-package"
    bootstrap.ensure_system_packages({missing: None, "coreutils": None, "python3-x": "sh"})
    out = capsys.readouterr().out
    line = next(text for text in out.splitlines() if "apt-get install" in text)
    assert line.strip() == (
        f"sudo apt-get update && sudo apt-get install -y --no-install-recommends {missing}"
    )


@pytest.mark.skipif(not shutil.which("dpkg-query"), reason="Debian/Ubuntu only")
def test_installed_packages_and_present_commands_are_not_asked_for():
    # coreutils is always installed; "sh" on PATH stands in for a package's command.
    assert bootstrap.missing_debian_packages({"coreutils": None, "no-such-pkg-x": "sh"}) == []


def test_the_test_command_runs_pytest_under_xvfb_without_a_display(monkeypatch, tmp_path):
    calls = []
    monkeypatch.setattr(
        bootstrap, "ensure_system_packages", lambda packages: calls.append(packages)
    )
    monkeypatch.setattr(bootstrap, "ensure_venv", lambda with_tests: calls.append(with_tests))
    monkeypatch.delenv("DISPLAY", raising=False)
    monkeypatch.setattr(bootstrap.shutil, "which", lambda name: f"/usr/bin/{name}")

    class Done:
        returncode = 0

    seen = {}

    def run(cmd, **options):
        seen.update(cmd=cmd, **options)
        return Done()

    monkeypatch.setattr(bootstrap.subprocess, "run", run)
    assert bootstrap.main(["test", "-q"]) == 0
    assert "xvfb" in calls[0] and calls[1] is True
    assert seen["cmd"][:2] == ["xvfb-run", "-a"]
    assert seen["cmd"][-4:] == [str(bootstrap.venv_python()), "-m", "pytest", "-q"]
    assert seen["env"]["BRDF_LAB_STRICT"] == "1"

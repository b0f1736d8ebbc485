"""The pinned grading environment: lab/constraints-core.txt, refreshed by one command.

    python -m lab.grading.lock          (needs the package index; about a minute)

resolves lab/requirements-core.txt (the lean grading install) in a fresh virtual
environment and writes every package it installed, at its exact version, as pip
constraints. The Gradescope set-up (setup.sh) and the Classroom workflow install with
`-c constraints-core.txt`, so a grade does not change because a dependency released.
"""

from __future__ import annotations

import os
import subprocess
import sys
import tempfile
import venv
from pathlib import Path

from lab.resources import package_dir

SKIP = ("setuptools", "wheel", "brdf-lab", "brdf_lab")  # tools of the venv, the lab itself
REQUIREMENTS = "requirements-core.txt"
CONSTRAINTS = "constraints-core.txt"
HEADER = """\
# The grading environment, pinned: every package the lean install (requirements-core.txt)
# pulls in, at the version graders use. Written by 'python -m lab.grading.lock' with
# Python {python} (tomli, needed before 3.11 only, is left free); refresh it with that
# command and commit it once the tests pass with it.
"""


def constraints_path() -> Path:
    return package_dir() / CONSTRAINTS


def pinned(text: str) -> dict[str, str]:
    """name -> version of the `name==version` lines of a constraints file."""
    out = {}
    for line in text.splitlines():
        line = line.split("#")[0].strip()
        if "==" in line:
            name, version = line.split("==", 1)
            out[name.strip().lower()] = version.split(";")[0].strip()
    return out


def refresh(out: Path | None = None) -> Path:
    """Resolve the core requirements in a fresh venv and write the constraints file."""
    out = out or constraints_path()
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}  # nothing of this lab
    with tempfile.TemporaryDirectory() as tmp:
        venv.create(tmp, with_pip=True)
        python = Path(tmp) / ("Scripts" if sys.platform == "win32" else "bin") / "python"
        requirements = package_dir() / REQUIREMENTS
        subprocess.run(
            [str(python), "-m", "pip", "install", "-q", "-r", str(requirements)],
            check=True,
            env=env,
        )
        frozen = subprocess.run(
            [str(python), "-m", "pip", "freeze", "--all", "--exclude", "pip"],
            check=True,
            env=env,
            capture_output=True,
            text=True,
        ).stdout
    lines = sorted(
        (ln for ln in frozen.splitlines() if "==" in ln and not ln.startswith(SKIP)),
        key=str.lower,
    )
    version = ".".join(map(str, sys.version_info[:2]))
    out.write_text(HEADER.format(python=version) + "\n".join(lines) + "\n", encoding="utf-8")
    return out


def main() -> int:
    path = refresh()
    print(f"wrote {path} ({len(pinned(path.read_text()))} packages pinned)")
    return 0


if __name__ == "__main__":
    sys.exit(main())

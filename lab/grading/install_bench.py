"""Installed size and time: the lean grading install against the whole lab.

    python -m lab.grading.install_bench [--keep DIR]

Builds the wheel from this clone, then times three installs into fresh venvs with pip
(from the package index, no cache): the lean set (requirements-core.txt at the pinned
versions of constraints-core.txt, then the wheel with --no-deps, as Gradescope's setup.sh
does), the whole lab from the wheel, and
the editable install of the source tree that the Gradescope set-up used before.
Prints seconds and MiB for each. Needs the network.
"""

from __future__ import annotations

import argparse
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from lab.grading.package import _clone_root, build_wheel
from lab.resources import package_dir


def _size_mib(folder: Path) -> float:
    return sum(p.stat().st_size for p in folder.rglob("*") if p.is_file()) / 2**20


def _install(venv: Path, *steps: list[str]) -> tuple[float, float]:
    """(seconds, MiB) of a fresh venv plus the pip installs in `steps`."""
    start = time.monotonic()
    subprocess.run([sys.executable, "-m", "venv", str(venv)], check=True)
    pip = [str(venv / "bin" / "python"), "-m", "pip", "install", "-q", "--no-cache-dir"]
    for step in steps:
        subprocess.run([*pip, *step], check=True)
    return time.monotonic() - start, _size_mib(venv)


def run(keep: Path | None = None) -> None:
    root = _clone_root()
    if root is None:
        raise SystemExit("install_bench builds the wheel: run it from a clone")
    with tempfile.TemporaryDirectory() as tmp:
        base = keep or Path(tmp)
        wheel = build_wheel(base / "dist")
        core = package_dir() / "requirements-core.txt"
        cases = {
            "lean (requirements-core.txt pinned + wheel --no-deps)": [
                ["-r", str(core), "-c", str(package_dir() / "constraints-core.txt")],
                ["--no-deps", str(wheel)],
            ],
            "whole lab (pip install of the wheel)": [[str(wheel)]],
            "editable source tree (the old Gradescope set-up)": [["-e", str(root)]],
        }
        print(f"{'install':52} {'seconds':>8} {'MiB':>7}")
        for i, (name, steps) in enumerate(cases.items()):
            seconds, size = _install(base / f"venv{i}", *steps)
            print(f"{name:52} {seconds:8.1f} {size:7.0f}", flush=True)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--keep", type=Path, help="build the venvs here and keep them")
    run(parser.parse_args(argv).keep)
    return 0


if __name__ == "__main__":
    sys.exit(main())

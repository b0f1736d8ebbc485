"""Helpers for the tests of the built wheel: build it once, install it into throw-away venvs.

Offline and fast: the wheel is built without build isolation, installed with --no-deps
--no-index, and the venv sees this environment's third-party packages through a .pth
file added after the install (so pip never sees, let alone touches, the editable lab).
"""

from __future__ import annotations

import importlib.metadata
import os
import shutil
import subprocess
import sys
import sysconfig
import zipfile
from pathlib import Path

from packaging.requirements import Requirement
from packaging.utils import canonicalize_name

ROOT = Path(__file__).resolve().parents[1]
SITE_PACKAGES = Path(sysconfig.get_paths()["purelib"])


def build_wheel(dest: Path) -> Path:
    """`pip wheel` of this checkout into `dest`; returns the .whl. With BRDF_LAB_WHEEL set
    (the release workflow), that built wheel instead: the tests check the file released."""
    dest.mkdir(parents=True, exist_ok=True)
    given = os.environ.get("BRDF_LAB_WHEEL")
    if given:
        return Path(shutil.copy(given, dest))
    command = [sys.executable, "-m", "pip", "wheel", "--no-deps", "--no-build-isolation"]
    subprocess.run(
        [*command, "-q", "--no-index", str(ROOT), "-w", str(dest)],
        check=True,
        capture_output=True,
        timeout=300,
    )
    (wheel,) = dest.glob("brdf_lab-*.whl")
    return wheel


def venv_bin(venv: Path) -> Path:
    return venv / ("Scripts" if sys.platform == "win32" else "bin")


def install_wheel(wheel: Path, venv: Path, borrow_packages: bool = True) -> Path:
    """A fresh venv with the wheel installed; returns its brdf-lab script.

    `borrow_packages`: afterwards let the venv import this environment's numpy, moderngl,
    Qt, ... (the lab itself still comes from the wheel: the venv's own site-packages is
    first on sys.path, and the editable install's hook is a .pth that is not processed).
    """
    subprocess.run([sys.executable, "-m", "venv", str(venv)], check=True, timeout=120)
    python = venv_bin(venv) / "python"
    subprocess.run(
        [str(python), "-m", "pip", "install", "-q", "--no-deps", "--no-index", str(wheel)],
        check=True,
        capture_output=True,
        timeout=300,
    )
    if borrow_packages:
        site = subprocess.run(
            [str(python), "-c", "import sysconfig; print(sysconfig.get_paths()['purelib'])"],
            check=True,
            capture_output=True,
            text=True,
        ).stdout.strip()
        (Path(site) / "zz_borrowed_packages.pth").write_text(f"{SITE_PACKAGES}\n")
    return venv_bin(venv) / "brdf-lab"


def wheel_names(wheel: Path) -> set[str]:
    with zipfile.ZipFile(wheel) as archive:
        return set(archive.namelist())


def _closure(requirements: list[str]) -> dict[str, importlib.metadata.Distribution]:
    """The installed distributions that `requirements` pull in, transitively."""
    found: dict[str, importlib.metadata.Distribution] = {}
    todo = [Requirement(r) for r in requirements]
    while todo:
        req = todo.pop()
        if req.marker and not req.marker.evaluate({"extra": ""}):
            continue
        key = canonicalize_name(req.name)
        if key in found:
            continue
        found[key] = dist = importlib.metadata.distribution(req.name)
        todo += [Requirement(r) for r in dist.requires or []]
    return found


def wheelhouse(requirements_file: Path, dest: Path) -> list[str]:
    """Wheels re-packed from this environment's installed copies of a requirements file's
    packages and their dependencies, so pip can install them with --no-index (offline).

    Returns the distribution names. Anything outside the closure (PyQt6, say) is absent,
    so an install from here fails if the set is not as lean as it claims.
    """
    dest.mkdir(parents=True, exist_ok=True)
    lines = [ln.split("#")[0].strip() for ln in requirements_file.read_text().splitlines()]
    dists = _closure([ln for ln in lines if ln])
    for dist in dists.values():
        info = Path(str(dist._path))  # the .dist-info folder
        tag = next(
            ln.split(":", 1)[1].strip()
            for ln in (info / "WHEEL").read_text().splitlines()
            if ln.startswith("Tag:")
        )
        name = f"{canonicalize_name(dist.metadata['Name']).replace('-', '_')}-{dist.version}"
        with zipfile.ZipFile(dest / f"{name}-{tag}.whl", "w", zipfile.ZIP_STORED) as whl:
            for file in dist.files or []:
                path = Path(file.locate())
                if file.parts[0] == ".." or "__pycache__" in file.parts or not path.is_file():
                    continue
                whl.write(path, file.as_posix())
    return sorted(dists)

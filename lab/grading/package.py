"""The Gradescope autograder zip: the built wheel, the lean requirements and their pinned
versions (constraints-core.txt), the exercises.

Unpacked by Gradescope into /autograder/source. setup.sh installs the wheel with the lean
dependency set (no Qt, no matplotlib) into /autograder/venv; the Dockerfile builds the
same image by running that same setup.sh. run_autograder grades in hidden mode by
default, seeded by the submission.
"""

from __future__ import annotations

import importlib.metadata
import subprocess
import sys
import tempfile
import zipfile
from pathlib import Path

from lab.errors import UsageError
from lab.grading.exercise import Exercise
from lab.resources import install_line, package_dir

TEMPLATES = Path(__file__).resolve().parent / "templates"
REQUIREMENTS = package_dir() / "requirements-core.txt"
CONSTRAINTS = package_dir() / "constraints-core.txt"  # lab.grading.lock writes it
SCRIPTS = ("setup.sh", "run_autograder")  # executable, as Gradescope requires


def _clone_root() -> Path | None:
    """The source tree this lab runs from, when it runs from one (not from a wheel)."""
    root = package_dir().parent
    return root if (root / "pyproject.toml").is_file() and (root / "setup.py").is_file() else None


def build_wheel(outdir: Path) -> Path:
    """Build the lab's wheel from the clone it runs from (offline when setuptools is new)."""
    root = _clone_root()
    if root is None:
        raise UsageError(
            "this brdf-lab is an installed wheel, not a clone: pass the wheel with "
            f'--wheel FILE.whl (the release\'s wheel, or: pip wheel --no-deps "{install_line()}")'
        )
    command = [sys.executable, "-m", "pip", "wheel", "--no-deps", "-q", "-w", str(outdir)]
    try:
        if int(importlib.metadata.version("setuptools").split(".")[0]) >= 77:
            command.append("--no-build-isolation")  # no download of the build back-end
    except importlib.metadata.PackageNotFoundError:
        pass
    result = subprocess.run([*command, str(root)], capture_output=True, text=True)
    wheels = sorted(outdir.glob("brdf_lab-*.whl"))
    if result.returncode != 0 or not wheels:
        lines = [ln for ln in (result.stderr or result.stdout).splitlines() if ln.strip()]
        raise UsageError(f"building the wheel failed: {lines[-1] if lines else 'no wheel'}")
    return wheels[-1]


def _add_tree(archive: zipfile.ZipFile, folder: Path, prefix: str) -> None:
    for path in sorted(folder.rglob("*")):
        if path.is_file() and "__pycache__" not in path.parts:
            archive.write(path, f"{prefix}/{path.relative_to(folder).as_posix()}")


def run_script(exercises: list[Exercise], hidden: bool, seed: int | None) -> str:
    names = " ".join(f"exercises/{e.name}" for e in exercises)
    text = (TEMPLATES / "run_autograder").read_text(encoding="utf-8")
    mode = "hidden" if hidden else "reference"
    return (
        text.replace("__EXERCISES__", names)
        .replace("__MODE__", mode)
        .replace("__SEED__", str(seed) if seed is not None else "")
    )


def gradescope_zip(
    exercises: list[Exercise],
    out: Path,
    seed: int | None = None,
    hidden: bool = True,
    wheel: Path | None = None,
) -> Path:
    """Zip with Gradescope's two scripts, the Dockerfile, the wheel and the exercises.

    `hidden` (the default): random parameters and lights, seeded per submission (or all
    with `seed`); the solutions travel along, since hidden mode renders them live.
    """
    if hidden:
        missing = [e.name for e in exercises if not e.solution.is_file()]
        if missing:
            raise UsageError(
                f"hidden mode renders the solutions live, and solutions/ lacks {', '.join(missing)}"
                ": run from a clone with solutions/ beside exercises/, or use --reference-mode"
            )
    with tempfile.TemporaryDirectory() as tmp:
        if wheel is None:
            wheel = build_wheel(Path(tmp))
        elif not (
            wheel.is_file() and wheel.name.startswith("brdf_lab-") and wheel.suffix == ".whl"
        ):
            raise UsageError(f"--wheel {wheel}: not a brdf_lab-*.whl file")
        with zipfile.ZipFile(out, "w", zipfile.ZIP_DEFLATED) as archive:
            texts = {
                "setup.sh": (TEMPLATES / "setup.sh").read_text(encoding="utf-8"),
                "run_autograder": run_script(exercises, hidden, seed),
                "Dockerfile": (TEMPLATES / "Dockerfile").read_text(encoding="utf-8"),
                "requirements-core.txt": REQUIREMENTS.read_text(encoding="utf-8"),
                "constraints-core.txt": CONSTRAINTS.read_text(encoding="utf-8"),
            }
            for name, text in texts.items():
                info = zipfile.ZipInfo(name)
                info.external_attr = (0o755 if name in SCRIPTS else 0o644) << 16
                archive.writestr(info, text)
            archive.write(wheel, wheel.name)
            for exercise in exercises:
                _add_tree(archive, exercise.folder, f"exercises/{exercise.name}")
                if hidden:
                    _add_tree(archive, exercise.solution.parent, f"solutions/{exercise.name}")
    return out


def unpack(archive: Path, source: Path) -> None:
    """Unpack as Gradescope does, keeping the scripts executable (for tests and Docker)."""
    with zipfile.ZipFile(archive) as z:
        z.extractall(source)
        for info in z.infolist():
            mode = info.external_attr >> 16
            if mode:
                (source / info.filename).chmod(mode)

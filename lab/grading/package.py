"""The Gradescope autograder zip: setup.sh, run_autograder and the lab's source."""

from __future__ import annotations

import zipfile
from pathlib import Path

from lab.grading.exercise import Exercise

ROOT = Path(__file__).resolve().parents[2]
TEMPLATES = Path(__file__).resolve().parent / "templates"


def _add_tree(archive: zipfile.ZipFile, folder: Path, prefix: str) -> None:
    for path in sorted(folder.rglob("*")):
        if path.is_file() and "__pycache__" not in path.parts:
            archive.write(path, f"{prefix}/{path.relative_to(folder).as_posix()}")


def gradescope_zip(exercises: list[Exercise], out: Path, seed: int | None = None) -> Path:
    """Zip with the two scripts Gradescope runs at the top and the lab under source/.

    Gradescope unpacks the zip into /autograder/source. Solutions travel along only
    for hidden mode (`seed`), which renders them live.
    """
    names = " ".join(f"exercises/{e.name}" for e in exercises)
    run = (TEMPLATES / "run_autograder").read_text(encoding="utf-8")
    run = run.replace("__EXERCISES__", names).replace("__SEED__", f"--seed {seed}" if seed else "")
    with zipfile.ZipFile(out, "w", zipfile.ZIP_DEFLATED) as archive:
        for name, text in (
            ("setup.sh", (TEMPLATES / "setup.sh").read_text(encoding="utf-8")),
            ("run_autograder", run),
        ):
            info = zipfile.ZipInfo(name)
            info.external_attr = 0o755 << 16  # executable, as Gradescope requires
            archive.writestr(info, text)
        for name in ("pyproject.toml", "README.md"):
            archive.write(ROOT / name, name)
        _add_tree(archive, ROOT / "lab", "lab")
        _add_tree(archive, ROOT / "shaders", "shaders")
        for exercise in exercises:
            _add_tree(archive, exercise.folder, f"exercises/{exercise.name}")
            if seed is not None:
                _add_tree(archive, exercise.solution.parent, f"solutions/{exercise.name}")
    return out

"""Where the lab's data lives, in a clone and in an installed wheel: one lookup for both.

The repository keeps `shaders/`, `slides/` and `exercises/` at its top level. A built
wheel carries copies of them inside the package as `lab/_data/<name>` (setup.py puts them
there), so an installed lab never needs its source tree. `importlib.resources` finds the
package; files inside the package (web page, presets, templates) sit next to the code.
"""

from __future__ import annotations

from importlib.resources import files
from pathlib import Path

# Top-level folders of the repository that the wheel carries as lab/_data/<name>.
DATA_FOLDERS = ("shaders", "slides", "exercises")
REPOSITORY = "https://github.com/brdf-lab/brdf-lab"


def install_line(extra: str = "") -> str:
    """The pip requirement that installs this release today (no PyPI release yet): the
    repository at its version tag. README, error hints and course init use this line."""
    from lab import __version__

    return f"brdf-lab{extra} @ git+{REPOSITORY}@v{__version__}"


class ResourceError(RuntimeError):
    """A data folder of the lab is missing from this install."""


def package_dir() -> Path:
    """The `lab` package's folder (a plain folder: the lab is never run from a zip)."""
    return Path(str(files("lab")))


def data_dir(name: str) -> Path:
    """`shaders`, `slides` or `exercises`: inside the installed package, else the clone's."""
    if name not in DATA_FOLDERS:
        raise ValueError(f"unknown data folder {name!r}: one of {', '.join(DATA_FOLDERS)}")
    installed = package_dir() / "_data"
    if installed.is_dir():  # a wheel's install: its data, even if a folder went missing
        return installed / name
    return package_dir().parent / name  # a clone (or an editable install of one)


def require_dir(path: Path, what: str) -> Path:
    """`path` if it is a folder, else a one-line error saying how to repair the install."""
    if not path.is_dir():
        raise ResourceError(
            f"{what} ({path}) is missing from this install of brdf-lab: reinstall it "
            f"(pip install --force-reinstall \"{install_line()}\", or 'pip install -e .' in a "
            "clone)"
        )
    return path

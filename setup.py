"""Build step that pyproject.toml cannot express: the wheel carries the repository's
top-level data folders (shaders/, slides/, exercises/) as lab/_data/, where
lab.resources finds them. Editable installs read them from the clone instead."""

import shutil
from pathlib import Path

from setuptools import setup
from setuptools.command.build_py import build_py

HERE = Path(__file__).resolve().parent
DATA_FOLDERS = ("shaders", "slides", "exercises")  # = lab.resources.DATA_FOLDERS
SKIP = shutil.ignore_patterns("node_modules", "__pycache__", "*.pyc", ".*")


class BuildWithData(build_py):
    def run(self) -> None:
        editable = getattr(self, "editable_mode", False)
        if not editable:  # a stale build/lib would ship modules deleted since
            shutil.rmtree(Path(self.build_lib) / "lab", ignore_errors=True)
        super().run()
        if editable:
            return
        for name in DATA_FOLDERS:
            target = Path(self.build_lib) / "lab" / "_data" / name
            if target.exists():
                shutil.rmtree(target)
            shutil.copytree(HERE / name, target, ignore=SKIP)


setup(cmdclass={"build_py": BuildWithData})

"""The lean install (lab/requirements-core.txt: no scipy, PyQt6 or matplotlib) grades with
the same words as the full one: a grading run with those packages blocked gives the same
messages and diagnosis sentences, 'Likely' included, as one with them."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
DESKTOP_ONLY = ["PyQt6", "matplotlib", "pyqtgraph", "glfw", "scipy"]
BLOCKER = (
    "import sys\n"
    "class Block:\n"
    "    def find_spec(self, name, path=None, target=None):\n"
    f"        if name.split('.')[0] in {DESKTOP_ONLY!r}:\n"
    "            raise ImportError('the lean install has no ' + name)\n"
    "sys.meta_path.insert(0, Block())\n"
)


def grade(tmp_path: Path, submission: Path, lean: bool, name: str) -> dict:
    env = dict(os.environ)
    if lean:
        blocker = tmp_path / "blocker"
        blocker.mkdir(exist_ok=True)
        (blocker / "sitecustomize.py").write_text(BLOCKER, encoding="utf-8")
        env["PYTHONPATH"] = str(blocker)
    out = tmp_path / f"{name}.json"
    command = [sys.executable, "-m", "lab.cli", "grade", str(ROOT / "exercises" / "02_phong")]
    command += ["--submission", str(submission), "--json", str(out)]
    done = subprocess.run(command, env=env, capture_output=True, text=True, cwd=ROOT)
    assert done.returncode in (0, 1), done.stderr
    return {t["name"]: t["output"] for t in json.loads(out.read_text())["tests"]}


def test_the_lean_install_says_the_same_sentences(tmp_path):
    """A Phong lobe twice too wide: the polar check's diagnosis, and the row tolerances of
    the value checks, use lab.reference, which needed scipy and was dropped without a word."""
    solution = (ROOT / "solutions" / "02_phong" / "phong.glsl").read_text(encoding="utf-8")
    assert "pow(RoV, ke)" in solution
    submission = tmp_path / "phong.glsl"
    submission.write_text(solution.replace("pow(RoV, ke)", "pow(RoV, 0.5 * ke)"), "utf-8")
    full = grade(tmp_path, submission, lean=False, name="full")
    lean = grade(tmp_path, submission, lean=True, name="lean")
    assert lean == full
    # the polar check's diagnosis: the trace's line, or the lobe fitted with lab.reference
    said = [t for n, t in full.items() if "polar" in n and ("Likely:" in t or "Where:" in t)]
    assert said, full
    control = subprocess.run(
        [sys.executable, "-c", "import scipy"],
        env={**os.environ, "PYTHONPATH": str(tmp_path / "blocker")},
        capture_output=True,
        text=True,
    )
    assert "the lean install has no scipy" in control.stderr  # the blocker works

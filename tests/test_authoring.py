"""The authoring guide is the test's input: its code blocks alone make a new exercise
(Oren-Nayar), and `brdf-lab exercise check` grades its solution, stub and mistakes."""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
GUIDE = ROOT / "docs" / "authoring.md"
BLOCK = re.compile(r"^```\w+ file=(\S+)\n(.*?)^```$", re.S | re.M)


def build_from_guide(root: Path) -> Path:
    """Write each `file=PATH` block of the guide under `root`; returns the exercise folder."""
    blocks = BLOCK.findall(GUIDE.read_text(encoding="utf-8"))
    assert len(blocks) == 5, [path for path, _ in blocks]
    for path, text in blocks:
        (root / path).parent.mkdir(parents=True, exist_ok=True)
        (root / path).write_text(text, encoding="utf-8")
    return root / "exercises" / "11_oren_nayar"


def check(folder: Path) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-m", "lab.cli", "exercise", "check", str(folder)],
        capture_output=True,
        text=True,
        timeout=240,
    )


def rows(out: str) -> dict[str, list[str]]:
    """The table's rows by their first column."""
    found = {}
    for line in out.splitlines():
        cells = re.split(r"\s{2,}", line.strip())
        if len(cells) >= 4 and cells[3] in ("ok", "WRONG"):
            found[cells[0]] = cells
    return found


@pytest.fixture(scope="module")
def exercise(tmp_path_factory) -> Path:
    return build_from_guide(tmp_path_factory.mktemp("course"))


def test_the_guides_exercise_passes_exercise_check(exercise):
    done = check(exercise)
    assert done.returncode == 0, done.stdout + done.stderr
    table = rows(done.stdout)
    assert table["solution"][1] == "10/10"
    assert table["solution, hidden mode --seed 1"][1] == "10/10"
    assert table["stub"][1] != "10/10" and table["stub"][3] == "ok"
    mistakes = [cells for name, cells in table.items() if name.startswith("mistake")]
    assert len(mistakes) == 3
    for cells in mistakes:
        assert cells[1] != "10/10" and cells[3] == "ok", cells
        assert cells[4] == "hint named", cells  # the grader tells the student the hint
    references = exercise / "references"
    assert {"values.npz", "diagnosis.json", "sphere.back_light.png"} <= {
        p.name for p in references.iterdir()
    }


def test_a_mistake_no_check_sees_or_that_does_not_compile_is_reported(exercise):
    """A stored mistake that changes nothing, and one that does not compile, are WRONG in
    the table, each with what to do."""
    path = exercise.parent.parent / "solutions" / "11_oren_nayar" / "mistakes.toml"
    text = path.read_text(encoding="utf-8")
    path.write_text(
        text + "\n[[mistake]]\nedits = [['float s2 = sigma * sigma;', 'float s2 = sigma*sigma;']]"
        '\nhint = "no difference at all"\n'
        "\n[[mistake]]\nedits = [['float s2 = sigma * sigma;', 'float s2 = sigma * ;']]"
        '\nhint = "a syntax error"\n',
        encoding="utf-8",
    )
    try:
        done = check(exercise)
    finally:
        path.write_text(text, encoding="utf-8")
    assert done.returncode == 1, done.stdout + done.stderr
    assert rows(done.stdout)["mistake 4"][3] == "WRONG"
    assert "mistake 4 passes every check" in done.stdout
    assert rows(done.stdout)["mistake 5"][3] == "WRONG"
    assert re.search(r"mistake 5 does not compile \(\S+oren_nayar.glsl:\d+: ", done.stdout)

"""Exercise 14 on the page: the file compiles as the grader's build does: the solution
compiles in WebGL with the grader's texts around it (exercises.json `estimator`), and a slip
is reported at the student's own line on every check, as `brdf-lab grade` reports it. (Its
ibl_render checks' verdicts in the page: tests/test_web_practice.py.)"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from lab.web.browser import chromium_path
from tests.test_web_exercise import grade, page  # noqa: F401 - the page fixture

ROOT = Path(__file__).resolve().parents[1]
NAME = "14_reflection_equation"
FILE = "reflection_equation.glsl"
pytestmark = pytest.mark.skipif(chromium_path() is None, reason="no Chromium")


def compile_row(page, text: str) -> str:  # noqa: F811
    """The checks' rows: each waits for its run (✓ compiled) or names the compile error."""
    if page.evaluate("brdfLab.exercises?.exercise?.name ?? ''") != NAME:
        page.evaluate("n => brdfLab.openExercise(n)", NAME)
    runs = page.evaluate("brdfLab.exercises.runs")
    page.evaluate("t => brdfLab.editor.editor.setText(t)", text)
    page.wait_for_function(f"brdfLab.exercises.runs > {runs}")
    rows = page.evaluate(
        "[...document.querySelectorAll('#exercise ul.checks li[data-check]')].map(li => "
        "li.classList.contains('pending') ? '✓ compiled, runs on request' : li.textContent)"
    )
    assert rows and len(set(row[0] for row in rows)) == 1, rows  # all compile, or none
    return " ".join(rows)


def test_the_page_compiles_the_estimate_as_the_grader_does(page, tmp_path):  # noqa: F811
    solution = (ROOT / "solutions" / NAME / FILE).read_text(encoding="utf-8")
    assert "✓" in compile_row(page, solution)
    for label, text in (
        ("slip", solution.replace("return sum / float(n);", "return sum / float(n)")),
        ("unknown", solution.replace("environment(L)", "environment_map(L)")),
    ):
        path = tmp_path / label / FILE
        path.parent.mkdir()
        path.write_text(text, encoding="utf-8")
        graded = grade(NAME, path, tmp_path)
        assert graded and not any(passed for passed, _ in graded.values()), graded
        line = re.search(rf"{FILE}:(\d+)", " ".join(m for _, m in graded.values()))
        shown = compile_row(page, text)
        assert "✗" in shown and f"{FILE}:{line.group(1)}:" in shown, (shown, graded)
    assert page.errors == []

"""Exercise 15 in the page's practice mode (static/shcheck.js): the student's harmonics run in
the grader's view (grade_sh.glsl) at the grader's rows and are judged against the lab's values
shipped in exercises.json; the page's verdicts and points equal `brdf-lab grade`'s on the
solution, the stub, every stored mistake and the correct rewrites; the practice form is
accessible."""

from __future__ import annotations

import json
import re
import time
from pathlib import Path

import numpy as np
import pytest

from lab.web.browser import chromium_path

pytestmark = pytest.mark.skipif(
    chromium_path() is None, reason="Chromium is not installed (apt-get install chromium)"
)

ROOT = Path(__file__).resolve().parents[1]
NAME = "15_spherical_harmonics"
SOLUTIONS = ROOT / "solutions" / NAME


@pytest.fixture(scope="module")
def page(tmp_path_factory):
    from webpage import open_page

    with open_page(tmp_path_factory, "model=phong&size=96", 1300, 900) as tab:
        tab.evaluate("n => brdfLab.openExercise(n)", NAME)
        tab.wait_for_function("brdfLab.exercises.runs > 0", timeout=120_000)
        yield tab


def practice(page, text: str) -> tuple[dict[str, tuple[bool, str]], float]:
    """Each check's verdict and message on `text`, and the seconds the page took."""
    runs = page.evaluate("brdfLab.exercises.runs")
    start = time.perf_counter()
    page.evaluate("t => brdfLab.editor.editor.setText(t)", text)
    page.wait_for_function(f"brdfLab.exercises.runs > {runs}", timeout=120_000)
    seconds = time.perf_counter() - start
    results = page.evaluate(
        "brdfLab.exercises.results.map(r => [r.check.name, r.passed, r.message])"
    )
    return {name: (passed, message) for name, passed, message in results}, seconds


def grade(submission: Path, tmp_path: Path) -> dict[str, tuple[bool, str]]:
    from lab.cli import main

    out = tmp_path / f"{submission.parent.name}_{submission.stem}.json"
    main(["grade", str(ROOT / "exercises" / NAME), "--submission", str(submission),
          "--json", str(out)])  # fmt: skip
    tests = json.loads(out.read_text())["tests"]
    return {t["name"].split(".", 1)[1]: (t["status"] == "passed", t["output"]) for t in tests}


NUMBER = re.compile(r"[-+]?\d+(?:\.\d+)?(?:e[-+]?\d+)?")


def same_words(mine: str, theirs: str, rtol: float = 0.01) -> bool:
    """The same text, and the same numbers within `rtol`."""
    if NUMBER.sub("#", mine) != NUMBER.sub("#", theirs):
        return False
    pairs = zip(NUMBER.findall(mine), NUMBER.findall(theirs), strict=True)
    return all(abs(float(a) - float(b)) <= rtol * abs(float(b)) for a, b in pairs)


def files(tmp_path: Path) -> dict[str, Path]:
    """The solution, the stub, each stored mistake (applied to the solution) and each
    correct rewrite, by label."""
    from lab.grading.exercise import load_exercise
    from lab.grading.mistakes import known_mistakes

    exercise = load_exercise(ROOT / "exercises" / NAME)
    solution = exercise.solution.read_text(encoding="utf-8")
    out = {"solution": exercise.solution, "stub": exercise.stub}
    for variant in known_mistakes(exercise):
        path = tmp_path / variant.key / exercise.student_file
        path.parent.mkdir(parents=True)
        path.write_text(variant.apply(solution), encoding="utf-8")
        out[f"mistake {variant.key}"] = path
    out.update((f"correct {p.stem}", p) for p in sorted((SOLUTIONS / "correct").glob("*.glsl")))
    return out


def test_the_pages_rows_are_the_graders(page):
    """shcheck.js expands each check's directions into the rows sh.py's _rows makes (every
    (l, m) up to the order at each direction, in the same order): the logic is in both."""
    from lab.grading.exercise import load_exercise
    from lab.grading.kinds import kind_of

    exercise = load_exercise(ROOT / "exercises" / NAME)
    for check in exercise.checks:
        mine = page.evaluate(
            """async (name) => {
              const { shRows } = await import("./shcheck.js");
              const check = brdfLab.exercises.exercise.checks.find((c) => c.name === name);
              return shRows(check);
            }""",
            check.name,
        )
        assert np.array_equal(np.array(mine), kind_of(check).rows(check)), check.name


def test_practice_gives_the_graders_verdicts(page, tmp_path, output_dir):
    """Every check's pass or fail and the points equal brdf-lab grade's on the solution, the
    stub, every stored mistake and every correct rewrite; the first sentence (how many values
    are off, where, the values) is the grader's (the counts and timings go to output_dir)."""
    points = {c["name"]: c["points"] for c in page.evaluate("brdfLab.exercises.exercise.checks")}
    assert sorted(points) == ["basis.low_bands", "basis.order_6", "ggx", "lambert", "phong"]
    assert page.evaluate("brdfLab.exercises.exercise.grader_only") == []
    found = files(tmp_path)
    assert len(found) >= 2 + 12 + 3
    differ, words, agree, times, likely, failed = [], [], 0, {}, [], 0
    for label, path in found.items():
        theirs = grade(path, tmp_path)
        mine, times[label] = practice(page, path.read_text(encoding="utf-8"))
        assert set(mine) == set(theirs), label
        for name, (passed, message) in mine.items():
            if passed != theirs[name][0]:
                differ.append(f"{label} {name}: page {message!r}, grader {theirs[name][1]!r}")
            else:
                agree += 1
            # the first sentence (how many values are off, which, the lobe's distance) read
            # as the grader's, its numbers within 1 %: a wrong file's own values come from
            # another GPU (the page counts 2162 rows off where llvmpipe counts 2160)
            first = re.split(r"\. |\n", theirs[name][1])[0]
            # the likely mistake, said as the grader says it save where in the code (its
            # trace, which the page has not): counted, not required
            said = [re.sub(r" Where: .*", "", m.split(". Likely: ", 1)[-1]) if ". Likely: " in m
                    else "" for m in (message, theirs[name][1].split("\n")[0])]  # fmt: skip
            failed += not passed
            if not passed and said[0] != said[1]:
                likely.append(f"{label} {name}: page {said[0]!r}, grader {said[1]!r}")
            if not same_words(re.split(r"\. |\n", message)[0], first):
                words.append(f"{label} {name}: page {message!r}, grader {first!r}")
        score = sum(points[n] for n, (p, _) in mine.items() if p)
        assert score == sum(points[n] for n, (p, _) in theirs.items() if p) or differ, label
        if label.startswith(("solution", "correct")):
            assert score == sum(points.values()), (label, mine)
        else:
            assert score < sum(points.values()), label
    counts = {"files": len(found), "checks": len(found) * len(points), "verdicts_agree": agree,
              "verdicts_differ": len(differ), "failed": failed, "first_sentence_differs": words,
              "likely_differs": likely, "seconds": times}  # fmt: skip
    (output_dir / "web_sh_verdicts.json").write_text(json.dumps(counts, indent=1))
    assert not differ, "\n".join(differ)
    assert not words, "\n".join(words)
    assert page.errors == []


def rerun(page) -> float:
    """The page's milliseconds to run the five checks again on the same text (programs
    compiled), diagnosis and all."""
    return page.evaluate(
        """() => {
          const start = performance.now();
          brdfLab.exercises.run();
          return performance.now() - start;
        }"""
    )


def test_practice_form_is_accessible(page, output_dir):
    """axe finds no violation on exercise 15's results, passed and failed (with the failed
    checks' tables); the page's time to run the checks goes to output_dir."""
    from axe import violations

    text = (SOLUTIONS / "sh_projection.glsl").read_text(encoding="utf-8")
    shown, _ = practice(page, text)
    assert all(passed for passed, _ in shown.values()), shown
    assert violations(page) == []
    solution_ms = rerun(page)
    stub = (ROOT / "exercises" / NAME / "sh_projection.glsl").read_text(encoding="utf-8")
    shown, _ = practice(page, stub)
    assert not any(passed for passed, _ in shown.values()), shown
    # each failed check's table (the grader's report's): a labelled region the keyboard can
    # scroll, its rows marked in words
    region = page.locator('#exercise .exercise-table[data-check="lambert"] [role=region]')
    assert region.get_attribute("tabindex") == "0" and "lab's" in region.get_attribute("aria-label")
    cells = region.locator("tbody tr").first.locator("td").all_inner_texts()
    assert cells[0].startswith("(1, ") and cells[1] == "0" and cells[3] == "✗ differs", cells
    assert page.locator("#exercise .exercise-table").count() == 5
    assert violations(page) == []
    page.locator("#exercise").screenshot(path=output_dir / "web_practice_sh.png")
    stub_ms = rerun(page)
    assert max(solution_ms, stub_ms) < 5000, (solution_ms, stub_ms)
    (output_dir / "web_sh_run.json").write_text(json.dumps({"solution_ms": solution_ms,
                                                            "stub_ms": stub_ms}))  # fmt: skip
    assert page.errors == []

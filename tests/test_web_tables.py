"""Exercise 12 in the page's practice mode: the page makes the tables its checks read on its
own GPU (static/tables.js, shaders/views/tabulate.glsl) from the grader's recipe and
tabulate.py's counter-based noise; its tables equal the grader's, and its verdicts equal
`brdf-lab grade`'s on the solution, the stub, every stored mistake and the correct
rewrites; the practice form is accessible."""

from __future__ import annotations

import base64
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
NAME = "12_tabulated_lookup"
SOLUTIONS = ROOT / "solutions" / NAME
LAYERS = [0, 1, 2, 7, 30, 60, 89]  # theta_h bins compared (the peak's first, then wider)


@pytest.fixture(scope="module")
def page(tmp_path_factory):
    from webpage import open_page

    with open_page(tmp_path_factory, "model=phong&size=96", 1300, 900) as tab:
        yield tab


@pytest.fixture(scope="module")
def opened(page):
    """Exercise 12 opened (its tables made), and how long the page took."""
    start = time.perf_counter()
    page.evaluate("n => brdfLab.openExercise(n)", NAME)
    page.wait_for_function("brdfLab.exercises.runs > 0", timeout=120_000)
    seconds = time.perf_counter() - start
    return page, page.evaluate("brdfLab.exercises.tables.ms"), seconds


def practice(page, text: str) -> dict[str, tuple[bool, str]]:
    runs = page.evaluate("brdfLab.exercises.runs")
    page.evaluate("t => brdfLab.editor.editor.setText(t)", text)
    page.wait_for_function(f"brdfLab.exercises.runs > {runs}", timeout=120_000)
    results = page.evaluate(
        "brdfLab.exercises.results.map(r => [r.check.name, r.passed, r.message])"
    )
    return {name: (passed, message) for name, passed, message in results}


def grade(submission: Path, tmp_path: Path) -> dict[str, tuple[bool, str]]:
    from lab.cli import main

    out = tmp_path / f"{submission.parent.name}_{submission.stem}.json"
    main(["grade", str(ROOT / "exercises" / NAME), "--submission", str(submission),
          "--json", str(out)])  # fmt: skip
    tests = json.loads(out.read_text())["tests"]
    return {t["name"].split(".", 1)[1]: (t["status"] == "passed", t["output"]) for t in tests}


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


def grader_table(check_name: str) -> np.ndarray:
    """The grader's table of the check (RGB f_r, dims + (3,)), made as it grades."""
    from lab.grading import tables
    from lab.grading.exercise import load_exercise

    exercise = load_exercise(ROOT / "exercises" / NAME)
    check = next(c for c in exercise.checks if c.name == check_name)
    assert tables.made_here(check)
    spec = check.table[0]
    found = tables._tables[(spec.model, spec.params, spec.noise, spec.dims)]
    return np.maximum(found.table.rgb, 0.0)


@pytest.mark.parametrize("check", ["bins.index", "probe.lookup"], ids=["noisy", "smooth"])
def test_the_pages_table_is_the_graders(opened, check, output_dir):
    """Bin for bin the grader's table on the layers compared, noise and all: within float32
    rounding of a model's shader on two GPUs (1.2e-5 relative at most over all 1.46 M bins;
    3e-5 allowed, against the 2 % noise, so a noise off by one bin shows), and
    the page took under 2 s to make its tables (the figure is written to output_dir)."""
    page, ms, seconds = opened
    encoded = page.evaluate(
        """([name, layers]) => {
          const mode = brdfLab.exercises;
          const check = mode.exercise.checks.find((c) => c.name === name);
          const bytes = new Uint8Array(mode.tables.texels(check, layers).buffer);
          let text = "";
          for (let i = 0; i < bytes.length; i += 8192) {
            text += String.fromCharCode(...bytes.subarray(i, i + 8192));
          }
          return btoa(text);
        }""",
        [check, LAYERS],
    )
    mine = np.frombuffer(base64.b64decode(encoded), "<f4").reshape(len(LAYERS), 90, 180, 4)[..., :3]
    theirs = grader_table(check)[LAYERS]
    off = np.abs(mine - theirs)
    allowed = 3e-5 * np.abs(theirs) + 1e-7
    assert (off <= allowed).all(), (np.argwhere(off > allowed)[:5], off.max())
    if check == "bins.index":  # the noise is there: 2 % from the smooth table's values
        smooth = grader_table("probe.lookup")[LAYERS]
        lit = smooth > 1e-3
        assert 0.015 < np.std(mine[lit] / smooth[lit]) < 0.025
    assert ms < 2000, ms
    (output_dir / "web_tables_build.json").write_text(
        json.dumps({"table_ms": ms, "open_s": seconds})
    )


def test_practice_gives_the_graders_verdicts(opened, tmp_path, output_dir):
    """Every check's pass or fail and the points equal brdf-lab grade's on the solution, the
    stub, every stored mistake and every correct rewrite (the counts go to output_dir)."""
    page = opened[0]
    points = {c["name"]: c["points"] for c in page.evaluate("brdfLab.exercises.exercise.checks")}
    assert sorted(points) == ["bins.index", "bins.lookup", "probe.lookup", "sphere.grazing",
                              "sphere.lookup"]  # fmt: skip
    assert page.evaluate("brdfLab.exercises.exercise.grader_only") == []
    found = files(tmp_path)
    assert len(found) == 2 + 12 + 3
    differ, same_words, agree = [], 0, 0
    for label, path in found.items():
        theirs = grade(path, tmp_path)
        mine = practice(page, path.read_text(encoding="utf-8"))
        assert set(mine) == set(theirs), label
        for name, (passed, message) in mine.items():
            if passed != theirs[name][0]:
                differ.append(f"{label} {name}: page {message!r}, grader {theirs[name][1]!r}")
            else:
                agree += 1
            # the first sentence (how many rows or pixels are off) read as the grader's
            first = re.split(r"\. |\n", theirs[name][1])[0]
            same_words += message.startswith(first)
        score = sum(points[n] for n, (p, _) in mine.items() if p)
        assert score == sum(points[n] for n, (p, _) in theirs.items() if p) or differ, label
        if label.startswith(("solution", "correct")):
            assert score == sum(points.values()), (label, mine)
        else:
            assert score < sum(points.values()), label
    counts = {"files": len(found), "verdicts_agree": agree, "verdicts_differ": len(differ),
              "first_sentence_same": same_words}  # fmt: skip
    (output_dir / "web_tables_verdicts.json").write_text(json.dumps(counts))
    assert not differ, "\n".join(differ)


def test_practice_form_is_accessible(opened, output_dir):
    """axe finds no violation on exercise 12's results; no check is left to the grader."""
    from axe import violations

    page = opened[0]
    text = (SOLUTIONS / "tabulated.glsl").read_text(encoding="utf-8")
    results = practice(page, text.replace("vec3 t = merl_position(angles) - 0.5;",
                                          "vec3 t = merl_position(angles);"))  # fmt: skip
    assert not results["bins.lookup"][0]
    assert page.locator("#exercise .grader-only").count() == 0
    assert violations(page) == []
    page.locator("#exercise").screenshot(path=output_dir / "web_practice_tables.png")


def test_building_the_tables_is_said_in_words(page):
    """While the tables are made the section says so; a table the page cannot make fails its
    checks with words (not a stuck page or a traceback)."""
    said = page.evaluate(
        """async (name) => {
          const mode = brdfLab.exercises;
          const seen = [];
          const root = document.querySelector('#exercise');
          const watch = new MutationObserver(() => seen.push(root.textContent));
          watch.observe(root, { childList: true, subtree: true });
          const exercise = (await mode.load()).find((e) => e.name === name);
          const saved = exercise.checks[0].table[0].model;
          await mode.open(name);
          watch.disconnect();
          exercise.checks[0].table[0].model = 'no_such_model';
          await mode.open(name);
          const results = mode.results.map((r) => [r.check.name, r.passed, r.message]);
          exercise.checks[0].table[0].model = saved;
          await mode.open(name);
          return { seen, results };
        }""",
        NAME,
    )
    assert any("building table…" in text for text in said["seen"]), said["seen"][:3]
    broken = {name: (passed, message) for name, passed, message in said["results"]}
    passed, message = broken["bins.index"]
    assert not passed and "cannot make the table" in message and "no_such_model" in message

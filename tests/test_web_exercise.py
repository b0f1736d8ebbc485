"""Exercise mode in the page: the practice verdict of every check equals `brdf-lab grade` on
the same file, for a correct and a wrong submission, with the grader's messages."""

from __future__ import annotations

import json
import re
from pathlib import Path

import numpy as np
import pytest

from lab.web.browser import chromium_path

pytestmark = pytest.mark.skipif(
    chromium_path() is None, reason="Chromium is not installed (apt-get install chromium)"
)

ROOT = Path(__file__).resolve().parents[1]
# (exercise, the solution's file, a wrong version of it: one typical slip)
CASES = [
    ("02_phong", "phong.glsl", ("pow(RoV, ke)", "pow(RoV, ke * 0.5)")),
    ("02_phong", "phong.glsl", ("max(dot(R, V), 0.0)", "abs(dot(R, V))")),
    # a rougher Beckmann lobe peaks further out at the same width: the roughness is named
    ("06_microfacet_distributions", "distributions.glsl", ("m2 = m * m", "m2 = 2.25 * m * m")),
    ("07_geometric_attenuation", "geometry.glsl", ("min(1.0", "max(1.0")),
]


@pytest.fixture(scope="module")
def page(tmp_path_factory):
    from lab.web.browser import chromium
    from lab.web.site import export, serving

    site = export(tmp_path_factory.mktemp("site")).parent
    with serving(site) as url, chromium() as browser:
        tab = browser.new_page(viewport={"width": 1300, "height": 900})
        tab.errors = []
        tab.on("pageerror", lambda e: tab.errors.append(str(e)))
        tab.goto(f"{url}index.html#model=phong&size=96")
        tab.evaluate("window.brdfLab.ready")
        yield tab


FLIP_TOL = 2e-3


def flip(message: str) -> float:
    return float(re.search(r"mean FLIP (\d+\.\d+)", message).group(1))


def grade(exercise: str, submission: Path, tmp_path: Path) -> dict[str, tuple[bool, str]]:
    from lab.cli import main

    out = tmp_path / f"{submission.stem}.json"
    main(
        [
            "grade",
            str(ROOT / "exercises" / exercise),
            "--submission",
            str(submission),
            "--json",
            str(out),
        ]
    )
    tests = json.loads(out.read_text())["tests"]
    return {t["name"].split(".", 1)[1]: (t["status"] == "passed", t["output"]) for t in tests}


def practice(page, exercise: str, text: str) -> dict[str, tuple[bool, str]]:
    if page.evaluate("brdfLab.exercises?.exercise?.name ?? ''") != exercise:
        page.evaluate("n => brdfLab.openExercise(n)", exercise)
    runs = page.evaluate("brdfLab.exercises.runs")
    page.evaluate("t => brdfLab.editor.editor.setText(t)", text)
    page.wait_for_function(f"brdfLab.exercises.runs > {runs}")
    results = page.evaluate(
        "brdfLab.exercises.results.map(r => [r.check.name, r.passed, r.message])"
    )
    return {name: (passed, message) for name, passed, message in results}


@pytest.mark.parametrize("exercise,student_file,slip", CASES)
def test_practice_verdict_equals_the_grader(page, tmp_path, exercise, student_file, slip):
    solution = (ROOT / "solutions" / exercise / student_file).read_text()
    assert slip[0] in solution
    wrong = solution.replace(slip[0], slip[1], 1)
    for label, text in (("correct", solution), ("wrong", wrong)):
        path = tmp_path / label / student_file
        path.parent.mkdir()
        path.write_text(text)
        graded = grade(exercise, path, tmp_path)
        shown = practice(page, exercise, text)
        assert set(shown) == set(graded)
        for name, (passed, message) in graded.items():
            assert shown[name][0] == passed, (label, name, shown[name], message)
            # The grader may add its diagnosis ('. Likely: ...'); FLIP as the grader computes
            # it, from this rasterizer's render (a pixel's byte may differ by one). Where the
            # grader's trace of the code overrules a stored hint (lab.grading.localise), the
            # page, which cannot trace, keeps the hint: then the verdicts must agree.
            mine = shown[name][1].split(", mean FLIP")[0]
            if ". Likely: " not in message or "Where: " in message:
                mine = mine.split(". Likely: ")[0]  # (the sentence: test below)
            assert message.startswith(mine), (label, name, shown[name][1], message)
            if ", mean FLIP " in message:
                assert abs(flip(shown[name][1]) - flip(message)) <= FLIP_TOL, (name, message)
        if label == "correct":
            assert all(passed for passed, _ in graded.values())
        else:
            assert not all(passed for passed, _ in graded.values())
    assert page.locator("#exercise .practice").inner_text().startswith("practice check")
    assert page.errors == []


def test_exercise_mode_shows_reference_yours_and_signed_difference(page, output_dir):
    practice(
        page,
        "02_phong",
        (ROOT / "solutions/02_phong/phong.glsl")
        .read_text()
        .replace("pow(RoV, ke)", "pow(RoV, ke) * 1.5"),
    )
    figures = page.locator("#exercise .exercise-images figure")
    assert figures.count() == 3
    captions = [figures.nth(i).locator("figcaption").inner_text() for i in range(3)]
    assert captions[0].startswith("reference") and captions[1] == "yours"
    assert "red: too bright" in captions[2]
    # Too bright a highlight: the difference image has red pixels and no blue ones.
    red_blue = page.evaluate(
        """() => { const c = document.querySelectorAll('#exercise canvas')[2];
          const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
          let red = 0, blue = 0;
          for (let i = 0; i < d.length; i += 4) {
            if (d[i] - d[i + 2] > 30) red++;
            if (d[i + 2] - d[i] > 30) blue++;
          }
          return [red, blue]; }"""
    )
    assert red_blue[0] > 20 and red_blue[1] == 0, red_blue
    page.locator("#exercise").screenshot(path=output_dir / "web_exercise.png")


# Wrong submissions the grader's diagnosis names in different ways: a stored known mistake,
# the wrong one of two declared terms with the shape of its error, the shape of the whole
# error (a factor), the lobe's width with the exponent fitted from the grader's width table
# (diagnosis.width_table, in exercises.json), a generated mutant (sphere images too).
DIAGNOSED = [
    ("02_phong", "phong.glsl", ("kd * INV_PI", "kd")),
    ("02_phong", "phong.glsl", ("ks * pow(RoV, ke)", "ks * 3.0 * pow(RoV, ke)")),
    ("02_phong", "phong.glsl", ("pow(RoV, ke)", "pow(RoV, ke * 0.5)")),
    ("03_blinn_phong", "blinn_phong.glsl", ("pow(NoH, ke)", "pow(NoH, 4.0 * ke)")),
    ("07_geometric_attenuation", "geometry.glsl", ("max(VoH, EPS)", "max(NoL, EPS)")),
    ("02_phong", "phong.glsl", ("max(dot(R, V), 0.0)", "abs(dot(R, V))")),
    # a rougher Beckmann lobe peaks further out at the same width: the roughness is named
    ("06_microfacet_distributions", "distributions.glsl", ("m2 = m * m", "m2 = 2.25 * m * m")),
]


def unlocated(message: str) -> str:
    """The grader's message without where the fault is ('Where: ...', from the trace of
    the code: lab.grading.localise), which the page cannot say."""
    message = re.sub(r"(?<=\.) Where: [^\n]*", "", message)
    return re.sub(r"^(.*?)\. Where: [^\n]*", r"\1", message, flags=re.M)


def likely(message: str) -> str:
    """The diagnosis sentence (the grader's output goes on with where the fault is, which
    only the grader can trace, and a table of rows)."""
    if "Likely: " not in message:
        return ""
    return message.split("Likely: ", 1)[1].split("\n")[0].split(" Where: ")[0]


@pytest.mark.parametrize("exercise,student_file,slip", DIAGNOSED)
def test_practice_diagnosis_equals_the_grader(page, tmp_path, exercise, student_file, slip):
    """Each failed check shows the grader's own 'Likely: ...' sentence (or none, as it)."""
    solution = (ROOT / "solutions" / exercise / student_file).read_text()
    assert slip[0] in solution
    path = tmp_path / student_file
    path.write_text(solution.replace(slip[0], slip[1], 1))
    graded = grade(exercise, path, tmp_path)
    shown = practice(page, exercise, path.read_text())
    assert not all(passed for passed, _ in graded.values())
    named = 0
    for name, (passed, message) in graded.items():
        assert shown[name][0] == passed, (name, shown[name], message)
        if "Where: " not in message:
            assert likely(shown[name][1]) == likely(message), (name, shown[name][1], message)
        elif "Likely: " in message:  # with the trace's line, no shape of the error after it
            mine, theirs = likely(shown[name][1]), likely(message).rstrip(".")
            assert mine.startswith(theirs), (name, shown[name][1], message)
        # else the grader traced the code to a line the page cannot know, and says that
        named += bool(likely(message) or "Where: " in message)
    assert named, f"the grader names no likely mistake for {slip}: pick another slip"
    if slip[0].startswith("pow("):  # the exponent scaled: fitted from the same table
        assert any(
            "exponent of about" in likely(m) or "to the power" in m for _, m in graded.values()
        ), graded
    assert page.errors == []


SAMPLER = "10_importance_sampling"
SAMPLER_FILE = "blinn_phong_sampling.glsl"
# Slips of exercise 10: the sampler's exponent (a stored mistake; only the chi-square
# fails), the pdf's Jacobian (every sampling check fails) and a pdf 1.2 times too large
# (named as a stored mistake at ke = 4, explained as "the pdf is what is wrong" at ke = 20).
SAMPLER_SLIPS = [
    ("1.0 / (ke + 1.0)", "1.0 / (ke + 2.0)"),
    ("pdf_half_vector(H, N) / (4.0 * VoH)", "pdf_half_vector(H, N)"),
    ("(ke + 1.0) * 0.5 * INV_PI", "(ke + 1.0) * 0.6 * INV_PI"),
]


def sampling_practice(page, text: str) -> dict[str, tuple[bool, str]]:
    """The page's sampling checks (run on request) on `text`: {name: (passed, message)}."""
    practice(page, SAMPLER, text)
    results = page.evaluate(
        "brdfLab.exercises.runSampling()"
        ".then(rs => rs.map(r => [r.check.name, r.passed, r.message]))"
    )
    return {name: (passed, message) for name, passed, message in results}


def shape(message: str) -> str:
    """A message with its numbers blanked (the page's GPU rounds the student's pow and
    sin a little differently: chi-square 533 where the grader has 532)."""
    return re.sub(r"\d+", "#", message)


@pytest.mark.parametrize("slip", [None, *SAMPLER_SLIPS])
def test_sampling_checks_give_the_graders_verdicts(page, tmp_path, slip):
    """Exercise 10's checks run in the page (the grader's directions, random numbers,
    quadrature and second draws) with the grader's verdicts and messages, its likely
    mistake included: chi-square and pdf integral; the IBL render's verdict (its words from
    other random draws: tests/test_web_practice.py)."""
    text = (ROOT / "solutions" / SAMPLER / SAMPLER_FILE).read_text()
    if slip:
        assert slip[0] in text
        text = text.replace(*slip)
    path = tmp_path / SAMPLER_FILE
    path.write_text(text)
    graded = grade(SAMPLER, path, tmp_path)
    web = sampling_practice(page, text)
    assert set(web) == set(graded)  # every check runs in the page
    for name, (passed, message) in web.items():
        assert passed == graded[name][0], (name, message, graded[name][1])
        if name.startswith("ibl_render."):
            continue
        graders = unlocated(graded[name][1])
        if "Where: " in graded[name][1] and "Likely: " not in graded[name][1]:
            message = message.split(" Likely: ")[0]  # the grader traced the code instead
        mine, theirs = shape(message).rstrip("."), shape(graders).rstrip(".")
        assert mine == theirs, (name, message, graded[name][1])
    assert (slip is None) == all(passed for passed, _ in web.values())
    assert "only the grader runs" not in page.locator("#exercise").inner_text()
    assert page.errors == []


def test_sampling_checks_wait_for_the_button_and_name_compile_errors(page, tmp_path):
    solution = (ROOT / "solutions" / SAMPLER / SAMPLER_FILE).read_text()
    practice(page, SAMPLER, solution)
    pending = page.locator("#exercise li.pending")
    assert pending.count() == 4  # typing does not run seconds of sampling
    page.locator("#exercise button.run-sampling").click()
    page.wait_for_function("document.querySelectorAll('#exercise li.pending').length === 0")
    assert page.locator("#exercise li.pass").count() == 4
    # The grader's pictures: a correct sampler's histogram looks like its pdf's.
    figures = page.locator('#exercise .exercise-images[data-check="chi_square.glossy"] canvas')
    assert figures.count() == 3
    pixels = figures.evaluate_all(
        "cs => cs.map(c => Array.from(c.getContext('2d')"
        ".getImageData(0, 0, c.width, c.height).data))"
    )
    pdf, samples, theirs = (np.array(p, float).reshape(-1, 4)[:, :3] for p in pixels)
    assert pdf.max() > 200 and np.abs(pdf - samples).mean() < 8
    np.testing.assert_allclose(pdf, theirs, atol=2)  # the solution's pdf: the same
    # A mistake the compiler finds: the grader's file and line, on every check.
    lines = solution.splitlines()
    line = next(i for i, t in enumerate(lines, 1) if "float pdf_lobe" in t)
    lines[line] = lines[line] + " undefined_name;"
    broken = "\n".join(lines) + "\n"
    path = tmp_path / SAMPLER_FILE
    path.write_text(broken)
    graded = grade(SAMPLER, path, tmp_path)
    where = re.search(r"blinn_phong_sampling\.glsl:(\d+)", graded["chi_square.glossy"][1])
    results = practice(page, SAMPLER, broken)
    for name, (passed, message) in results.items():
        assert not passed and not graded[name][0]
        assert f"{SAMPLER_FILE}:{where.group(1)}:" in message, (name, message)
    assert page.errors == []


def test_every_solution_passes_in_the_page_one_exercise_after_another(page):
    """As the grader passes them: 06's Blinn exponent ln 2 / -ln cos(beta) once failed on
    SwiftShader's coarse cos, and the sixth exercise opened found no free panel."""
    from lab.grading.exercise import find_exercises

    for exercise in find_exercises(ROOT / "exercises"):
        if exercise.sampler_for:
            continue  # its checks run on request (test_sampling_checks_give_...)
        shown = practice(page, exercise.name, exercise.solution.read_text(encoding="utf-8"))
        assert shown and all(passed for passed, _ in shown.values()), (exercise.name, shown)
    assert page.evaluate("brdfLab.state.panels.length") <= 2
    assert page.errors == []


@pytest.mark.parametrize("exercise", ["02_phong", "07_geometric_attenuation"])
def test_the_untouched_stub_gets_the_graders_sentence(page, tmp_path, exercise):
    """The stub is told its TODO steps are not done, in the page as by the grader (not a
    stored mistake whose values it happens to give)."""
    from lab.grading.mistakes import STUB_HINT

    stub = next((ROOT / "exercises" / exercise).glob("*.glsl"))
    graded = grade(exercise, stub, tmp_path)
    shown = practice(page, exercise, stub.read_text())
    for name, (passed, message) in graded.items():
        assert shown[name][0] == passed, name
        assert likely(shown[name][1]) == likely(message), (name, shown[name][1], message)
    assert any(likely(m) == f"{STUB_HINT}." for _, m in graded.values()), graded
    assert page.errors == []

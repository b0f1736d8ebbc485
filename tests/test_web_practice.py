"""The page's practice mode of the kinds that run more than a model at angles: exercise 11's
`properties` checks (the student's tests linked with each check's model, properties.js)
give `brdf-lab grade`'s verdict and words on the same file."""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest

from lab.web.browser import chromium_path

pytestmark = pytest.mark.skipif(
    chromium_path() is None, reason="Chromium is not installed (apt-get install chromium)"
)

ROOT = Path(__file__).resolve().parents[1]
PROPERTIES = "11_brdf_properties"


@pytest.fixture(scope="module")
def page(tmp_path_factory):
    from webpage import open_page

    with open_page(tmp_path_factory, "model=phong&size=96", 1300, 900) as tab:
        yield tab


def grade(exercise: str, submission: Path, tmp_path: Path) -> dict[str, tuple[bool, str]]:
    from lab.cli import main

    out = tmp_path / f"{submission.stem}.json"
    main(["grade", str(ROOT / "exercises" / exercise), "--submission", str(submission),
          "--json", str(out)])  # fmt: skip
    tests = json.loads(out.read_text())["tests"]
    return {t["name"].split(".", 1)[1]: (t["status"] == "passed", t["output"]) for t in tests}


def practice(page, exercise: str, text: str) -> dict[str, tuple[bool, str]]:
    if page.evaluate("brdfLab.exercises?.exercise?.name ?? ''") != exercise:
        page.evaluate("n => brdfLab.openExercise(n)", exercise)
    runs = page.evaluate("brdfLab.exercises.runs")
    page.evaluate("t => brdfLab.editor.editor.setText(t)", text)
    page.wait_for_function(f"brdfLab.exercises.runs > {runs}", timeout=120_000)
    results = page.evaluate(
        "brdfLab.exercises.results.map(r => [r.check.name, r.passed, r.message])"
    )
    return {name: (passed, message) for name, passed, message in results}


def unlocated(message: str) -> str:
    """The grader's message without where the fault is ('Where: ...', from its trace of the
    code, lab.grading.localise), which the page cannot say."""
    return re.sub(r" Where: [^\n]*", "", message).split("\n")[0]


NUMBER = re.compile(r"[-+]?\d+(?:\.\d+)?(?:e[-+]?\d+)?")


def same_words(mine: str, theirs: str, rtol: float = 0.01) -> bool:
    """The same text, and the same numbers within `rtol`: a wrong test's own values (not the
    grader's measurement, which the page is given) come from another GPU's sin and cos
    (the page's 1.475 where the grader's llvmpipe gives 1.479 on a peaked lobe)."""
    if NUMBER.sub("#", mine) != NUMBER.sub("#", theirs):
        return False
    pairs = zip(NUMBER.findall(mine), NUMBER.findall(theirs), strict=True)
    return all(abs(float(a) - float(b)) <= rtol * abs(float(b)) for a, b in pairs)


# The solution, the stub, and every wrong submission of exercise 11's batches (written before
# its diagnosis was tuned, and held out after): stored mistakes, a test that always says
# "pass", ones named by the shape of their values and ones the grader names nothing for.
FILES = [
    "solutions/11_brdf_properties/properties.glsl",
    "exercises/11_brdf_properties/properties.glsl",
    *sorted(p.relative_to(ROOT).as_posix() for p in (ROOT / "tests/exercise_11").glob("*/*.glsl")),
]


@pytest.mark.parametrize("file", FILES, ids=lambda f: Path(f).stem)
def test_properties_practice_gives_the_graders_verdicts_and_words(page, tmp_path, file):
    text = (ROOT / file).read_text(encoding="utf-8")
    path = tmp_path / "properties.glsl"
    path.write_text(text, encoding="utf-8")
    graded = grade(PROPERTIES, path, tmp_path)
    shown = practice(page, PROPERTIES, text)
    assert set(shown) == set(graded)
    for name, (passed, message) in graded.items():
        assert shown[name][0] == passed, (name, shown[name][1], message)
        assert same_words(shown[name][1], unlocated(message)), (name, shown[name][1], message)
    if file.startswith("solutions/"):
        assert all(passed for passed, _ in graded.values())
    else:
        assert not all(passed for passed, _ in graded.values())
    assert page.errors == []


# -- ibl_render: exercise 10's render check (static/iblcheck.js) ----------------------------
SAMPLER = "10_importance_sampling"
SAMPLER_FILE = "blinn_phong_sampling.glsl"
IBL = "ibl_render.grey_room"


def test_ibl_statistics_equal_the_graders_on_the_same_arrays(page):
    """iblcheck.js's judge_render, t_limit and nearest on the grader's own arrays (the
    stored mistakes' renders and the reference): the grader's verdicts, words and figures."""
    import base64

    import numpy as np

    from lab.grading import mistakes, sampling
    from lab.grading.exercise import load_exercise
    from lab.grading.kinds import kind_of

    exercise = load_exercise(ROOT / "exercises" / SAMPLER)
    check = next(c for c in exercise.checks if c.name == IBL)
    kind = kind_of(check)
    hints = mistakes.read_hints(exercise)
    with np.load(exercise.references / "values.npz") as values:
        reference = values[IBL]
    with np.load(exercise.references / mistakes.VALUES) as data:
        stored = {k.split("|", 1)[1]: data[k] for k in data.files if k.startswith(f"{IBL}|")}
    # Besides: an unbiased estimator three times as noisy, and one with a NaN pixel.
    noisy = reference.copy()
    noisy[2, ..., 0] *= 9.0
    broken = reference.copy()
    broken[1, 16, 16, 1] = np.nan
    renders = {"solution": reference, "noisy": noisy, "nan": broken, **stored}
    js = page.evaluate(
        """async ([name, arrays]) => {
          const m = await import('./iblcheck.js');
          const data = await (await fetch('exercises.json')).json();
          (await import('./diagnosis.js')).useRules(data.diagnosis);  // its sentences
          const exercise = data.exercises.find((e) => e.name === '10_importance_sampling');
          const check = exercise.checks.find((c) => c.name === name);
          const luma = brdfLab.state.constants.LUMA;
          const out = {};
          for (const [key, text] of Object.entries(arrays)) {
            const bytes = Uint8Array.from(atob(text), (c) => c.charCodeAt(0));
            const raw = new Float32Array(bytes.buffer);
            const verdict = m.judgeRender(check, raw, luma);
            out[key] = [verdict.passed, verdict.message, verdict.stats,
              m.nearestRender(check, exercise, raw, luma)];
          }
          out.limits = [1, 2.5, 7, 31, 400].map((dof) => m.tLimit(check.z_normal, dof));
          return out;
        }""",
        [
            IBL,
            {k: base64.b64encode(v.astype("<f4").tobytes()).decode() for k, v in renders.items()},
        ],
    )
    passes, o = kind.passes(check), check.options
    groups = sampling.Z_GROUPS + 1
    for dof, limit in zip([1, 2.5, 7, 31, 400], js.pop("limits"), strict=True):
        assert limit == pytest.approx(sampling.t_limit(o["alpha"], groups, dof), rel=1e-12)
    verdicts = set()
    for key, raw in renders.items():
        ok, message, stats = sampling.judge_render(
            raw, reference, o["samples"], passes, o["factor"], o["alpha"]
        )
        passed, words, figures, likely = js[key]
        assert (passed, words) == (ok, message), key
        for name, value in stats.items():
            assert figures[name] == pytest.approx(value, rel=1e-9), (key, name)
        found = kind.nearest(check, kind.stored(raw, check), reference, {
            k: v for k, v in stored.items() if k in hints
        })  # fmt: skip
        assert likely == (f"Likely: {hints[found].rstrip('.')}." if found else ""), key
        verdicts.add("passes" if ok else "bias" if "biased" in message else message[-30:])
    assert len(verdicts) == 4, verdicts  # passes, biased, noisy, NaN


# Slips of exercise 10 (as tests/test_web_exercise.py's) and whether the IBL render passes:
# the sampler's exponent (its draws follow another lobe, weighed by their own pdf: unbiased,
# only the chi-square sees it), the pdf's Jacobian and a pdf 1.2 times too large (biased).
IBL_SLIPS = [
    (None, True),
    (("1.0 / (ke + 1.0)", "1.0 / (ke + 2.0)"), True),
    (("pdf_half_vector(H, N) / (4.0 * VoH)", "pdf_half_vector(H, N)"), False),
    (("(ke + 1.0) * 0.5 * INV_PI", "(ke + 1.0) * 0.6 * INV_PI"), False),
]


def ibl_shape(message: str) -> str:
    """The words of a render check's message: its numbers and the group it names (the
    page's passes are other random draws than the grader's: iblcheck.js says why) blanked."""
    message = re.sub(r"(ring θ #–#°|whole sphere)", "GROUP", NUMBER.sub("#", message))
    return message.replace("+#", "#").replace("-#", "#")


@pytest.mark.parametrize("slip,passes", IBL_SLIPS, ids=["solution", "exponent", "jacobian", "pdf"])
def test_ibl_render_practice_gives_the_graders_verdict(page, tmp_path, slip, passes):
    text = (ROOT / "solutions" / SAMPLER / SAMPLER_FILE).read_text(encoding="utf-8")
    if slip:
        assert slip[0] in text
        text = text.replace(*slip)
    path = tmp_path / SAMPLER_FILE
    path.write_text(text, encoding="utf-8")
    graded = grade(SAMPLER, path, tmp_path)
    practice(page, SAMPLER, text)
    shown = dict(
        (name, (passed, message))
        for name, passed, message in page.evaluate(
            "brdfLab.exercises.runSampling()"
            ".then(rs => rs.map(r => [r.check.name, r.passed, r.message]))"
        )
    )
    passed, message = shown[IBL]
    assert passed == graded[IBL][0], (message, graded[IBL][1])
    theirs = unlocated(graded[IBL][1]).rstrip(".")  # (a trace alone leaves its '.')
    assert ibl_shape(message.rstrip(".")) == ibl_shape(theirs), (message, graded[IBL][1])
    assert passed == passes
    assert page.errors == []


def test_practice_results_are_accessible(page, output_dir):
    """axe finds no violation in the results of both kinds; a failed properties check's
    table is a labelled region the keyboard can scroll; the render pictures are named."""
    from axe import violations

    wrong = (ROOT / "tests/exercise_11/wrong/no_sine.glsl").read_text(encoding="utf-8")
    practice(page, PROPERTIES, wrong)
    region = page.locator('#exercise .exercise-table[data-check="lambert"] [role=region]')
    assert region.get_attribute("tabindex") == "0" and "grader's" in region.get_attribute(
        "aria-label"
    )
    cells = region.locator("tbody tr").first.locator("td").all_inner_texts()
    assert cells[0].startswith("directional_albedo") and cells[3] == "✗ differs", cells
    # What the grader checks besides and the page does not (scope.py) is said in words.
    note = page.locator("#exercise > p.practice-note").inner_text()
    assert note.startswith("Not checked here") and "PI, INV_PI, EPS, BRDF" in note, note
    assert violations(page) == []
    page.locator("#exercise").screenshot(path=output_dir / "web_practice_properties.png")
    practice(page, SAMPLER, (ROOT / "solutions" / SAMPLER / SAMPLER_FILE).read_text("utf-8"))
    page.locator("#exercise button.run-sampling").click()
    page.wait_for_function(
        "document.querySelectorAll('#exercise li.pending').length === 0", timeout=120_000
    )
    pictures = page.locator(f'#exercise .exercise-images[data-check="{IBL}"] canvas')
    assert pictures.count() == 4
    assert all(
        pictures.nth(i).get_attribute("role") == "img"
        and pictures.nth(i).get_attribute("aria-label")
        for i in range(4)
    )
    note = page.locator(f'#exercise .practice-note[data-check="{IBL}"]').inner_text()
    assert "other random numbers" in note and "brdf-lab grade decides" in note
    assert violations(page) == []
    page.locator("#exercise").screenshot(path=output_dir / "web_practice_ibl_render.png")


@pytest.mark.parametrize(
    "slip",
    [
        # a syntax error: every check names the file and line, as the grader
        (
            "return max(total.r, max(total.g, total.b));",
            "return max(total.r, max(total.g, total.b))",
        ),
        # the stand-in's include left out: the panel cannot compile the file alone, every
        # check links it (as the grader) and passes
        ("// @include terms/brdf_stand_in.glsl\n", ""),
    ],
    ids=["syntax", "no_include"],
)
def test_properties_compile_as_the_grader_links(page, tmp_path, slip):
    text = (ROOT / "solutions" / PROPERTIES / "properties.glsl").read_text(encoding="utf-8")
    assert slip[0] in text
    text = text.replace(*slip)
    path = tmp_path / "properties.glsl"
    path.write_text(text, encoding="utf-8")
    graded = grade(PROPERTIES, path, tmp_path)
    shown = practice(page, PROPERTIES, text)
    for name, (passed, message) in graded.items():
        assert shown[name][0] == passed, (name, shown[name][1], message)
        if not passed:
            where = re.search(r"properties\.glsl:(\d+):", message).group(0)
            assert f"the shader does not compile: {where}" in shown[name][1], shown[name][1]
        else:
            assert same_words(shown[name][1], message)
    assert page.errors == []


def test_ibl_render_names_a_stopped_loop_as_the_grader(page, tmp_path):
    """A sampler whose loop never ends: the loop guard stops it, and the check says where,
    in the grader's words (the first pixel of the render it stopped at)."""
    text = (ROOT / "solutions" / SAMPLER / SAMPLER_FILE).read_text(encoding="utf-8")
    first = "    vec3 H = sample_half_vector(u, N, X, Y);"
    assert first in text
    text = text.replace(
        first, "    float k = 0.0;\n    while (k >= 0.0) { k += 1.0; }\n" + first, 1
    )
    path = tmp_path / SAMPLER_FILE
    path.write_text(text, encoding="utf-8")
    graded = grade(SAMPLER, path, tmp_path)
    practice(page, SAMPLER, text)
    # Only this check (the others' 100,000 samples would each run the loop out too).
    page.evaluate(f"brdfLab.exercises.results.forEach(r => r.pending &&= r.check.name === '{IBL}')")
    shown = page.evaluate(
        "brdfLab.exercises.runSampling().then(rs => rs.find(r => r.check.name === "
        f"'{IBL}')).then(r => [r.passed, r.message])"
    )
    assert not graded[IBL][0] and "did not end within" in graded[IBL][1]
    assert shown == [False, graded[IBL][1].replace(str(path), SAMPLER_FILE)]
    assert page.errors == []


# Exercise 14 (an estimator exercise: the student's estimate is the IBL view's pass): its
# ibl_render checks in the page, driven by the checks' data (environment, turn, samples).
ESTIMATOR = "14_reflection_equation"
ESTIMATOR_FILES = [
    "solutions/14_reflection_equation/reflection_equation.glsl",
    "tests/exercise_14/wrong/no_pdf.glsl",
    "tests/exercise_14/wrong/no_mean.glsl",
    "tests/exercise_14/wrong/mirror_lookup.glsl",
]


@pytest.mark.parametrize("file", ESTIMATOR_FILES, ids=lambda f: Path(f).stem)
def test_estimator_renders_give_the_graders_verdicts(page, tmp_path, file):
    text = (ROOT / file).read_text(encoding="utf-8")
    path = tmp_path / "reflection_equation.glsl"
    path.write_text(text, encoding="utf-8")
    graded = grade(ESTIMATOR, path, tmp_path)
    practice(page, ESTIMATOR, text)
    shown = dict(
        (name, (passed, message))
        for name, passed, message in page.evaluate(
            "brdfLab.exercises.runSampling()"
            ".then(rs => rs.map(r => [r.check.name, r.passed, r.message]))"
        )
    )
    assert set(shown) == set(graded)
    for name, (passed, message) in graded.items():
        assert shown[name][0] == passed, (name, shown[name][1], message)
        mine = ibl_shape(shown[name][1].split(". Likely: ")[0].rstrip("."))
        assert mine == ibl_shape(unlocated(message).split(". Likely: ")[0].rstrip(".")), name
    assert all(p for p, _ in graded.values()) == file.startswith("solutions/")
    assert page.errors == []


# -- object: exercise 13's textured object (static/objectcheck.js) --------------------------
SVBRDF = "13_svbrdf"
SVBRDF_FILE = "svbrdf.glsl"
# Stored mistakes of solutions/13_svbrdf/mistakes.toml (by index): the anisotropy's axes
# swapped, the mask inverted, the textures read at (v, u).
SVBRDF_MISTAKES = [0, 1, 6]


def svbrdf_files() -> list[tuple[str, str]]:
    from lab.grading import mistakes
    from lab.grading.exercise import load_exercise

    exercise = load_exercise(ROOT / "exercises" / SVBRDF)
    solution = exercise.solution.read_text(encoding="utf-8")
    known = mistakes.known_mistakes(exercise)
    return [
        ("solution", solution),
        ("stub", (ROOT / "exercises" / SVBRDF / SVBRDF_FILE).read_text(encoding="utf-8")),
        *((known[i].key, known[i].apply(solution)) for i in SVBRDF_MISTAKES),
    ]


# A texture never read (no stored mistake): the grader names the sampler (ObjectKind.explain).
UNREAD_MASK = ("float mask = texture(mask_map, uv).r;", "float mask = 0.3;")


@pytest.mark.parametrize(
    "key", ["solution", "stub", *(f"mistake.{i}" for i in SVBRDF_MISTAKES), "unread_mask"]
)
def test_object_practice_gives_the_graders_verdicts(page, tmp_path, key):
    """The page draws the grader's object view with the check's textures and judges the
    image as the sphere kind: every check's verdict, words and likely mistake are the
    grader's."""
    files = dict(svbrdf_files())
    text = files.get(key) or files["solution"].replace(*UNREAD_MASK)
    path = tmp_path / SVBRDF_FILE
    path.write_text(text, encoding="utf-8")
    graded = grade(SVBRDF, path, tmp_path)
    shown = practice(page, SVBRDF, text)
    assert set(shown) == set(graded)
    assert page.evaluate("brdfLab.exercises.exercise.grader_only.length") == 0
    for name, (passed, message) in graded.items():
        assert shown[name][0] == passed, (name, shown[name][1], message)
        if not passed:  # the grader's words and likely mistake; its figures within 2 %
            # (SwiftShader's renders differ from llvmpipe's in a few edge pixels)
            assert same_words(shown[name][1], unlocated(message), 0.02), (name, shown[name][1])
    assert all(p for p, _ in graded.values()) == (key == "solution")
    assert page.errors == []


def test_object_practice_results_are_accessible(page, output_dir):
    """A failed object check shows the reference, the student's render and their difference
    as named images; axe finds no violation; pictures at the page's user sizes."""
    from axe import violations

    practice(page, SVBRDF, dict(svbrdf_files())["mistake.1"])
    pictures = page.locator('#exercise .exercise-images[data-check="torus.front"] canvas')
    assert pictures.count() == 3
    for i in range(3):
        assert pictures.nth(i).get_attribute("role") == "img"
        assert pictures.nth(i).get_attribute("aria-label")
    assert "Only brdf-lab grade" not in page.locator("#exercise").inner_text()
    assert violations(page) == []
    shown = page.locator('#exercise .exercise-images[data-check="torus.front"]')
    for width, height in [(1024, 768), (390, 844)]:
        page.set_viewport_size({"width": width, "height": height})
        shown.scroll_into_view_if_needed()
        page.screenshot(path=output_dir / f"web_practice_object_{width}.png")
    page.set_viewport_size({"width": 1300, "height": 900})
    assert page.errors == []


def test_object_practice_names_a_stopped_loop_as_the_grader(page, tmp_path):
    """An SVBRDF whose loop never ends: the loop guard stops it and every check says where,
    in the grader's words (the object's pixel)."""
    text = dict(svbrdf_files())["solution"]
    last = "    return mix(f_paint, f_metal, mask);"
    assert last in text
    text = text.replace(last, "    float k = 0.0;\n    while (k >= 0.0) { k += 1.0; }\n" + last)
    path = tmp_path / SVBRDF_FILE
    path.write_text(text, encoding="utf-8")
    graded = grade(SVBRDF, path, tmp_path)
    shown = practice(page, SVBRDF, text)
    for name, (passed, message) in graded.items():
        assert not passed and "did not end within" in message and "of the object" in message
        assert shown[name] == (False, message.replace(str(path), SVBRDF_FILE)), name
    assert page.errors == []


def test_sampled_check_names_a_stopped_loop_as_the_grader(page, tmp_path):
    """A sampler whose loop never ends for a few of its samples: the sampled checks name
    the line as the grader does (the sample differs: the page draws other numbers)."""
    text = (ROOT / "solutions" / SAMPLER / SAMPLER_FILE).read_text(encoding="utf-8")
    first = "    vec3 H = sample_half_vector(u, N, X, Y);"
    text = text.replace(
        first, "    float k = 0.0;\n    while (u.x < 0.001 && k >= 0.0) { k += 1.0; }\n" + first, 1
    )
    path = tmp_path / SAMPLER_FILE
    path.write_text(text, encoding="utf-8")
    graded = grade(SAMPLER, path, tmp_path)
    name = next(n for n in graded if n.startswith("chi_square"))
    practice(page, SAMPLER, text)
    only = f"r.check.name === '{name}'"
    page.evaluate(f"brdfLab.exercises.results.forEach(r => r.pending &&= {only})")
    shown = page.evaluate(
        f"brdfLab.exercises.runSampling().then(rs => rs.find(r => {only}))"
        ".then(r => [r.passed, r.message])"
    )
    said = graded[name][1].replace(str(path), SAMPLER_FILE)
    assert not graded[name][0] and "did not end within" in said
    sample = re.compile(r"at sample \d+")
    assert shown[0] is False and sample.sub("", shown[1]) == sample.sub("", said), (shown, said)
    assert page.errors == []

"""The grader's diagnoses: realistic wrong submissions get the right "Likely: ..." sentence,
equivalent rewrites get none, and every stored mistake gets its own hint back.

The corpus is written as a student would write the mistake, not copied from the stored
mistakes (solutions/NN/mistakes.toml), so a match shows that the values, not the text,
identify the mistake.
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest

from lab.grading import diagnosis, mistakes
from lab.grading.exercise import find_exercises
from lab.grading.explain import FINGERPRINT
from lab.grading.runner import Pool, Task

ROOT = Path(__file__).resolve().parent.parent
EXERCISES = {e.name: e for e in find_exercises(ROOT / "exercises")}
GOAL = 0.8

# (exercise, label, [(text in the solution, the student's text)], words the diagnosis names)
CORPUS = [
    ("02_phong", "no 1/pi", [("kd * INV_PI + ks", "kd + ks")], "1/π"),
    ("02_phong", "reflect(L, N)", [("2.0 * NoL * N - L", "reflect(L, N)")], "reflect"),
    ("02_phong", "unclamped R.V", [("max(dot(R, V), 0.0)", "dot(V, R)")], "not clamped"),
    (
        "02_phong",
        "cosine inside",
        [("kd * INV_PI + ks * pow(RoV, ke)", "kd * INV_PI * NoL + ks * pow(RoV, ke) * NoL")],
        "multiplied by N·L",
    ),
    (
        "02_phong",
        "no horizon test",
        [("if (NoL <= 0.0 || NoV <= 0.0) return vec3(0.0);", "// no test")],
        "below the surface",
    ),
    ("02_phong", "extra 1/pi on ks", [("ks * pow(RoV, ke)", "ks * pow(RoV, ke) / PI")], "1/π"),
    ("02_phong", "exponent scaled", [("pow(RoV, ke)", "pow(RoV, 0.2 * ke)")], "exponent of about"),
    ("03_blinn_phong", "exponent scaled", [("pow(NoH, ke)", "pow(NoH, 4.0 * ke)")], "about 160"),
    ("03_blinn_phong", "H not normalised", [("normalize(L + V)", "L + V")], "not normalised"),
    ("03_blinn_phong", "no 1/pi", [("kd * INV_PI", "kd")], "1/π"),
    ("03_blinn_phong", "V.H", [("dot(N, H)", "dot(H, V)")], "V·H"),
    ("03_blinn_phong", "cosine inside", [("+ ks * pow(NoH, ke)", "+ ks * pow(NoH, ke) * NoL")], ""),
    (
        "03_blinn_phong",
        "Phong instead",
        [("max(dot(N, H), 0.0)", "max(dot(reflect(-L, N), V), 0.0)")],
        "Phong",
    ),
    ("04_phong_illumination", "no ambient", [("ka * ambient", "vec3(0.0)")], "ambient"),
    (
        "04_phong_illumination",
        "first light only",
        [
            (
                "for (int l = 0; l < 8; ++l) {\n        if",
                "for (int l = 0; l < 1; ++l) {\n        if",
            )
        ],
        "first light",
    ),
    ("04_phong_illumination", "no N.L", [("kd * NoL + ks", "kd + ks")], "N·L"),
    (
        "04_phong_illumination",
        "count ignored",
        [
            (
                "for (int l = 0; l < 8; ++l) {\n        if (l >= count) break;",
                "for (int l = 0; l < 8; ++l) {",
            )
        ],
        "all 8 slots",
    ),
    ("04_phong_illumination", "no light colour", [("light_rgb[l] * (", "(")], "colour"),
    (
        "04_phong_illumination",
        "ambient with kd",
        [("vec3 color = ka * ambient;", "vec3 color = ambient * kd;")],
        "ka, not kd",
    ),
    (
        "05_ward",
        "axes swapped",
        [
            ("dot(H, X) / alpha_x", "dot(H, Y) / alpha_x"),
            ("dot(H, Y) / alpha_y", "dot(H, X) / alpha_y"),
        ],
        "swapped",
    ),
    ("05_ward", "no sqrt", [("sqrt(NoL * NoV)", "NoL * NoV")], "√(N·L N·V)"),
    ("05_ward", "no 4", [("4.0 * PI * alpha_x", "PI * alpha_x")], "4"),
    ("05_ward", "no 1/pi", [("kd * INV_PI", "kd")], "1/π"),
    ("05_ward", "no 1/cos^2", [(" / (NoH * NoH)", "")], "(N·H)²"),
    (
        "06_microfacet_distributions",
        "pi m^2 cos^4",
        [("4.0 * m2 * c2 * c2", "PI * m2 * pow(NoH, 4.0)")],
        "1/(π m² cos⁴θh)",
    ),
    ("06_microfacet_distributions", "cos^2", [("(4.0 * m2 * c2 * c2)", "(4.0 * m2 * c2)")], "cos⁴"),
    (
        "06_microfacet_distributions",
        "degrees",
        [("cos(beta)", "cos(beta * PI / 180.0)")],
        "radians",
    ),
    (
        "06_microfacet_distributions",
        "Blinn unnormalised",
        [("(e + 2.0) / 8.0 * pow(max(NoH, 0.0), e)", "pow(max(NoH, 0.0), e)")],
        "normaliser",
    ),
    ("06_microfacet_distributions", "alpha = N.H", [("angle_from_cos(NoH)", "NoH")], "acos"),
    ("07_geometric_attenuation", "no min 1", [("min(1.0, min(", "(min(")], "min(1.0"),
    (
        "07_geometric_attenuation",
        "masking only",
        [("min(g * NoV, g * NoL)", "NoV * g")],
        "shadowing",
    ),
    (
        "07_geometric_attenuation",
        "fraction upside down",
        [("2.0 * NoH / max(VoH, EPS)", "2.0 * VoH / max(NoH, EPS)")],
        "swapped",
    ),
    (
        "07_geometric_attenuation",
        "max",
        [("min(g * NoV, g * NoL)", "max(g * NoL, g * NoV)")],
        "min",
    ),
    ("07_geometric_attenuation", "no 2", [("2.0 * NoH", "NoH")], "2"),
    ("08_fresnel", "fourth power", [("(k2 * k2 * k)", "pow(k, 4.0)")], "fourth power"),
    ("08_fresnel", "no 1 minus", [("1.0 - clamp(VoH, 0.0, 1.0)", "clamp(VoH, 0.0, 1.0)")], "1 −"),
    ("08_fresnel", "no 1/2", [("return 0.5 * a * a", "return a * a")], "1/2"),
    ("08_fresnel", "n not squared", [("ior * ior - 1.0", "ior - 1.0")], "squared"),
    (
        "08_fresnel",
        "grey f0",
        [
            (
                "return f0 + (vec3(1.0) - f0) * (k2 * k2 * k);",
                "return vec3(f0.x + (1.0 - f0.x) * pow(k, 5.0));",
            )
        ],
        "colour",
    ),
    ("09_cook_torrance", "F(N.L)", [("fresnel_F(VoH)", "fresnel_F(NoL)")], "V·H"),
    (
        "09_cook_torrance",
        "no denominator",
        [("(D * G / (PI * NoL * NoV))", "D * G / PI")],
        "denominator",
    ),
    (
        "09_cook_torrance",
        "no G",
        [("(D * G / (PI * NoL * NoV))", "(D / (PI * NoL * NoV))")],
        "G is missing",
    ),
    ("09_cook_torrance", "4 N.L N.V", [("PI * NoL * NoV", "4.0 * NoL * NoV")], "4·N·L·N·V"),
    ("09_cook_torrance", "no 1/pi", [("kd * INV_PI", "kd")], "1/π"),
    (
        "10_importance_sampling",
        "no Jacobian",
        [
            (
                "if (VoH <= 0.0) return 0.0;\n    return pdf_half_vector(H, N) / (4.0 * VoH);",
                "return VoH > 0.0 ? pdf_half_vector(H, N) : 0.0;",
            )
        ],
        "Jacobian",
    ),
    ("10_importance_sampling", "exponent", [("1.0 / (ke + 1.0)", "1.0 / (2.0 + ke)")], "exponent"),
    (
        "10_importance_sampling",
        "no sqrt",
        [("sqrt(max(1.0 - cos_t * cos_t, 0.0))", "max(1.0 - cos_t * cos_t, 0.0)")],
        "square root",
    ),
    (
        "10_importance_sampling",
        "local frame",
        [("return h.x * X + h.y * Y + h.z * N;", "return vec3(h.x, h.y, h.z);")],
        "local frame",
    ),
    (
        "10_importance_sampling",
        "reflect sign",
        [("return reflect(-V, H);", "return V - 2.0 * dot(V, H) * H;")],
        "reflect",
    ),
    ("10_importance_sampling", "half circle", [("2.0 * PI * u.y", "u.y * PI")], "whole circle"),
    # not in any mistake list: only the shape of the error can tell
    ("02_phong", "exponent doubled", [("pow(RoV, ke)", "pow(RoV, 2.0 * ke)")], "exponent of about"),
    ("03_blinn_phong", "pi on ks", [("ks * pow(NoH, ke)", "PI * ks * pow(NoH, ke)")], "π times"),
    ("05_ward", "extra N.V", [("ks * spec", "ks * spec * NoV")], "cos θo"),
    ("02_phong", "abs(R.V)", [("max(dot(R, V), 0.0)", "abs(dot(R, V))")], "solution clamps"),
    ("06_microfacet_distributions", "m 1.5x", [("m2 = m * m", "m2 = 2.25 * m * m")], "m of about"),
    (
        "07_geometric_attenuation",
        "N.H for V.H",
        [("2.0 * NoH / max(VoH, EPS)", "2.0 * NoH / max(NoH, EPS)")],
        "N·H where V·H belongs",
    ),
    (
        "06_microfacet_distributions",
        "alpha in degrees",
        [("float alpha = angle_from_cos(NoH);", "float alpha = degrees(acos(NoH));")],
        "57 times",
    ),
]

# Rewrites that are correct: they must pass and get no diagnosis at all.
EQUIVALENT = [
    ("02_phong", [("2.0 * NoL * N - L", "reflect(-L, N)"), ("kd * INV_PI", "kd / PI")]),
    ("03_blinn_phong", [("max(dot(N, H), 0.0)", "clamp(dot(H, N), 0.0, 1.0)")]),
    ("05_ward", [("sqr(dot(H, X) / alpha_x)", "dot(H, X) * dot(H, X) / (alpha_x * alpha_x)")]),
    ("06_microfacet_distributions", [("angle_from_cos(NoH)", "acos(clamp(NoH, -1.0, 1.0))")]),
    (
        "07_geometric_attenuation",
        [("min(1.0, min(g * NoV, g * NoL))", "min(1.0, g * min(NoV, NoL))")],
    ),
    ("08_fresnel", [("(k2 * k2 * k)", "pow(k, 5.0)")]),
    ("09_cook_torrance", [("kd * INV_PI", "kd / PI")]),
    (
        "10_importance_sampling",
        [("return h.x * X + h.y * Y + h.z * N;", "return to_world(h, X, Y, N);")],
    ),
]


def write(tmp: Path, name: str, label: str, edits) -> Path:
    exercise = EXERCISES[name]
    text = exercise.solution.read_text(encoding="utf-8")
    for old, new in edits:
        at = text.rfind(old)  # the code, not the header's formula
        assert at >= 0, f"{name}: {old!r} is not in the solution"
        text = text[:at] + new + text[at + len(old) :]
    path = tmp / f"{name}-{label.replace(' ', '_').replace('/', '_')}" / exercise.student_file
    path.parent.mkdir(parents=True)
    path.write_text(text, encoding="utf-8")
    return path


@pytest.fixture(scope="module")
def graded(tmp_path_factory) -> dict[tuple, Task]:
    tmp = tmp_path_factory.mktemp("corpus")
    tasks = {}
    for name, label, edits, _ in CORPUS:
        tasks["corpus", name, label] = Task(EXERCISES[name], write(tmp, name, label, edits))
    for number, (name, edits) in enumerate(EQUIVALENT):
        tasks["equivalent", name, number] = Task(
            EXERCISES[name], write(tmp, name, f"eq{number}", edits)
        )
    for exercise in EXERCISES.values():
        solution = exercise.solution.read_text(encoding="utf-8")
        for variant in mistakes.known_mistakes(exercise):
            path = tmp / f"{exercise.name}-{variant.key}" / exercise.student_file
            path.parent.mkdir(parents=True)
            path.write_text(variant.apply(solution), encoding="utf-8")
            tasks["stored", exercise.name, variant.key] = Task(exercise, path)
    with Pool(2, timeout=20.0) as pool:
        pool.run(list(tasks.values()))
    return tasks


def diagnoses(task: Task) -> list[str]:
    return [r.diagnosis for r in task.checks() if r.diagnosis]


def test_corpus_has_five_wrong_submissions_per_exercise():
    for number in range(2, 10):
        name = next(n for n in EXERCISES if n.startswith(f"0{number}_"))
        assert sum(1 for c in CORPUS if c[0] == name) >= 5, name


def test_share_of_the_corpus_diagnosed_correctly(graded):
    right, report = 0, []
    for name, label, _, words in CORPUS:
        task = graded["corpus", name, label]
        assert task.score < task.max_score, f"{name} '{label}' got full marks"
        said = diagnoses(task)
        ok = bool(said) and any(words in d for d in said)
        right += ok
        report.append(f"{'ok ' if ok else 'MISS'} {name} {label}: {said[:1]}")
    share = right / len(CORPUS)
    print(f"\ndiagnosed correctly: {right} of {len(CORPUS)} ({100 * share:.0f}%)")
    print("\n".join(report))
    assert share >= GOAL, "\n".join(report)


def test_edits_that_behave_alike_are_both_named(graded):
    """2 N·H / N·H and 2 V·H / V·H give the same G: the hint names both possible edits."""
    said = diagnoses(graded["corpus", "07_geometric_attenuation", "N.H for V.H"])
    assert said and all("N·H where V·H belongs" in d and "V·H where N·H belongs" in d for d in said)
    said = diagnoses(graded["corpus", "06_microfacet_distributions", "alpha in degrees"])
    assert said and all("57 times" in d for d in said), said


def test_equivalent_rewrites_pass_without_a_diagnosis(graded):
    for name, number in [(k[1], k[2]) for k in graded if k[0] == "equivalent"]:
        task = graded["equivalent", name, number]
        assert task.score == task.max_score, [r.message for r in task.checks() if not r.passed]
        assert not diagnoses(task)


def test_every_stored_mistake_gets_its_own_hint(graded):
    for key in [k for k in graded if k[0] == "stored"]:
        task = graded[key]
        hint = mistakes.read_hints(task.exercise).get(key[2])
        assert hint, f"{key}: no stored values (equivalent to the solution?)"
        assert task.score < task.max_score
        said = [d.split(" Where: ")[0] for d in diagnoses(task)]  # and where, if traced
        assert diagnosis.sentence(hint) in said, (key, diagnoses(task))


# -- the shape analysis alone, on made-up values --------------------------------------------
def test_cook_torrance_sphere_fails_for_the_classic_mistakes(graded):
    """09's sphere check alone catches F(N·L), the missing denominator and the missing G."""
    for label in ("F(N.L)", "no denominator", "no G"):
        task = graded["corpus", "09_cook_torrance", label]
        sphere = task.results["sphere.default"]
        assert not sphere.passed and sphere.diagnosis, (label, sphere.message)


# -- the HTML report of three typical mistakes, looked at in Chromium -----------------------
SHOTS = [
    ("02_phong", "no 1/pi"),
    ("05_ward", "axes swapped"),
    ("09_cook_torrance", "F(N.L)"),
]


def test_report_screenshots_of_three_typical_mistakes(graded, output_dir, tmp_path):
    from lab.grading.report import html_report
    from lab.web.browser import chromium

    with chromium() as browser:
        for name, label in SHOTS:
            task = graded["corpus", name, label]
            page_html = html_report([task], f"Grading report: {name}, {label}")
            hint = next(r.diagnosis for r in task.checks() if r.diagnosis)
            assert hint in page_html  # the same sentence as the terminal and the JSON
            assert "too bright" in page_html and "failing pixels" in page_html
            if any(r.curve for r in task.checks()):
                assert "rings at" in page_html and "failing directions" in page_html
            path = tmp_path / f"{name}.html"
            path.write_text(page_html, encoding="utf-8")
            stem = "report_" + re.sub(r"\W+", "_", f"{name} {label}").strip("_")
            for width, height, suffix in ((1024, 768, ""), (390, 844, "_phone")):
                page = browser.new_page(viewport={"width": width, "height": height})
                page.goto(path.as_uri())
                # nothing runs off the side of the page: no clipped plot, no wide text
                assert page.evaluate("document.documentElement.scrollWidth") <= width
                page.screenshot(path=output_dir / f"{stem}{suffix}.png", full_page=True)
                page.close()


# -- the same sentence everywhere, hidden mode, and messages that do not mislead ------------
def test_same_sentence_in_terminal_gradescope_and_classroom(graded):
    import io

    from rich.console import Console

    from lab.grading import report

    task = graded["corpus", "02_phong", "no 1/pi"]
    hint = task.results["probe.sharp"].diagnosis
    assert hint.startswith("Likely: ") and "1/π" in hint
    buffer = io.StringIO()
    report.terminal([task], Console(file=buffer, width=400, highlight=False, soft_wrap=True))
    assert hint in buffer.getvalue()
    outputs = [t["output"] for t in report.gradescope([task], 1.0)["tests"]]
    messages = [t["message"] for t in report.classroom([task])["tests"]]
    assert any(hint in o for o in outputs) and any(hint in m for m in messages)
    assert hint in report.html_report([task])


def test_hidden_mode_renders_the_mistakes_live(graded, tmp_path):
    exercise = EXERCISES["09_cook_torrance"]
    path = write(tmp_path, "09_cook_torrance", "hidden", [("fresnel_F(VoH)", "fresnel_F(NoL)")])
    task = Task(exercise, path, seed=11)
    with Pool(1, timeout=20.0) as pool:
        pool.run([task])
    failed = [r for r in task.checks() if not r.passed]
    assert failed and all(r.setting and r.setting["seed"] == 11 for r in task.checks())
    assert any("V·H" in r.diagnosis for r in failed), [r.message for r in failed]


def grade_text(tmp_path: Path, name: str, text: str) -> Task:
    exercise = EXERCISES[name]
    path = tmp_path / exercise.student_file
    path.write_bytes(text.encode("utf-8"))
    task = Task(exercise, path)
    with Pool(1, timeout=20.0) as pool:
        pool.run([task])
    return task


def test_bom_helper_names_and_header_edits(tmp_path):
    exercise = EXERCISES["02_phong"]
    solution = exercise.solution.read_text(encoding="utf-8")
    assert grade_text(tmp_path, "02_phong", "\ufeff" + solution).passed  # a byte-order mark
    helper = "vec3 from_angles(float t, float p) { return vec3(t, p, 0.0); }\nvec3 BRDF("
    task = grade_text(tmp_path, "02_phong", solution.replace("vec3 BRDF(", helper, 1))
    assert task.passed, [r.message for r in task.checks()]  # no clash with the harness
    line = "// @param ke float 1 1000 50 log"
    assert line in solution
    task = grade_text(tmp_path, "02_phong", solution.replace(line, "// @param ke color 1 1 1"))
    message = task.checks()[0].message
    assert "you changed the type of ke from float to color" in message, message
    assert "phong.glsl:7:" in message
    default = solution.replace("// @param ke float 1 1000 50", "// @param ke float 1 1000 9")
    assert grade_text(tmp_path, "02_phong", default).passed  # the stub's defaults count


def test_no_loop_note_unless_the_loop_guard_stopped_one(graded):
    """06's solution loops (Simpson's rule); its wrong submissions are not about the loop."""
    for key in [k for k in graded if k[1] == "06_microfacet_distributions"]:
        for result in graded[key].checks():
            assert "loop" not in result.message, result.message


def test_stored_variants_fit_the_references():
    """diagnosis.npz was made with the same checks as the references (else re-make both)."""
    from lab.grading.checks import VALUES_FILE, read_png

    for exercise in EXERCISES.values():
        hints = mistakes.read_hints(exercise)
        with np.load(exercise.references / VALUES_FILE) as refs:
            shapes = {k: refs[k].shape for k in refs.files}
        for check in exercise.checks:
            if check.kind in ("sphere", "object"):  # image references
                shapes[check.name] = read_png(exercise.references / f"{check.name}.png").shape
        with np.load(exercise.references / mistakes.VALUES) as data:
            for key in data.files:
                check, variant = key.split("|")
                if check == FINGERPRINT:  # a sampler's, at its first check's settings
                    assert variant == "solution" or variant in hints, (exercise.name, key)
                    assert data[key].shape == data[f"{FINGERPRINT}|solution"].shape
                    continue
                assert data[key].shape == shapes[check], (exercise.name, key)
                assert variant.startswith("term.") or variant in hints, (exercise.name, key)
        if exercise.name >= "02":
            assert sum(k.startswith("mistake.") for k in hints) >= 5, exercise.name

"""Diagnoses beyond the corpus: 09's D, G and F seen alone through the student's code,
generated mutants named live in hidden mode, and header lines whose default or range a
student changed."""

from __future__ import annotations

from pathlib import Path

import pytest

from lab.grading import mistakes
from lab.grading.exercise import find_exercises
from lab.grading.runner import Pool, Task

ROOT = Path(__file__).resolve().parent.parent
EXERCISES = {e.name: e for e in find_exercises(ROOT / "exercises")}


def grade(tmp_path: Path, name: str, edits: list[tuple[str, str]], seed: int | None = None):
    exercise = EXERCISES[name]
    text = exercise.solution.read_text(encoding="utf-8")
    for old, new in edits:
        assert old in text, old
        text = text.replace(old, new, 1)
    path = tmp_path / exercise.student_file
    path.write_text(text, encoding="utf-8")
    task = Task(exercise, path, seed=seed)
    with Pool(1, timeout=30.0) as pool:
        pool.run([task])
    return task


def diagnoses(task) -> list[str]:
    return [r.diagnosis for r in task.checks() if not r.passed]


@pytest.mark.parametrize("seed", [None, 5], ids=["stored", "hidden"])
@pytest.mark.parametrize(
    ("edit", "wrong", "right"),
    [
        # F of V·H squared: no stored mistake or mutant is like it; F alone is wrong.
        (("fresnel_F(VoH)", "fresnel_F(VoH * VoH)"), "the F term is wrong", "D and G"),
        # G of a wrong N·H: G alone is wrong, D and F are right.
        (
            (
                "float G = G_vgroove(NoL, NoV, NoH, VoH);",
                "float G = G_vgroove(NoL, NoV, NoH * NoH, VoH);",
            ),
            "the G term is wrong",
            "D and F",
        ),
        # D of a sharper roughness: D alone is wrong.
        (
            ("return D_beckmann(NoH, m);", "return D_beckmann(NoH, 0.5 * m);"),
            "the D term is wrong",
            "G and F",
        ),
    ],
    ids=["F", "G", "D"],
)
def test_cook_torrance_names_the_wrong_factor(tmp_path, seed, edit, wrong, right):
    said = diagnoses(grade(tmp_path, "09_cook_torrance", [edit], seed))
    assert said and any(wrong in d and right in d for d in said), said
    assert not any("specular term is wrong" in d for d in said), said


def test_a_shared_factor_is_the_specular_term(tmp_path):
    """All of D, G and F alone are wrong when what they share is (here the denominator):
    the specular term is named, not its three factors."""
    edit = ("(D * G / (PI * NoL * NoV))", "(D * G / (PI * NoL * NoV * NoV))")
    said = diagnoses(grade(tmp_path, "09_cook_torrance", [edit]))
    assert any("the specular term is wrong" in d for d in said), said
    assert not any("F term" in d or "D term" in d for d in said), said


def test_inlined_terms_are_not_judged(tmp_path):
    """A student who writes G inline: the macros cannot isolate D, G or F in that code, so
    no factor is named (the diffuse/specular split still is)."""
    inline = "float G = min(1.0, min(2.0 * NoH * NoV / VoH, 2.0 * NoH * NoL / VoH));"
    edits = [
        ("float G = G_vgroove(NoL, NoV, NoH, VoH);", inline),
        ("fresnel_F(VoH)", "fresnel_F(VoH * VoH)"),
    ]
    said = diagnoses(grade(tmp_path, "09_cook_torrance", edits))
    assert said and not any(t in d for d in said for t in ("D term", "G term", "F term")), said


def test_hidden_mode_names_generated_mutants(tmp_path):
    """In hidden mode the single-edit mutants the references kept are rendered live, and a
    submission that is one of them gets its hint."""
    exercise = EXERCISES["02_phong"]
    kept = mistakes.read_hints(exercise)
    solution = exercise.solution.read_text(encoding="utf-8")
    # (a mutant of the early exit's test is named by the trace as that exit, not by its hint)
    found = [
        v
        for v in mistakes.mutants(solution)
        if v.key in kept and not any("return vec3(0.0)" in old for old, _ in v.edits)
    ]
    assert found, "02 keeps no generated mutant"
    variant = found[0]
    said = diagnoses(grade(tmp_path, "02_phong", list(variant.edits), seed=7))
    assert any(kept[variant.key] in d for d in said), (variant.key, said)


def test_header_default_and_range_edits_are_named(tmp_path):
    line = "// @param ke float 1 1000 50 log"
    task = grade(tmp_path, "02_phong", [(line, "// @param ke float 1 100 8 linear")])
    assert task.passed, [r.message for r in task.checks()]  # the stub's line counts
    notes = [w for r in task.checks() for w in r.warnings]
    text = "\n".join(notes)
    assert "you changed the default of ke from 50 to 8" in text, notes
    assert "you changed the range of ke from [1, 1000] to [1, 100]" in text, notes
    assert "slider scale of ke from log to linear" in text, notes
    assert "phong.glsl:" in text and line in text
    plain = grade(tmp_path, "02_phong", [])
    assert not [w for r in plain.checks() for w in r.warnings if "header" in w]


@pytest.mark.parametrize(
    ("model", "true", "wrong"),
    [("phong", 50.0, 10.0), ("blinn_phong", 50.0, 12.0), ("phong", 50.0, 200.0)],
)
def test_lobe_width_names_the_fitted_exponent(model, true, wrong):
    """A lobe of the wrong width names the exponent whose lobe (lab.reference) is as wide:
    Blinn-Phong's too, whose width in θo is not Phong's for the same exponent."""
    import numpy as np

    from lab import reference
    from lab.constants import LUMA
    from lab.grading import diagnosis
    from lab.grading.spec import Check

    theta = np.arange(-88.0, 88.5, 1.0)
    rows = np.stack(
        [np.full_like(theta, 30.0), np.zeros_like(theta), np.abs(theta), (theta >= 0) * 180.0],
        axis=1,
    )
    check = Check(name="polar.x", kind="polar", points=1, theta_i=30.0, params={"ke": true})
    lobe = {
        k: reference.brdf_angles(model, {"ke": k}, rows) @ np.array(LUMA) for k in (true, wrong)
    }
    text = diagnosis.lobe(check, theta, lobe[true], lobe[wrong], check.params, model)
    fitted = float(text.split("exponent of about ")[1].split()[0])
    assert abs(fitted / wrong - 1.0) < 0.1, text
    assert f"instead of {true:g}" in text and ("wide" in text)


def test_a_rougher_lobe_is_named_by_its_roughness_not_its_peak():
    """Cook-Torrance's off-specular peak moves with the roughness: a rougher lobe peaking
    later is named by the fitted m, not as a wrong reflected direction; a lobe that only
    rises toward grazing (f_r's 1/N·V) gets no width at all."""
    import numpy as np

    from lab import reference
    from lab.constants import LUMA
    from lab.grading import diagnosis
    from lab.grading.spec import Check

    theta = np.arange(-88.0, 88.5, 1.0)

    def lobe(theta_i: float, m: float) -> np.ndarray:
        rows = np.stack(
            [np.full_like(theta, theta_i), 0 * theta, np.abs(theta), (theta >= 0) * 180.0], 1
        )
        return reference.brdf_angles("cook_torrance", {"m": m}, rows) @ np.array(LUMA)

    check = Check(name="polar.x", kind="polar", points=1, theta_i=30.0, params={"m": 0.2})
    text = diagnosis.lobe(
        check, theta, lobe(30.0, 0.2), lobe(30.0, 0.3), {"m": 0.2}, "cook_torrance"
    )
    assert "roughness m of about 0.29 instead of 0.2" in text, text
    assert "reflected direction" not in text
    grazing = Check(name="polar.y", kind="polar", points=1, theta_i=60.0, params={"m": 0.3})
    assert not diagnosis.lobe(
        grazing, theta, lobe(60.0, 0.3), lobe(60.0, 0.15), {}, "cook_torrance"
    )

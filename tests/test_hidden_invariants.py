"""Hidden mode's invariants, for every BRDF exercise (01-09) and SEEDS random settings, and
in reference mode: the untouched stub scores 0, the solution full marks, and so does every
correct rewrite kept with the exercise (solutions/NN/correct/*.glsl). Exercise 04's
multi-light slips lose points at every setting.

Kept cheap for CI: one grader (one OpenGL context) for the whole file and no diagnosis;
per setting and check the solution is rendered once and every program is compared with
it, as Grader.run would (hidden mode's reference is the solution rendered live, so the
solution itself is graded against the committed references, in reference mode).
"""

from __future__ import annotations

from pathlib import Path

import pytest

from lab.grading.checks import Grader, Submission, hidden_variant, prepare
from lab.grading.exercise import Exercise, find_exercises, load_exercise

ROOT = Path(__file__).resolve().parents[1]
SEEDS = 50
BRDF_EXERCISES = {f"0{n}" for n in range(1, 10)}  # 10 (sampling) has its own statistics
EXERCISES = [e for e in find_exercises(ROOT / "exercises") if e.name[:2] in BRDF_EXERCISES]

# Exercise 04's slips with several lights: (what, [(text in the solution, replacement)]).
WRONG_04 = {
    "the specular term of a light below the surface": [
        ("        if (NoL <= 0.0) continue;\n", ""),
        ("kd * NoL", "kd * max(NoL, 0.0)"),
    ],
    "the ambient term once per light": [
        ("vec3 color = ka * ambient;", "vec3 color = vec3(0.0);"),
        ("if (l >= count) break;", "if (l >= count) break;\n        color += ka * ambient;"),
    ],
    "<= count": [("if (l >= count) break;", "if (l > count) break;")],
    "the light's colour on the diffuse term only": [
        (
            "color += light_rgb[l] * (kd * NoL + ks * pow(RoV, ke));",
            "color += light_rgb[l] * kd * NoL + ks * pow(RoV, ke);",
        )
    ],
    "= for +=": [("color += light_rgb[l]", "color = light_rgb[l]")],
}


@pytest.fixture(scope="module")
def grader() -> Grader:
    return Grader()  # no explainer: the diagnosis is not what is tested here


def scores(
    grader: Grader, exercise: Exercise, programs: dict[str, Submission], seed: int | None
) -> dict[str, tuple[float, list[str]]]:
    """Each program's score at one setting (None: reference mode) and its failed checks."""
    out: dict[str, tuple[float, list[str]]] = {name: (0.0, []) for name in programs}
    solution = grader.solution_model(exercise)
    for index, check in enumerate(exercise.checks):
        live = seed is not None
        drawn = hidden_variant(check, solution, seed, index) if live else check
        expected = grader.expected(exercise, drawn, live=live)
        for name, ready in programs.items():
            result = grader.grade(exercise, drawn, ready.model, ready.code, expected, live)
            points, failed = out[name]
            out[name] = (points + result.points, failed + ([] if result.passed else [check.name]))
    return out


def prepared(exercise: Exercise, paths: dict[str, Path]) -> dict[str, Submission]:
    out = {}
    for name, path in paths.items():
        ready = prepare(exercise, path)
        assert not ready.error, f"{name}: {ready.error}"
        out[name] = ready
    return out


def correct_variants(exercise: Exercise) -> dict[str, Path]:
    folder = exercise.solution.parent / "correct"
    return {f"correct/{p.name}": p for p in sorted(folder.glob("*.glsl"))}


@pytest.mark.parametrize("exercise", EXERCISES, ids=lambda e: e.name)
def test_stub_zero_solution_and_rewrites_full(grader: Grader, exercise: Exercise) -> None:
    variants = correct_variants(exercise)
    assert len(variants) >= 2, f"{exercise.name}: keep 2-3 correct rewrites in correct/"
    right = {"solution": exercise.solution, **variants}
    programs = prepared(exercise, {"stub": exercise.stub, **right})
    wrong = []
    for seed in [None, *range(SEEDS)]:
        # Hidden mode grades against the solution rendered live: it is full by construction.
        graded = {k: v for k, v in programs.items() if seed is None or k != "solution"}
        for name, (points, failed) in scores(grader, exercise, graded, seed).items():
            if name == "stub" and points > 0:
                passed = [c.name for c in exercise.checks if c.name not in failed]
                wrong.append(f"seed {seed}: the stub scores {points:g} (passes {passed})")
            elif name != "stub" and failed:
                wrong.append(f"seed {seed}: {name} fails {failed}")
    assert not wrong, f"{exercise.name}:\n" + "\n".join(wrong)


def test_multi_light_slips_lose_points(grader: Grader, tmp_path: Path) -> None:
    exercise = load_exercise(ROOT / "exercises" / "04_phong_illumination")
    solution = exercise.solution.read_text(encoding="utf-8")
    paths = {}
    for number, (what, edits) in enumerate(WRONG_04.items()):
        text = solution
        for old, new in edits:
            assert old in text, f"{what}: {old!r} is no longer in the solution"
            text = text.replace(old, new)
        path = tmp_path / str(number) / exercise.student_file
        path.parent.mkdir()
        path.write_text(text, encoding="utf-8")
        paths[what] = path
    programs = prepared(exercise, paths)
    full = []
    for seed in [None, *range(SEEDS)]:
        for what, (points, _) in scores(grader, exercise, programs, seed).items():
            if points >= exercise.max_points:
                full.append(f"seed {seed}: {what} scores full marks")
    assert not full, "\n".join(full)


def test_purposes_and_ranges_fit_each_model(grader: Grader) -> None:
    """Every declared range lies within its parameter's header range and every drawn light
    lies in its check's class: a broken exercise.toml fails here, not in a student's grade."""
    from lab.grading.kinds import kind_of
    from lab.grading.spec import PURPOSES, infer_purpose

    for exercise in find_exercises(ROOT / "exercises"):
        if not exercise.solution.is_file():
            continue
        solution = grader.solution_model(exercise)
        for index, check in enumerate(exercise.checks):
            drawn = hidden_variant(check, solution, 7, index)
            if kind_of(check).purpose_of != "lights":
                continue
            classes = check.purpose or tuple(infer_purpose(lt.theta) for lt in check.lights)
            for light, purpose in zip(drawn.lights, classes, strict=True):
                low, high = PURPOSES[purpose]
                assert low <= light.theta <= high, (exercise.name, check.name, purpose)
            for name, (low, high) in check.ranges.items():
                value = drawn.params[name]
                for v in value if isinstance(value, tuple) else (value,):
                    assert low <= v <= high, (exercise.name, check.name, name, v)


def test_same_keeps_a_group_of_parameters_equal(grader: Grader) -> None:
    """`same` (exercise 05's isotropic probe): hidden mode draws one value for the group,
    on every seed, while the other parameters still vary; a misspelled name stops."""
    from dataclasses import replace

    from lab.grading.spec import ExerciseError

    exercise = next(e for e in EXERCISES if e.name.startswith("05"))
    solution = grader.solution_model(exercise)
    index, check = next((i, c) for i, c in enumerate(exercise.checks) if c.same)
    drawn = [hidden_variant(check, solution, seed, index).params for seed in range(SEEDS)]
    assert all(p["alpha_x"] == p["alpha_y"] for p in drawn)
    assert len({p["alpha_x"] for p in drawn}) == SEEDS  # still drawn anew each seed
    with pytest.raises(ExerciseError, match="alpha_z"):
        hidden_variant(replace(check, same=(("alpha_x", "alpha_z"),)), solution, 1, index)

"""Only the handout's API is in scope (lab/grading/scope.py): a submission that names the
lab's library outside its exercise's `api`, writes into the harness's namespace or clashes
with a library name is refused before rendering, with its line and what to do; the
exercises' own files, and names a student declares, are never refused."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from lab.grading.exercise import SubmissionError, build_model, find_exercises, load_exercise
from lab.grading.scope import exercise_names, read_code

ROOT = Path(__file__).resolve().parent.parent
EXERCISES = find_exercises(ROOT / "exercises")
SAMPLING = load_exercise(ROOT / "exercises" / "10_importance_sampling")
LAMBERT = load_exercise(ROOT / "exercises" / "01_lambert")

# Exercise 10 from the library's own pieces: 10/10 before the API was enforced.
LIBRARY_SAMPLER = """
vec3 sample_lobe(vec2 u, vec3 V, vec3 N, vec3 X, vec3 Y) {
    return reflect_about(V, sample_power_cosine(u, N, ke));
}
float pdf_lobe(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {
    vec3 H = normalize(L + V);
    return half_to_light_pdf(pdf_power_cosine(H, N, ke), V, H);
}
"""


def submit(exercise, tmp_path: Path, code: str) -> Path:
    path = tmp_path / exercise.student_file
    path.write_text(code, encoding="utf-8")
    return path


def refusal(exercise, tmp_path: Path, code: str) -> str:
    path = submit(exercise, tmp_path, code)
    with pytest.raises(SubmissionError) as err:
        build_model(exercise, path, code)
    return str(err.value)


def solution_with(exercise, old: str, new: str) -> str:
    text = exercise.solution.read_text(encoding="utf-8")
    assert old in text, old
    return text.replace(old, new, 1)


@pytest.mark.parametrize("exercise", EXERCISES, ids=lambda e: e.name)
def test_each_api_is_in_the_library_and_in_the_readme(exercise):
    names = exercise_names(exercise)
    readme = (exercise.folder / "README.md").read_text(encoding="utf-8")
    assert exercise.api, f"{exercise.name}: exercise.toml has no api"
    for name in exercise.api:
        assert name in names, f"{exercise.name}: api name {name} is not in the lab's library"
        assert f"`{name}`" in readme or f"`{name}(" in readme, f"{exercise.name}: {name}"


@pytest.mark.parametrize("exercise", EXERCISES, ids=lambda e: e.name)
def test_the_stub_and_the_solution_stay_in_scope(exercise, tmp_path):
    for path in (exercise.stub, exercise.solution):
        build_model(exercise, path, path.read_text(encoding="utf-8"))


def test_the_library_sampler_is_refused_with_the_line_and_what_to_do(tmp_path):
    message = refusal(SAMPLING, tmp_path, LIBRARY_SAMPLER)
    assert message.startswith(f"{tmp_path / SAMPLING.student_file}:3: reflect_about is part")
    assert "shaders/terms/sampling.glsl" in message
    assert "not of this exercise's API: write it yourself" in message
    assert "the API is PI, INV_PI, EPS, to_world" in message


def test_one_library_call_is_enough_to_be_refused(tmp_path):
    code = solution_with(
        SAMPLING,
        "    vec3 H = sample_half_vector(u, N, X, Y);\n    return reflect(-V, H);",
        "    return reflect_about(V, sample_half_vector(u, N, X, Y));",
    )
    assert ": reflect_about is part of the lab's library" in refusal(SAMPLING, tmp_path, code)
    code = solution_with(LAMBERT, "albedo * INV_PI", "albedo * INV_PI * sqr(1.0)")
    assert "sqr is part of the lab's library (shaders/terms/common.glsl)" in refusal(
        LAMBERT, tmp_path, code
    )


@pytest.mark.parametrize(
    "line",
    [
        "    lab_loop_sampler_0 = 0;",  # the guard's counter, reset: an endless loop
        "    lab_loop_line = 0;",
        "    LAB_L(loop_sampler_0) = 0;",  # pasted by a macro: checked after the preprocessor
    ],
)
def test_the_loop_guard_cannot_be_reset(tmp_path, line):
    code = solution_with(
        SAMPLING, "    float phi = 2.0 * PI * u.y;\n", f"    float phi = 2.0 * PI * u.y;\n{line}\n"
    )
    code = "#define LAB_L(x) lab_##x\n" + code
    number = code.splitlines().index(line) + 1
    message = refusal(SAMPLING, tmp_path, code)
    assert f"{SAMPLING.student_file}:{number}: rename 'lab_" in message, message
    assert "belong to the lab's harness" in message


def test_double_underscores_and_gl_names_are_refused(tmp_path):
    code = solution_with(LAMBERT, "albedo * INV_PI", "albedo * INV_PI * my__scale()")
    code = "float my__scale() { return 1.0; }\n" + code
    message = refusal(LAMBERT, tmp_path, code)
    assert ":1: rename 'my__scale': GLSL reserves names containing '__'" in message
    code = "const float gl_scale = 1.0;\n" + LAMBERT.solution.read_text(encoding="utf-8")
    assert ":1: rename 'gl_scale': GLSL and WebGL reserve" in refusal(LAMBERT, tmp_path, code)


def test_a_helper_named_like_a_library_function_is_told_to_rename(tmp_path):
    """sample_cosine has the library's signature: the compiler would say 'redefinition' at
    a line of the assembled program; another signature would be an overload that makes the
    library's reachable. Both are refused with the name and the fix."""
    for signature in (
        "vec3 sample_cosine(vec2 u, vec3 N, vec3 X, vec3 Y)",
        "float sample_cosine(float x)",
    ):
        code = f"{signature} {{ return {'N' if 'vec3 N' in signature else 'x'}; }}\n"
        code += SAMPLING.solution.read_text(encoding="utf-8")
        message = refusal(SAMPLING, tmp_path, code)
        assert ":1: rename your sample_cosine (for example my_sample_cosine)" in message
        assert "shaders/terms/sampling.glsl" in message and "would clash" in message
    code = "vec3 to_world(vec3 v, vec3 X, vec3 Y, vec3 N) { return v; }\n"
    message = refusal(SAMPLING, tmp_path, code + SAMPLING.solution.read_text(encoding="utf-8"))
    assert ":1: remove your definition of to_world: the lab gives it" in message


def test_own_names_fields_swizzles_and_comments_are_not_refused(tmp_path):
    code = """
struct Frame { vec3 sqr; float sample_cosine; };
// sample_cosine(u, N, X, Y) would be the library's: not called, only named in a comment
/* reflect_about(V, H) */
float my_cosine(Frame f) { return f.sample_cosine + f.sqr.x; }
vec3 sample_half_vector(vec2 u, vec3 N, vec3 X, vec3 Y) {
    float sqr = u.x;  // a local named like a library helper hides it
    float pdf_cosine = 1.0, to_world = 2.0;
    vec3 v = vec3(sqr, pdf_cosine, to_world);
    return normalize(v.xyz + N);
}
"""
    code += re.sub(
        r"vec3 sample_half_vector\(.*?\n}\n",
        "",
        SAMPLING.solution.read_text(encoding="utf-8"),
        flags=re.S,
    )
    path = submit(SAMPLING, tmp_path, code)
    build_model(SAMPLING, path, code)


def test_a_library_name_used_outside_the_scope_that_hides_it_is_refused(tmp_path):
    code = solution_with(
        LAMBERT,
        "albedo * INV_PI",
        "albedo * INV_PI * sqr(1.0)",
    )
    code = "float unused() { float sqr = 2.0; return sqr; }\n" + code
    assert "sqr is part of the lab's library" in refusal(LAMBERT, tmp_path, code)


def test_the_reader_sees_declarations_and_uses():
    reading = read_code(
        "const float A = 1.0, B = A;\nstruct S { float x; };\n"
        "float f(S s, float y[2]) { for (int i = 0, j = 1; i < j; ++i) { y[i] = s.x; }"
        " return g(y[0]); }\n"
    )
    assert list(reading.globals) == ["A", "B", "S", "f"]
    assert [name for name, _ in reading.uses] == ["g"]


def test_the_grader_reports_the_refusal_for_every_check(ctx, tmp_path):
    """The endless loop with its counter reset was cut by llvmpipe and told 'a constant
    factor is off'; now the file is refused before anything renders, every check saying
    why (the loop guard still names an endless loop: test_exercise_sampling)."""
    from lab.grading.checks import Grader

    loop = "    float x = 1.0;\n    while (x < 2.0) { lab_loop_sampler_0 = 0; x += 1e-30 * x; }\n"
    code = solution_with(
        SAMPLING, "    float phi = 2.0 * PI * u.y;\n", "    float phi = 2.0 * PI * u.y;\n" + loop
    )
    path = submit(SAMPLING, tmp_path, code)
    line = code.splitlines().index(loop.splitlines()[1]) + 1
    results = list(Grader().run(SAMPLING, path))
    assert len(results) == len(SAMPLING.checks)
    for result in results:
        assert result.points == 0 and f"{path.name}:{line}: rename 'lab_loop_sampler_0'" in (
            result.message
        ), result.message


def test_discard_is_refused_with_its_line(tmp_path):
    """discard throws the grader's pixel away: the probe would read 0 there and the hint
    would blame a term; the student is told the line and what to write instead."""
    guarded = "if (albedo.r > 2.0) discard;\n    return albedo * INV_PI;"
    code = solution_with(LAMBERT, "return albedo * INV_PI;", guarded)
    number = code.splitlines().index("    if (albedo.r > 2.0) discard;") + 1
    message = refusal(LAMBERT, tmp_path, code)
    assert f"{LAMBERT.student_file}:{number}: remove 'discard'" in message, message
    code = "// we never discard anything\n" + LAMBERT.solution.read_text(encoding="utf-8")
    build_model(LAMBERT, submit(LAMBERT, tmp_path, code), code)  # a comment is not code

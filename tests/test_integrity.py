"""A catalogue of hostile submissions (issue 9): each is graded and must earn what it deserves.

Every entry names the item of the issue it attacks and the words the grader's message
must contain. The honest solution beside them must keep full marks.
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from lab.grading.exercise import load_exercise
from lab.grading.runner import Pool, Task
from lab.grading.submission import SourceError, check_directives, logical_lines

ROOT = Path(__file__).resolve().parent.parent
MAIN = "import sys; from lab.cli import main; sys.exit(main(sys.argv[1:]))"
PHONG = load_exercise(ROOT / "exercises" / "02_phong")
COOK = load_exercise(ROOT / "exercises" / "09_cook_torrance")
HEADER = "\n".join(
    line for line in PHONG.stub.read_text(encoding="utf-8").splitlines() if line.startswith("//")
)
SIGNATURE = "vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y)"
PHONG_BODY = """    vec3 R = reflect(-L, N);
    return kd / 3.14159265 + ks * pow(max(dot(R, V), 0.0), ke);"""


def phong(body: str = PHONG_BODY, before: str = "") -> str:
    return f"{HEADER}\n{before}{SIGNATURE} {{\n{body}\n}}\n"


DUMMY = f"#if 0\n{SIGNATURE} {{ return vec3(0.0); }}\n#endif\n"
# name -> (exercise, file text, words the messages must contain, most points it may earn)
HOSTILE = {
    # 1. library code pulled in, required function faked inside #if 0 or by a macro
    "at_include_library": (
        PHONG,
        "// @include brdfs/phong.glsl\n" + HEADER + "\n" + DUMMY,
        ["phong.glsl:1:", "remove '@include brdfs/phong.glsl'"],
        0,
    ),
    "if0_dummy": (PHONG, HEADER + "\n" + DUMMY, ["BRDF is missing"], 0),
    "macro_function": (
        PHONG,
        HEADER + f"\n#define BRDF(L, V, N, X, Y) vec3(0.0)\n// {SIGNATURE} {{\n",
        ["BRDF is missing"],
        0,
    ),
    "extra_include_in_term_exercise": (
        COOK,
        "// @include brdfs/cook_torrance.glsl\n" + COOK.stub.read_text(encoding="utf-8"),
        ["cook_torrance.glsl:1:", "@include brdfs/cook_torrance.glsl"],
        0,
    ),
    # 9. directives hidden from a line-by-line filter
    "comment_then_extension": (
        PHONG,
        phong(before="/**/#extension GL_ARB_gpu_shader5 : enable\n"),
        ["phong.glsl:8:", "'#extension'"],
        0,
    ),
    "continued_directive": (
        PHONG,
        phong(before="#\\\nextension GL_ARB_gpu_shader5 : enable\n"),
        ["phong.glsl:8:", "'#extension'"],
        0,
    ),
    "line_directive": (PHONG, phong(before="#line 1\n"), ["phong.glsl:8:", "'#line'"], 0),
    "version_in_comment_block": (
        PHONG,
        phong(before="/* a\n   b */ #version 330\n"),
        ["phong.glsl:9:", "'#version'"],
        0,
    ),
    # 5. endless loops: the guard stops them and names the loop and the directions
    "endless_while": (
        PHONG,
        phong("    float x = 1.0;\n    while (x < 2.0) { x += 1e-30 * x; }\n" + PHONG_BODY),
        ["phong.glsl:10:", "loop at line 10 did not end within 10,000 iterations", "θi"],
        0,
    ),
    "nested_loops": (
        PHONG,
        phong(
            "    float s = 0.0;\n"
            "    for (int i = 0; i < 1000; i++)\n"
            "        for (int j = 0; j < 1000; j++)\n"
            "            for (int k = 0; k < 1000; k++) s += 1e-9;\n" + PHONG_BODY
        ),
        ["loop at line 12 did not end within 10,000 iterations"],
        0,
    ),
    "loop_made_by_a_macro": (
        PHONG,
        phong(
            "    float x = 1.0;\n    W (x < 2.0) { x += 1e-30 * x; }\n" + PHONG_BODY,
            before="#define W whi ## le\n",
        ),
        ["loop at line 11 did not end"],
        0,
    ),
    "endless_do_while": (
        PHONG,
        phong("    float x = 1.0;\n    do { x += 0.0; } while (x > 0.0);\n" + PHONG_BODY),
        ["loop at line 10 did not end"],
        0,
    ),
}


def _write(tmp: Path, name: str, exercise, text: str) -> Path:
    path = tmp / name / exercise.student_file
    path.parent.mkdir(parents=True)
    path.write_text(text, encoding="utf-8")
    return path


@pytest.fixture(scope="module")
def hostile(tmp_path_factory) -> dict[str, Task]:
    tmp = tmp_path_factory.mktemp("hostile")
    tasks = {
        name: Task(exercise, _write(tmp, name, exercise, text))
        for name, (exercise, text, _, _) in HOSTILE.items()
    }
    tasks["honest"] = Task(PHONG, PHONG.solution)
    with Pool(2, timeout=5.0) as pool:
        pool.run(list(tasks.values()))
    return tasks


@pytest.mark.parametrize("name", sorted(HOSTILE))
def test_hostile_submission_earns_nothing_and_is_told_why(hostile, name):
    _, _, words, most = HOSTILE[name]
    task = hostile[name]
    assert len(task.results) == len(task.exercise.checks)
    messages = " | ".join(r.message for r in task.checks())
    for word in words:
        assert word in messages, messages
    assert task.score <= most
    assert hostile["honest"].score == hostile["honest"].max_score


def test_loop_guard_flag_names_the_line_for_the_diagnosis(hostile):
    results = hostile["endless_while"].checks()
    assert all(r.loop_line == 10 for r in results)
    assert all(r.loop_line == 0 for r in hostile["honest"].checks())


def test_directives_are_found_the_way_the_preprocessor_sees_them():
    assert logical_lines("a\\\nb\nc /* x\ny */ #d\n") == [
        (1, "ab"),
        (3, "c "),
        (4, "  #d"),
        (5, ""),
    ]
    for text in ("// #version 330\n", "/* #extension x */\n", "float f; // #line 3\n"):
        check_directives(text, "f.glsl", [])
    with pytest.raises(SourceError, match="f.glsl:2: remove the '#include'"):
        check_directives("float a;\n  #  include <x>\n", "f.glsl", [])


def test_loop_limit_is_settable_in_exercise_toml(tmp_path, renderer):
    """A loop of 50 iterations passes the default bound and is stopped by a bound of 20."""
    import shutil

    from lab.grading.exercise import build_model

    folder = tmp_path / "02_phong"
    shutil.copytree(PHONG.folder, folder)
    spec = folder / "exercise.toml"
    spec.write_text("loop_limit = 20\n" + spec.read_text(encoding="utf-8"), encoding="utf-8")
    path = _write(
        tmp_path,
        "sub",
        PHONG,
        phong(
            "    float s = 0.0;\n    for (int i = 0; i < 50; i++) s += 0.02;\n"
            + PHONG_BODY.replace("kd /", "s * kd /")
        ),
    )
    code = path.read_text(encoding="utf-8")
    for exercise, stopped in ((PHONG, None), (load_exercise(folder), 10)):
        model = build_model(exercise, path, code)
        image = renderer.sphere(model, size=32)
        stop = renderer.loop_stop()
        assert (stop[0] if stop else None) == stopped
        assert np.isfinite(image).all()


def test_linked_exercise_folder_is_refused(tmp_path):
    """Item 2: a submission whose `exercises` folder links to the solutions earns nothing."""
    submission = tmp_path / "submission"
    submission.mkdir()
    (submission / "exercises").symlink_to(ROOT / "solutions")
    result = subprocess.run(
        [sys.executable, "-c", MAIN, "grade", str(PHONG.folder), "--from", str(submission)],
        capture_output=True,
        text=True,
        cwd=ROOT,
    )
    assert result.returncode == 1
    assert "is a symbolic link" in result.stdout and "total 0/10" in result.stdout

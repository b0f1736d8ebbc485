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

from lab.constants import LOOP_WARNING
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


SOLVED = PHONG.solution.read_text(encoding="utf-8")
RETURN = "    return kd * INV_PI + ks * pow(RoV, ke);"
HOSTILE.update(
    {
        # 8. right everywhere but at a special direction: Inf at exact normal incidence
        "inf_at_normal_incidence": (
            PHONG,
            SOLVED.replace(RETURN, RETURN.replace(";", " + kd * 1e-12 / (1.0 - NoL);")),
            ["NaN, infinite or negative"],
            4,  # the polar and sphere checks never meet L = N exactly
        ),
        "inf_at_normal_view": (
            PHONG,
            SOLVED.replace(RETURN, RETURN.replace(";", " + kd * 1e-12 / (1.0 - NoV);")),
            ["NaN, infinite or negative"],
            4,
        ),
        "nan_at_grazing": (
            PHONG,
            SOLVED.replace(RETURN, "    if (NoL < 0.002) return vec3(log(-1.0 - NoL));\n" + RETURN),
            ["NaN"],
            4,
        ),
    }
)


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


def test_grade_all_takes_any_class(tmp_path):
    """Item 7: every entry gets a row under its real name; formulas are escaped; a linked
    folder and a stray file are listed with the reason and no points; files stay in --out."""
    import csv

    lambert = ROOT / "exercises" / "01_lambert"
    solution = (ROOT / "solutions" / "01_lambert" / "lambert.glsl").read_text(encoding="utf-8")
    names = [
        "a" * 252,
        "Zoë Ünïcødé 学生",
        "line\nbreak",
        "-rf",
        ".hidden_student",
        "..dots",
        '=HYPERLINK("http://x","y")',
        "+1+cmd|' /C calc'!A0",
        "@SUM(1)",
        "../escape",
    ]
    root = tmp_path / "class"
    root.mkdir()
    for name in names:
        folder = root / name.replace("/", "_")
        (folder / "01_lambert").mkdir(parents=True)
        (folder / "01_lambert" / "lambert.glsl").write_text(solution, encoding="utf-8")
    (root / "linked").symlink_to(root / "-rf")
    (root / "notes.txt").write_text("not a student", encoding="utf-8")
    out = tmp_path / "grades"
    result = subprocess.run(
        [
            sys.executable,
            "-c",
            MAIN,
            "grade-all",
            str(root),
            "--exercises",
            str(lambert),
            "--out",
            str(out),
            "--workers",
            "1",
            "--similarity",
        ],
        capture_output=True,
        text=True,
        cwd=ROOT,
    )
    assert result.returncode == 1, result.stdout + result.stderr  # not all full marks
    with open(out / "gradebook.csv", newline="", encoding="utf-8") as handle:
        rows = {row["student"]: row for row in csv.DictReader(handle)}
    graded = [n.replace("/", "_") for n in names]
    assert len(rows) == len(graded) + 2
    for name in graded:
        shown = "'" + name if name[0] in "=+-@" else name
        assert rows[shown]["total"] == rows[shown]["max"], name
        assert (out / rows[shown]["report"]).is_file()
    assert rows["linked"]["total"] == "0" and "symbolic link" in rows["linked"]["note"]
    assert rows["notes.txt"]["total"] == "0" and "not a folder" in rows["notes.txt"]["note"]
    written = [p.resolve() for p in out.rglob("*")]
    assert all(out.resolve() in p.parents for p in written)
    assert all(len(p.name) < 80 for p in written)
    assert (out / "similarity.html").is_file() and (out / "similarity.csv").is_file()


def test_similarity_sees_copies_through_renaming_and_comments():
    """A library shader handed in with new names and comments is listed against the
    library, once per student: two students who both hand it in are not a pair (it is
    the reference, not a classmate, they share); a different correct solution matches."""
    from lab.grading import similarity

    library = (ROOT / "shaders" / "brdfs" / "blinn_phong.glsl").read_text(encoding="utf-8")
    exercise = load_exercise(ROOT / "exercises" / "03_blinn_phong")
    disguised = "// my own work\n" + library.replace("NoH", "cosHalf").replace("H", "halfway")
    own = exercise.solution.read_text(encoding="utf-8").replace(
        "normalize(L + V)", "(L + V) / length(L + V)"
    )
    files = {
        "copier": {exercise.name: (disguised, None)},
        "other": {exercise.name: (library, None)},
        "stub": {exercise.name: (exercise.stub.read_text(encoding="utf-8"), None)},
    }
    matches = similarity.compare_class(files, [exercise])
    owners = [m.a.owner for m in matches]
    assert sorted(owners) == ["copier", "other"], owners
    assert all(m.b.owner in ("library", "solution") and not m.pair for m in matches)
    assert similarity.score(*[similarity.document("x", "x", t, set()) for t in (own, own)]) == 1


LAMBERT = load_exercise(ROOT / "exercises" / "01_lambert")
LAMBERT_BODY = "    return albedo * INV_PI;"


def macro_bomb() -> str:
    """1.3 KB whose macros expand to 2^39 statements."""
    lines = ["#define A0 x = fract(x * 3.7 + V.y);"]
    lines += [f"#define A{i} A{i - 1} A{i - 1}" for i in range(1, 40)]
    text = LAMBERT.solution.read_text(encoding="utf-8")
    text = text.replace("vec3 BRDF", "\n".join(lines) + "\nvec3 BRDF")
    return text.replace(LAMBERT_BODY, "    float x = 0.5;\n    A39\n" + LAMBERT_BODY)


def test_limits_end_bombs_with_the_cause_and_the_class_goes_on(tmp_path):
    """Item 6: a macro bomb stops in the preprocessor's time limit; a 50M-element array hits
    the worker's memory cap; both lose their points with the cause named, every result is
    written, and the next submission is graded normally."""
    bomb = _write(tmp_path, "bomb", LAMBERT, macro_bomb())
    huge = _write(
        tmp_path,
        "huge",
        LAMBERT,
        LAMBERT.solution.read_text(encoding="utf-8").replace(
            LAMBERT_BODY,
            "    float big[50000000];\n    big[int(V.x * 10.0)] = 1.0;\n"
            "    return albedo * INV_PI * big[3];",
        ),
    )
    tasks = [Task(LAMBERT, bomb), Task(LAMBERT, huge), Task(LAMBERT, LAMBERT.solution)]
    with Pool(1, timeout=8.0, memory=256 << 20) as pool:
        pool.run(tasks)
    assert all(len(t.results) == len(LAMBERT.checks) for t in tasks)
    assert "a macro expands too far" in tasks[0].checks()[0].message
    assert "running out of memory (256 MB allowed)" in tasks[1].checks()[0].message
    assert tasks[0].score == tasks[1].score == 0
    assert tasks[2].score == tasks[2].max_score


def test_portability_warning_names_the_line_and_costs_nothing(tmp_path):
    """A desktop-only line (an int where ES wants a float) passes with a warning."""
    text = PHONG.solution.read_text(encoding="utf-8").replace(
        "max(dot(R, V), 0.0)", "max(dot(R, V), 0)"
    )
    task = Task(PHONG, _write(tmp_path, "port", PHONG, text))
    with Pool(1) as pool:
        pool.run([task])
    assert task.score == task.max_score
    warnings = [w for r in task.checks() for w in r.warnings]
    assert len(warnings) == 1 and "phong.glsl:14:" in warnings[0] and "web lab" in warnings[0]


def test_desktop_lab_warns_about_a_loop_the_guard_stopped(qtbot, window, tmp_path):
    """Item 5: the desktop lab keeps running and names the loop instead of freezing."""
    text = (ROOT / "shaders" / "brdfs" / "lambert.glsl").read_text(encoding="utf-8")
    text = text.replace("@model lambert", "@model looping")
    head, brace, rest = text.partition("vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {")
    line = head.count("\n") + 2
    path = tmp_path / "looping.glsl"
    path.write_text(head + brace + "\n    float s = 1.0; while (s > 0.0) { s += 1.0; }" + rest)
    assert window.open_file(path) is not None
    said = window.error_text()
    assert f"looping.glsl:{line}: the loop at line {line} did not end" in said
    assert LOOP_WARNING.split("{where}")[1] in said  # the page's sentence too


def test_hidden_mode_names_seed_values_and_lights_and_reproduces(tmp_path):
    """The output of a hidden-mode run names what it drew; the same --seed draws it again."""
    path = _write(tmp_path, "wrong", PHONG, phong())  # no horizon test: fails some checks
    command = [sys.executable, "-c", MAIN, "grade", str(PHONG.folder), "--submission", str(path)]
    runs = [
        subprocess.run([*command, "--seed", "5"], capture_output=True, text=True, cwd=ROOT)
        for _ in range(2)
    ]
    assert runs[0].stdout == runs[1].stdout
    text = runs[0].stdout
    assert "hidden mode: seed 5; parameters kd=(" in text and "ke=" in text
    assert "sphere lights θ = " in text and "--seed 5)" in text

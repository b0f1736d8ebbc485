"""The grader on bad input, its outputs (terminal, JSON, HTML, Classroom) and its commands."""

from __future__ import annotations

import base64
import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from lab.grading.exercise import find_exercises, load_exercise
from lab.grading.runner import Pool, Task

ROOT = Path(__file__).resolve().parent.parent
MAIN = "import sys; from lab.cli import main; sys.exit(main(sys.argv[1:]))"
LAMBERT = load_exercise(ROOT / "exercises" / "01_lambert")
SOLUTION = LAMBERT.solution.read_text(encoding="utf-8")
BODY = "    return albedo * INV_PI;"
HEADER = "// @model lambert\n// @param albedo color 0.8 0.8 0.8 | albedo\n"


def long_compile() -> str:
    """A small file whose macros expand to 2^15 statements: no driver finishes it quickly."""
    lines = [HEADER, "#define S0 x = fract(x * 3.7 + V.y);"]
    lines += [f"#define S{i} S{i - 1} S{i - 1}" for i in range(1, 16)]
    lines += [
        "vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {",
        "    float x = albedo.r;",
        "    S15",
        "    return albedo * INV_PI * x;",
        "}",
    ]
    return "\n".join(lines) + "\n"


# name -> (file content: str, bytes, or None for "do not create"), words the message must contain
BAD = {
    "compile_error": (SOLUTION.replace(BODY, "    return albedo * INV_PI"), ["lambert.glsl:10:"]),
    "undeclared": (
        SOLUTION.replace(BODY, "    return albedo * INV_PI * k;"),
        ["lambert.glsl:9:", "k"],
    ),
    "misnamed": (SOLUTION.replace("vec3 BRDF(", "vec3 Brdf("), ["BRDF is missing", "Brdf"]),
    "missing": (HEADER + "vec3 shade(vec3 N) { return N; }\n", ["BRDF is missing"]),
    "signature": (
        SOLUTION.replace(
            "vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y)", "float BRDF(vec3 L, vec3 V)"
        ).replace("albedo * INV_PI;", "INV_PI;"),
        ["lambert.glsl:7:", "wrong signature"],
    ),
    "nan": (SOLUTION.replace(BODY, "    return albedo * log(dot(N, L) - 2.0);"), ["NaN"]),
    "inf": (
        SOLUTION.replace(BODY, "    return albedo * exp(1000.0 * dot(N, L));"),
        ["NaN, infinite"],
    ),
    "negative": (SOLUTION.replace(BODY, "    return -albedo * INV_PI;"), ["negative"]),
    "empty": ("", ["empty"]),
    "blank": ("\n  \n", ["empty"]),
    "too_large": (SOLUTION + "// padding\n" * 30000, ["over the limit of 256 KB"]),
    "not_utf8": (SOLUTION.encode() + b"// caf\xe9\n", ["lambert.glsl:11:", "not UTF-8"]),
    "version": ("#version 330 core\n" + SOLUTION, ["lambert.glsl:1:", "#version"]),
    "extension": (
        SOLUTION.replace("vec3 BRDF", "#extension GL_ARB_foo : enable\nvec3 BRDF"),
        ["lambert.glsl:7:", "#extension"],
    ),
    "include": (SOLUTION.replace("vec3 BRDF", '#include "common.glsl"\nvec3 BRDF'), ["#include"]),
    "header_changed": (
        SOLUTION.replace("@param albedo color", "@param rho color"),
        ["@param albedo"],
    ),
    "endless": (long_compile(), ["did not finish within"]),
    # The loop guard stops the loop and names it, on every driver.
    "runaway_loop": (
        SOLUTION.replace(
            BODY, "    float s = 0.0;\n    while (true) { s += 1.0; }\n    return albedo * s;"
        ),
        ["lambert.glsl:10:", "loop at line 10 did not end within 10,000 iterations", "exit"],
    ),
    "symlink": (None, ["symbolic link"]),
    "absent": (None, ["file not found"]),
}


def make(tmp: Path, name: str) -> Path:
    folder = tmp / name
    folder.mkdir()
    path = folder / "lambert.glsl"
    content = BAD[name][0]
    if isinstance(content, bytes):
        path.write_bytes(content)
    elif isinstance(content, str):
        path.write_text(content, encoding="utf-8")
    elif name == "symlink":
        path.symlink_to(LAMBERT.solution)
    return path


@pytest.fixture(scope="module")
def bad_results(tmp_path_factory) -> dict[str, Task]:
    tmp = tmp_path_factory.mktemp("bad")
    tasks = {name: Task(LAMBERT, make(tmp, name)) for name in BAD}
    tasks["good"] = Task(LAMBERT, LAMBERT.solution)
    with Pool(2, timeout=2.0) as pool:
        pool.run(list(tasks.values()))
    return tasks


@pytest.mark.parametrize("name", sorted(BAD))
def test_bad_input_gets_a_clear_message_and_zero(bad_results, name):
    task = bad_results[name]
    assert len(task.results) == len(LAMBERT.checks)  # every check graded, none lost
    messages = " | ".join(r.message + " " + " ".join(r.errors) for r in task.checks())
    for word in BAD[name][1]:
        assert word in messages, messages
    assert "Traceback" not in messages
    assert task.score == 0 or name in ("nan", "inf", "negative")
    assert task.score < task.max_score
    assert bad_results["good"].score == task.max_score


def test_nan_fails_even_where_a_comparison_would_not_see_it(bad_results):
    probe = bad_results["nan"].checks()[0]
    assert probe.status == "failed" and probe.rows and "nan" in str(probe.rows[0][-1]).lower()


def run_cli(*args, env=None, cwd=ROOT) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-c", MAIN, *args],
        capture_output=True,
        text=True,
        cwd=cwd,
        env={**os.environ, **(env or {})},
        timeout=120,
    )


def test_grade_command_writes_every_output(tmp_path):
    bad = tmp_path / "lambert.glsl"
    bad.write_text(BAD["compile_error"][0], encoding="utf-8")
    github = tmp_path / "github_output"
    files = {k: tmp_path / f"out.{k}" for k in ("json", "html", "classroom")}
    done = run_cli(
        "grade",
        "exercises/01_lambert",
        "--submission",
        str(bad),
        *(x for k, p in files.items() for x in (f"--{k}", str(p))),
        env={"GITHUB_ACTIONS": "true", "GITHUB_OUTPUT": str(github)},
    )
    assert done.returncode == 1, done.stderr
    assert "lambert.glsl:10:" in done.stdout and "total 0/10" in done.stdout
    gradescope = json.loads(files["json"].read_text())
    assert gradescope["score"] == 0 and gradescope["execution_time"] > 0
    test = gradescope["tests"][0]
    assert set(test) >= {"name", "score", "max_score", "status", "output", "visibility"}
    assert test["status"] == "failed" and "lambert.glsl:10:" in test["output"]
    page = files["html"].read_text()
    assert "lambert.glsl:10:" in page
    key, _, value = github.read_text().strip().partition("=")
    classroom = json.loads(base64.b64decode(value))
    assert key == "result" and classroom == json.loads(files["classroom"].read_text())
    assert classroom["version"] == 1 and classroom["status"] == "fail"
    assert classroom["max_score"] == 10
    assert {"name", "status", "score", "message"} <= set(classroom["tests"][0])


def test_grade_exit_status_and_hidden_mode():
    passed = run_cli(
        "grade", "exercises/01_lambert", "--submission", str(LAMBERT.solution), "--seed", "3"
    )
    assert passed.returncode == 0 and "total 10/10" in passed.stdout, passed.stdout
    for args in (
        ["grade", "no/such/exercise"],
        ["grade", "exercises", "--submission", "x.glsl"],
        ["grade-all", "no/such/folder"],
    ):
        usage = run_cli(*args)
        assert usage.returncode == 2 and usage.stderr.startswith("brdf-lab: error:"), usage.stderr
        assert "Traceback" not in usage.stderr


def test_grade_all_writes_gradebook_and_reports(tmp_path):
    subs = tmp_path / "subs"
    (subs / "ada" / "01_lambert").mkdir(parents=True)
    (subs / "ada" / "01_lambert" / "lambert.glsl").write_text(SOLUTION, encoding="utf-8")
    (subs / "bob").mkdir()
    (subs / "bob" / "lambert.glsl").write_text(BAD["nan"][0], encoding="utf-8")
    (subs / "cy").mkdir()  # submitted nothing
    out = tmp_path / "grades"
    done = run_cli(
        "grade-all",
        str(subs),
        "--exercises",
        "exercises/01_lambert",
        "exercises/02_phong",
        "--out",
        str(out),
    )
    assert done.returncode == 1, done.stderr
    from lab.grading.students import file_stem

    rows = (out / "gradebook.csv").read_text().splitlines()
    assert rows[0] == "student,01_lambert,02_phong,total,max,report,note"
    assert rows[1].startswith("ada,10,0,10,20,") and rows[2].startswith("bob,")
    assert rows[3] == f"cy,0,0,0,20,reports/{file_stem('cy')}.html,"
    reports = out / "reports"
    assert "file not found" in (reports / f"{file_stem('cy')}.html").read_text()
    assert '<img src="data:image/png;base64,' in (reports / f"{file_stem('ada')}.html").read_text()
    assert json.loads((reports / f"{file_stem('ada')}.json").read_text())["score"] == 10


def test_an_upload_inside_its_own_folder_is_found_but_never_guessed(tmp_path):
    """Gradescope keeps the folder a student uploaded (lab1/lambert.glsl): the one file of
    the exercise's name in the student's folder is graded; with two copies none is picked."""
    from lab.grading.cli import locate

    exercise = next(e for e in find_exercises(ROOT / "exercises") if e.name == "01_lambert")
    nested = tmp_path / "ada" / "lab1" / "final"
    nested.mkdir(parents=True)
    (nested / "lambert.glsl").write_text(SOLUTION, encoding="utf-8")
    assert locate(tmp_path / "ada", exercise) == nested / "lambert.glsl"
    (tmp_path / "ada" / "old").mkdir()
    (tmp_path / "ada" / "old" / "lambert.glsl").write_text(SOLUTION, encoding="utf-8")
    assert locate(tmp_path / "ada", exercise) == tmp_path / "ada" / "lambert.glsl"  # not found


def test_classroom_workflow_template_runs_the_grader_and_reporter():
    text = (ROOT / "lab" / "grading" / "templates" / "classroom.yml").read_text()
    assert 'brdf-lab grade "${folders[@]}" --from exercises --seed' in text
    assert "classroom-resources/autograding-grading-reporter@v1" in text
    assert "BRDF-LAB_RESULTS" in text and "steps.brdf-lab.outputs.result" in text


def test_usage_error_still_writes_the_result_files(tmp_path):
    """Gradescope shows the reason instead of 'the autograder produced no results'."""
    results, classroom = tmp_path / "results.json", tmp_path / "classroom.json"
    result = run_cli(
        "grade",
        str(tmp_path / "no_such_exercise"),
        "--json",
        str(results),
        "--classroom",
        str(classroom),
    )
    assert result.returncode == 2
    assert "no exercise.toml" in result.stderr and "Traceback" not in result.stderr
    gradescope = json.loads(results.read_text())
    assert gradescope["score"] == 0 and "no exercise.toml" in gradescope["output"]
    assert json.loads(classroom.read_text())["status"] == "error"

"""Exercise 12 (tabulated BRDF lookup), the checks' `table` key and the `bin_edges` kind.

The solution is the lab's own `measured` model (lab/measured/measured.glsl) on the table
the grader tabulates, value for value, and agrees with the numpy lookup of lab.measured.merl;
the bin-edge rows lie where they say; the solution (and its correct rewrites) score full
and the stub 0 in reference mode and for 50 hidden seeds; each stored mistake loses points
with its own hint; every wrong submission loses points; bad tables and bad submissions get
an error in words, never a traceback.
"""

from __future__ import annotations

import importlib.util
import math
import shutil
import sys
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from lab import reference
from lab.grading import tables
from lab.grading.checks import Grader, hidden_variant, prepare
from lab.grading.exercise import load_exercise
from lab.grading.kinds import kind_of
from lab.grading.kinds.bin_edges import MARGIN, edge_angles
from lab.grading.spec import ExerciseError
from lab.measured.merl import MERL_DIMS, continuous_index, half_diff, lookup

ROOT = Path(__file__).resolve().parents[1]
EXERCISE = load_exercise(ROOT / "exercises" / "12_tabulated_lookup")
SEEDS = 50
HERE = ROOT / "tests" / "exercise_12"
_spec = importlib.util.spec_from_file_location("exercise_12_measure", HERE / "measure.py")
measure = importlib.util.module_from_spec(_spec)  # the batch's own reader (BEFORE/AFTER)
sys.modules["exercise_12_measure"] = measure
_spec.loader.exec_module(measure)


@pytest.fixture(scope="module")
def grader() -> Grader:
    return Grader()  # no explainer: scores only


def _check(name: str):
    return next(c for c in EXERCISE.checks if c.name == name)


def _directions(angles: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    theta = np.radians(angles)
    return (
        reference.direction(theta[:, 0], theta[:, 1]),
        reference.direction(theta[:, 2], theta[:, 3]),
    )


@pytest.mark.parametrize("name", ["bins.index", "bins.lookup", "probe.lookup"])
def test_the_solution_is_the_labs_measured_model(grader, name):
    """On the grader's table, at the check's rows: the solution gives exactly what the lab's
    measured model gives (same texture, same arithmetic), and the float64 numpy lookup of
    lab.measured.merl agrees within half the check's tolerance, or at ill-conditioned rows
    within what float32 moves the lookup there."""
    check = _check(name)
    mode = check.params["interpolation"]
    kind = kind_of(check)
    angles = kind.angles(check)
    mine = kind.render(grader.renderer, grader.solution_model(EXERCISE), check)
    measured = tables.measured(grader.renderer, check.table[0])
    lab = grader.renderer.eval_angles(measured, {"interpolation": mode}, angles)
    np.testing.assert_array_equal(mine, lab)
    want = lookup(measured.table, *_directions(angles), mode)
    # Half the check's rtol, or where a row is ill-conditioned (grazing: phi_d moves by a
    # hundredth of a bin when L and V are rounded to float32) the lookup's own float32
    # change there (tables.spread, before it is grown into the grader's tolerance).
    moved = 0.0 if mode == "nearest" else tables.spread(check, angles) / tables.SPREAD_GROW
    allowed = check.atol + 0.5 * check.rtol * np.abs(want) + moved
    assert (np.abs(mine[:, :3] - want) <= allowed).all(), np.argwhere(
        np.abs(mine[:, :3] - want) > allowed
    )
    assert (mine[:, 0] > 0).mean() > 0.8  # the rows mostly see the table, not the horizon


def test_bin_edge_rows_lie_on_the_grid():
    """Every row above the horizon; a third near a bin edge (theta_h's first bins among
    them), some at phi_d's fold and some at grazing theta_d; each row as far from an edge
    as float32 needs; the same rows for the same seed."""
    check = _check("bins.index")
    rows = edge_angles(check)
    assert rows.shape == (check.pairs, 4) and (rows[:, [0, 2]] < 90.0).all()
    assert rows is edge_angles(check)
    pos = np.stack(continuous_index(*half_diff(*_directions(rows))), axis=1)
    edge = np.abs(pos - np.round(pos))
    assert edge.min() > 0.8 * MARGIN  # no row sits on an edge
    near = edge < 1.2 * MARGIN
    assert near.any(axis=1).mean() > 0.4
    assert (near[:, 0] & (pos[:, 0] < 8.0)).sum() >= 10  # the peak's narrow bins
    fold = near[:, 2] & ((pos[:, 2] < 1.0) | (pos[:, 2] > MERL_DIMS[2] - 1.0))
    assert fold.sum() >= 10
    assert (pos[:, 1] > MERL_DIMS[1] - 6.0).sum() >= 20  # grazing theta_d
    other = edge_angles(replace(check, seed=check.seed + 1))
    assert not np.allclose(other, rows)


def test_hidden_mode_tabulates_other_models_within_their_ranges(grader):
    solution = grader.solution_model(EXERCISE)
    index = EXERCISE.checks.index(_check("bins.index"))
    drawn = [hidden_variant(EXERCISE.checks[index], solution, s, index) for s in range(30)]
    specs = [d.table[0] for d in drawn]
    assert all(len(d.table) == 1 for d in drawn)
    assert {s.model for s in specs} == {"ggx", "cook_torrance", "blinn_phong"}
    for spec in specs:
        params = dict(spec.params)
        for name, (low, high) in {"alpha": (0.08, 0.5), "m": (0.1, 0.5), "ke": (15, 400)}.items():
            if name in params:
                assert low <= params[name] <= high
        assert all(0.05 <= c <= 0.5 for c in params["kd"]) and spec.noise == 0.02
    assert len({s.params for s in specs}) == 30
    assert drawn[0].params["interpolation"] == "nearest"  # the lookup under test stays


def _scores(grader, files: dict[str, Path], seed: int | None) -> dict[str, tuple[float, list]]:
    out = {name: (0.0, []) for name in files}
    readings = {name: prepare(EXERCISE, path) for name, path in files.items()}
    solution = grader.solution_model(EXERCISE)
    for index, check in enumerate(EXERCISE.checks):
        drawn = hidden_variant(check, solution, seed, index) if seed is not None else check
        expected = grader.expected(EXERCISE, drawn, live=seed is not None)
        for name, reading in readings.items():
            assert not reading.error, (name, reading.error)
            result = grader.grade(EXERCISE, drawn, reading.model, reading.code, expected)
            score, failed = out[name]
            out[name] = (score + result.points, failed + ([] if result.passed else [check.name]))
    return out


def _failures(grader, files: dict[str, Path], seeds: list) -> list[str]:
    problems = []
    for seed in seeds:
        for name, (score, failed) in _scores(grader, files, seed).items():
            if name == "stub" and score != 0.0:
                problems.append(f"seed {seed}: the stub scores {score}")
            if name != "stub" and score != EXERCISE.max_points:
                problems.append(f"seed {seed}: {name} fails {failed}")
    return problems


def test_solution_full_and_stub_zero_in_reference_mode_and_50_seeds(grader):
    files = {"solution": EXERCISE.solution, "stub": EXERCISE.stub}
    problems = _failures(grader, files, [None, *range(SEEDS)])
    assert not problems, "\n".join(problems)


def test_correct_rewrites_full_marks_on_ten_seeds(grader):
    files = {p.stem: p for p in sorted((EXERCISE.solution.parent / "correct").glob("*.glsl"))}
    assert len(files) >= 2
    problems = _failures(grader, files, [None, *range(10)])
    assert not problems, "\n".join(problems)


@pytest.fixture(scope="module")
def graded(tmp_path_factory) -> dict:
    """With the diagnosis: each stored mistake and the wrong/heldout batch (reference mode)."""
    from lab.grading.mistakes import known_mistakes
    from lab.grading.runner import Pool, Task

    tmp = tmp_path_factory.mktemp("mistakes12")
    solution = EXERCISE.solution.read_text(encoding="utf-8")
    tasks = {}
    for variant in known_mistakes(EXERCISE):
        path = tmp / variant.key / EXERCISE.student_file
        path.parent.mkdir()
        path.write_text(variant.apply(solution), encoding="utf-8")
        tasks["mistake", variant.key] = (Task(EXERCISE, path), variant.hint)
    for label, path in measure.submissions().items():
        if label.startswith(("wrong/", "heldout/")):
            tasks["batch", label] = (Task(EXERCISE, path), "")
    with Pool(2, timeout=60.0) as pool:
        pool.run([task for task, _ in tasks.values()])
    return tasks


def test_each_stored_mistake_loses_points_with_its_own_hint(graded):
    missing = []
    for key, (task, hint) in graded.items():
        if key[0] != "mistake":
            continue
        assert task.score < task.max_score, f"{key[1]} scores full marks"
        said = [r.diagnosis for r in task.checks() if not r.passed]
        if not any(hint[:40] in s for s in said):
            missing.append(f"{key[1]} ({hint[:50]}...): {said}")
    assert not missing, "\n".join(missing)


def test_every_wrong_submission_loses_points_and_most_are_named(graded):
    batch = {key[1]: task for key, (task, _) in graded.items() if key[0] == "batch"}
    assert len([k for k in batch if k.startswith("wrong/")]) >= 8
    for label, task in batch.items():
        assert task.score < task.max_score, label
    named = [k for k, t in batch.items() if k.startswith("wrong/") and measure.named(k, t)]
    assert len(named) >= 11, named  # the AFTER figure: 12 of 12 (BEFORE: 0)


# -- bad input: words, never a traceback ------------------------------------------------------
def _grade_text(grader, tmp_path, text: str, name: str = "bins.index"):
    path = tmp_path / EXERCISE.student_file
    path.write_text(text, encoding="utf-8")
    reading = prepare(EXERCISE, path)
    if reading.error:
        return reading.error
    check = _check(name)
    result = grader.grade(
        EXERCISE, check, reading.model, reading.code, grader.expected(EXERCISE, check, live=False)
    )
    assert not result.passed
    return result.message


def test_bad_submissions_are_told_what_is_wrong(grader, tmp_path):
    solution = EXERCISE.solution.read_text(encoding="utf-8")
    gone = solution.replace("uniform highp sampler3D u_table;", "")
    assert "does not compile" in _grade_text(grader, tmp_path, gone)
    flat = solution.replace("uniform highp sampler3D u_table;", "uniform highp sampler2D u_table;")
    assert "does not compile" in _grade_text(grader, tmp_path, flat)
    no_index = solution.replace("ivec3 merl_index(vec3 angles)", "ivec3 bin_of(vec3 angles)")
    no_index = no_index.replace("table_texel(merl_index(angles))", "table_texel(bin_of(angles))")
    assert "merl_index" in _grade_text(grader, tmp_path, no_index)
    wild = solution.replace("return table_lookup(angles);", "return table_lookup(angles) / 0.0;")
    message = _grade_text(grader, tmp_path, wild, "probe.lookup")
    assert "differ" in message or "NaN" in message or "infinite" in message


@pytest.mark.parametrize(
    ("table", "words"),
    [
        ('{ model = "ggxx" }', "should name a library model"),
        ('{ model = "ggx", params = { roughness = 0.2 } }', "no parameter of ggx"),
        ('{ model = "ggx", ranges = { alpha = [0.0, 2.0] } }', "within the header's range"),
        ('{ model = "ggx", noise = 2.0 }', "noise = 2.0 should be"),
        ('{ model = "ggx", dims = [90, 90] }', "three whole numbers"),
        ('{ model = "ggx", filter = "linear" }', "no key 'filter'"),
        ('{ model = "ggx", uniform = "u table" }', "should be a GLSL name"),
        ('"ggx"', "should be a model to tabulate"),
    ],
)
def test_a_bad_table_stops_the_grader_with_words(tmp_path, table, words):
    folder = tmp_path / "exercises" / "12_x"
    folder.mkdir(parents=True)
    shutil.copy(EXERCISE.stub, folder / EXERCISE.student_file)
    (folder / "exercise.toml").write_text(
        'title = "x"\nstudent_file = "tabulated.glsl"\n\n[[checks]]\nname = "p"\n'
        f'kind = "probe"\npoints = 1\ntable = {table}\n',
        encoding="utf-8",
    )
    with pytest.raises(ExerciseError) as err:
        load_exercise(folder)
    assert words in str(err.value), str(err.value)


def test_a_table_survives_the_diagnosiss_copies_of_the_model(grader):
    """dataclasses.replace (the diagnosis's instrumented copies) keeps the bound table."""
    check = _check("probe.lookup")
    model = tables.bound(grader.renderer, grader.solution_model(EXERCISE), check)
    copy = replace(model, code=model.code + "\n")
    assert copy.table_source is model.table_source
    assert tables.bound(grader.renderer, model, check) is model
    rows = kind_of(check).angles(check)
    np.testing.assert_array_equal(
        grader.renderer.eval_angles(copy, {"interpolation": "linear"}, rows),
        grader.renderer.eval_angles(model, {"interpolation": "linear"}, rows),
    )
    assert math.isclose(float(model.table_source.table.dims[0]), 90.0)


def test_the_page_gets_the_graders_tolerances_or_leaves_tables_to_the_grader(monkeypatch):
    """exercises.json carries each value check with the grader's own tolerance, made from
    its table (wider than the check's plain one where the lookup is ill-conditioned: the
    page makes the table itself, tests/test_web_tables.py); where no OpenGL is to be had
    for that table, the checks are the grader's alone, said why."""
    import lab.grading.kinds as kinds
    from lab.grading.kinds import VALUES_FILE
    from lab.grading.kinds.values import floats_b64
    from lab.web.exercises import grader_only

    with np.load(EXERCISE.references / VALUES_FILE) as data:
        values = {k: data[k] for k in data.files}
    check = _check("bins.lookup")
    entry = kind_of(check).practice(EXERCISE, check, values)
    expected = values[check.name][:, :3]
    angles = kind_of(check).angles(check)
    tolerance = kind_of(check).tolerance(check, angles, expected, expected)
    assert entry["tolerance"] == floats_b64(tolerance)
    assert (tolerance > check.atol + check.rtol * np.abs(expected) * 1.01).any()
    assert grader_only(EXERCISE, values) == []
    monkeypatch.setattr(kinds, "made_here", lambda check: not check.table)
    for check in EXERCISE.checks:
        assert kind_of(check).practice(EXERCISE, check, values) is None
    assert all("no OpenGL" in entry["why"] for entry in grader_only(EXERCISE, values))


def test_any_kind_reads_a_table_the_check_names(grader):
    """The key is the format's, not exercise 12's: a polar check parsed with a table renders
    the solution bound to it (the lab's measured model's curve on that table)."""
    from lab.grading.kinds import find

    polar = find("polar")
    table = {"model": "blinn_phong", "params": {"ke": 40.0}}
    check = polar.parse(
        {
            "name": "polar.t",
            "points": 1,
            "table": table,
            "theta_i": 40.0,
            "params": {"interpolation": "linear"},
        },
        "test",
    )
    assert check.table[0].model == "blinn_phong" and dict(check.table[0].params) == {"ke": 40.0}
    got = polar.render(grader.renderer, grader.solution_model(EXERCISE), check)
    measured = tables.measured(grader.renderer, check.table[0])
    want = grader.renderer.eval_angles(measured, {"interpolation": "linear"}, polar.angles(check))
    np.testing.assert_array_equal(got, want)
    assert got.max() > 0.1


def test_the_cli_draws_a_file_that_reads_a_table(tmp_path, capsys):
    """`render FILE.glsl --table T.binary` binds the table to the file's u_table: the solution
    draws what `render measured --table` draws; a file without the sampler is told why."""
    from PIL import Image

    from lab.cli import main
    from lab.measured.merl import write_merl
    from lab.measured.tabulate import tabulate

    table = write_merl(tabulate("ggx", {"alpha": 0.25}), tmp_path / "t.binary")  # MERL bins
    for name, model in (("mine", str(EXERCISE.solution)), ("lab", "measured")):
        out = tmp_path / f"{name}.png"
        assert main(["render", model, "--table", str(table), "--size", "96", "-o", str(out)]) == 0
    mine, lab = (np.asarray(Image.open(tmp_path / f"{n}.png")) for n in ("mine", "lab"))
    assert mine.std() > 5.0  # a lit sphere, not black
    np.testing.assert_array_equal(mine, lab)
    phong = ROOT / "shaders" / "brdfs" / "phong.glsl"
    assert main(["render", str(phong), "--table", str(table), "-o", str(tmp_path / "x.png")]) == 2
    assert "uniform highp sampler3D u_table" in capsys.readouterr().err

"""Exercise 13 (spatially varying BRDF) and its check kind, `object`.

The kind's render against the lab's own object view of the library models (constant
textures: the blend's ends are Lambert and Ward there); hidden textures drawn anew, in the
committed ones' size, character and range; the solution full and the stub 0 in reference
mode and for 50 hidden seeds; each stored mistake loses points with its own hint; the
wrong submissions (tests/exercise_13/wrong, written before the tuning, and heldout/) lose
points, those of wrong/ named; the correct rewrites full marks; broken exercise files and
submissions are refused with what to fix.
"""

from __future__ import annotations

import importlib.util
import shutil
import sys
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from lab.grading.checks import Grader, hidden_variant, prepare
from lab.grading.exercise import load_exercise
from lab.grading.kinds import kind_of
from lab.grading.kinds import object as O
from lab.grading.spec import ExerciseError

ROOT = Path(__file__).resolve().parents[1]
EXERCISE = load_exercise(ROOT / "exercises" / "13_svbrdf")
SEEDS = 50
HERE = ROOT / "tests" / "exercise_13"
# Loaded under its own name: other batches have a measure.py too.
_spec = importlib.util.spec_from_file_location("exercise_13_measure", HERE / "measure.py")
measure = importlib.util.module_from_spec(_spec)
sys.modules["exercise_13_measure"] = measure
_spec.loader.exec_module(measure)


@pytest.fixture(scope="module")
def grader() -> Grader:
    return Grader()  # no explainer: scores only


def _constant(tmp_path: Path, rgb: tuple[int, int, int], name: str) -> str:
    from PIL import Image

    path = tmp_path / f"{name}.png"
    Image.fromarray(np.full((8, 16, 3), rgb, np.uint8), "RGB").save(path)
    return str(path)


@pytest.mark.parametrize("mask", [0, 255])
def test_constant_textures_give_the_library_model_on_the_object_view(grader, tmp_path, mask):
    """All paint is the library's Lambert, all metal its Ward (kd = 0) with alpha_y =
    alpha_x * anisotropy, as the lab's object view draws them: the kind binds the textures,
    finds the same surface points and passes the same tangent frame (X along u)."""
    from lab.app.renderer import AppRenderer
    from lab.models import load_model

    albedo, rough = (200, 120, 40), 51  # 8 bits: the values the shader reads exactly
    check = replace(EXERCISE.checks[0], params={"anisotropy": 3.0})
    options = dict(check.options)
    options["textures"] = {
        "albedo_map": _constant(tmp_path, albedo, "albedo"),
        "roughness_map": _constant(tmp_path, (rough,) * 3, "roughness"),
        "mask_map": _constant(tmp_path, (mask,) * 3, "mask"),
    }
    check = replace(check, options=options)
    got = O.KIND.render(grader.renderer, grader.solution_model(EXERCISE), check)
    colour = tuple(c / 255.0 for c in albedo)
    if mask:
        model = load_model("ward")
        values = {"kd": (0.0, 0.0, 0.0), "ks": colour, "alpha_x": rough / 255.0}
        values["alpha_y"] = 3.0 * rough / 255.0
    else:
        model, values = load_model("lambert"), {"albedo": colour}
    app = AppRenderer(grader.renderer.ctx)
    yaw, pitch = np.radians([check.options["yaw"], check.options["pitch"]])
    want = app.object(
        model, values, check.lights, shape=0, mode=1, yaw=yaw, pitch=pitch, size=check.size
    )
    covered = want[..., 3] > 0.5
    assert covered.mean() > 0.2 and np.array_equal(covered, got[..., 3] > 0.5)
    np.testing.assert_allclose(got[covered, :3], want[covered, :3], rtol=2e-4, atol=2e-5)
    assert got[covered, :3].max() > 0.2  # lit, not two black images


def test_hidden_textures_are_new_and_keep_size_character_and_range():
    check = EXERCISE.checks[0]
    committed = O.KIND.images(check)
    seen = []
    for seed in range(SEEDS):
        drawn = replace(check, seed=1000 + seed)
        assert O.KIND.hidden(drawn)
        images = O.KIND.images(drawn)
        assert set(images) == set(committed)
        for name, image in images.items():
            base = committed[name]
            assert image.shape == base.shape and image.dtype == np.uint8
            rgb, ref = image[..., :3].astype(int), base[..., :3].astype(int)
            assert ref.min() <= rgb.min() and rgb.max() <= ref.max(), name
            grey = (rgb[..., 0] == rgb[..., 1]).all() and (rgb[..., 1] == rgb[..., 2]).all()
            assert grey == (name != "albedo_map"), name
            assert np.abs(rgb - ref).mean() > 8.0, (seed, name)  # not the committed content
            assert np.ptp(rgb) > 20, (seed, name)  # varies across the surface
        seen.append(images["mask_map"])
        assert np.array_equal(O.KIND.images(drawn)["mask_map"], images["mask_map"])  # seeded
    assert len({s.tobytes() for s in seen}) == SEEDS
    assert O.KIND.turn(check)[0] == pytest.approx(np.radians(check.options["yaw"]))


def test_the_committed_textures_are_what_make_textures_writes(tmp_path, monkeypatch):
    from PIL import Image

    spec = importlib.util.spec_from_file_location("make_textures_13", HERE / "make_textures.py")
    make = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(make)
    monkeypatch.setattr(make, "OUT", tmp_path)
    make.main()
    for path in sorted((EXERCISE.folder / "textures").glob("*.png")):
        with Image.open(path) as old, Image.open(tmp_path / path.name) as new:
            assert old.mode == new.mode and np.array_equal(np.asarray(old), np.asarray(new))


def _scores(grader, readings: dict, seed: int | None) -> dict[str, tuple[float, list]]:
    """Each file's score at one setting (None: reference mode) and its failed checks;
    `readings`: name -> checks.prepare's reading of the file."""
    out = {name: (0.0, []) for name in readings}
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


def test_solution_full_and_stub_zero_in_every_mode(grader):
    files = {"solution": EXERCISE.solution, "stub": EXERCISE.stub}
    readings = {name: prepare(EXERCISE, path) for name, path in files.items()}
    problems = []
    for seed in [None, *range(SEEDS)]:
        scores = _scores(grader, readings, seed)
        if scores["solution"][0] != EXERCISE.max_points:
            problems.append(f"seed {seed}: solution fails {scores['solution'][1]}")
        if scores["stub"][0] != 0.0:
            problems.append(f"seed {seed}: stub scores {scores['stub'][0]}")
    assert not problems, "\n".join(problems)


def test_correct_rewrites_full_and_a_hard_coded_mask_zero_on_five_seeds(grader):
    files = {p.stem: p for p in sorted((EXERCISE.solution.parent / "correct").glob("*.glsl"))}
    assert len(files) >= 2
    files["hard_coded"] = HERE / "hardcoded" / "mask_formula.glsl"
    readings = {name: prepare(EXERCISE, path) for name, path in files.items()}
    for seed in [None, *range(5)]:
        for name, (score, failed) in _scores(grader, readings, seed).items():
            want = 0.0 if name == "hard_coded" else EXERCISE.max_points
            assert score == want, (seed, name, failed)


def test_the_held_out_wrong_submissions_lose_points(grader):
    """Written after the tuning (tests/exercise_13/heldout): each loses points in reference
    mode and at hidden seed 1."""
    files = {p.stem: p for p in sorted((HERE / "heldout").glob("*.glsl"))}
    assert len(files) >= 5
    readings = {name: prepare(EXERCISE, path) for name, path in files.items()}
    for seed in (None, 1):
        for name, (score, _) in _scores(grader, readings, seed).items():
            assert score < EXERCISE.max_points, (seed, name)


def test_hidden_mode_draws_textures_turn_lights_and_anisotropy(grader):
    solution = grader.solution_model(EXERCISE)
    check = EXERCISE.checks[1]
    drawn = [hidden_variant(check, solution, seed, 1) for seed in range(5)]
    assert all(O.KIND.hidden(d) for d in drawn)
    assert len({O.KIND.turn(d)[0] for d in drawn}) == 5
    assert len({d.lights[0].phi for d in drawn}) == 5
    assert all(2.0 <= d.params["anisotropy"] <= 5.0 for d in drawn)
    assert all(15.0 <= d.lights[0].theta <= 60.0 for d in drawn)  # purpose: highlight


def _exercise_copy(tmp_path: Path, old: str, new: str) -> Path:
    folder = tmp_path / "13_x"
    shutil.copytree(EXERCISE.folder, folder)
    text = (folder / "exercise.toml").read_text(encoding="utf-8")
    assert old in text
    (folder / "exercise.toml").write_text(text.replace(old, new, 1), "utf-8")
    return folder


@pytest.mark.parametrize(
    ("old", "new", "said"),
    [
        ('"textures/mask.png"', '"textures/masks.png"', "give a .png file of the exercise"),
        ("mask_map = ", "lab_mask = ", "a texture is named by the GLSL sampler2D"),
        ('shape = "torus"', 'shape = "teapot"', "'teapot' is not one of torus"),
        ("yaw = 35.0", 'yaw = "east"', "yaw = 'east' should be a number"),
    ],
)
def test_a_broken_exercise_file_says_what_to_fix(tmp_path, old, new, said):
    folder = _exercise_copy(tmp_path, old, new)
    with pytest.raises(ExerciseError, match=said):
        load_exercise(folder)


def test_a_texture_that_is_no_png_is_named(tmp_path):
    folder = _exercise_copy(tmp_path, "yaw = 35.0", "yaw = 35.0")
    (folder / "textures" / "mask.png").write_bytes(b"not a png")
    with pytest.raises(ExerciseError, match="mask_map = 'textures/mask.png': cannot be read"):
        load_exercise(folder)


def test_bad_submissions_fail_with_a_message_and_never_crash(grader, tmp_path):
    """Without the sampler declarations: a compile error at the student's line; a file
    without SVBRDF is refused before rendering; NaN pixels are named as such."""
    code = EXERCISE.solution.read_text(encoding="utf-8")
    path = tmp_path / EXERCISE.student_file
    path.write_text(code.replace("uniform sampler2D mask_map;", ""), encoding="utf-8")
    reading = prepare(EXERCISE, path)
    result = grader.grade(EXERCISE, EXERCISE.checks[0], reading.model, reading.code, None)
    assert not result.passed and "does not compile" in result.message
    assert any("mask_map" in e and "svbrdf.glsl:" in e for e in result.errors), result.errors
    path.write_text(code.replace("vec3 SVBRDF(", "vec3 SV_BRDF("), encoding="utf-8")
    assert "SVBRDF" in prepare(EXERCISE, path).error
    path.write_text(code.replace("float NoH = max(dot(N, H), EPS);", "float NoH = 0.0;"), "utf-8")
    reading = prepare(EXERCISE, path)
    expected = grader.expected(EXERCISE, EXERCISE.checks[0], live=False)
    result = grader.grade(EXERCISE, EXERCISE.checks[0], reading.model, reading.code, expected)
    assert not result.passed and "NaN, infinite or negative" in result.message


def test_the_page_gets_the_graders_textures_and_turn():
    """practice() sends each sampler's texture as the grader binds it (the files' bytes) and
    the turn it renders with, and no file path (exercises.json is served); the page's
    renders are held to the grader's verdicts in tests/test_web_practice.py."""
    import base64
    import json
    import zlib

    from lab.grading.kinds.object import read_texture

    for check in EXERCISE.checks:
        kind = kind_of(check)
        with np.load(EXERCISE.references / "values.npz") as values:
            sent = kind.practice(EXERCISE, check, values)
        assert sent["view"] == "grade_object"
        assert (sent["yaw_rad"], sent["pitch_rad"]) == kind.turn(check)
        assert set(sent["textures"]) == set(check.options["textures"])
        for sampler, path in check.options["textures"].items():
            texture = sent["textures"][sampler]
            image = read_texture(path)
            assert (texture["height"], texture["width"]) == image.shape[:2]
            assert zlib.decompress(base64.b64decode(texture["data"])) == image.tobytes()
    from lab.web.exercises import exercise_entry

    assert str(EXERCISE.folder.parent) not in json.dumps(exercise_entry(EXERCISE))


@pytest.fixture(scope="module")
def graded(tmp_path_factory) -> dict:
    """With the diagnosis, in reference mode: each stored mistake and the wrong files written
    before the tuning, in one pool (hidden mode's figures: tests/exercise_13/AFTER.txt)."""
    from lab.grading.mistakes import known_mistakes
    from lab.grading.runner import Pool, Task

    tmp = tmp_path_factory.mktemp("mistakes13")
    solution = EXERCISE.solution.read_text(encoding="utf-8")
    tasks = {}
    for variant in known_mistakes(EXERCISE):
        path = tmp / variant.key / EXERCISE.student_file
        path.parent.mkdir()
        path.write_text(variant.apply(solution), encoding="utf-8")
        tasks["mistake", variant.key] = (Task(EXERCISE, path), variant.hint)
    for label, path in measure.submissions().items():
        if label.startswith("wrong/"):
            tasks["batch", label, None] = (Task(EXERCISE, path), "")
    unread = tmp / "unread" / EXERCISE.student_file  # no stored mistake: the kind's own words
    unread.parent.mkdir()
    unread.write_text(solution.replace("texture(roughness_map, uv).r", "0.2"), encoding="utf-8")
    tasks["unread"] = (Task(EXERCISE, unread, 3), "")
    with Pool(2, timeout=120.0) as pool:
        pool.run([task for task, _ in tasks.values()])
    return tasks


def test_each_stored_mistake_loses_points_with_its_own_hint(graded):
    missing = []
    mistakes = [key for key in graded if key[0] == "mistake"]
    assert len(mistakes) >= 14
    for key in mistakes:
        task, hint = graded[key]
        assert task.score < task.max_score, f"{key[1]} scores full marks"
        said = [r.diagnosis for r in task.checks() if not r.passed]
        if not any(hint[:40] in s for s in said):
            missing.append(f"{key[1]} ({hint[:50]}...): {said}")
    assert not missing, "\n".join(missing)


def test_every_wrong_submission_loses_points(graded):
    batch = [key for key in graded if key[0] == "batch"]
    assert len(batch) >= 8
    for key in batch:
        assert graded[key][0].score < graded[key][0].max_score, key


def test_the_wrong_submissions_are_named(graded):
    """The AFTER figure: every one of wrong/ named (BEFORE: 3 of 13, two of them by words
    the localisation happened to quote)."""
    unnamed = [
        key
        for key, (task, _) in graded.items()
        if key[0] == "batch" and key[1].startswith("wrong/") and not measure.named(key[1], task)
    ]
    assert not unnamed, unnamed


def test_a_texture_the_file_never_reads_is_named(graded):
    task = graded["unread"][0]
    said = [r.diagnosis for r in task.checks() if not r.passed]
    assert said and all("never reads roughness_map" in s for s in said), said

"""Integrity of the exercises: solutions pass, stubs and plausible mistakes fail.

One grading run (a pool of two workers) grades every variant; the tests read its results.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from lab.grading.exercise import find_exercises
from lab.grading.runner import Pool, Task

ROOT = Path(__file__).resolve().parent.parent
MAIN = "import sys; from lab.cli import main; sys.exit(main(sys.argv[1:]))"
EXERCISES = {e.name: e for e in find_exercises(ROOT / "exercises")}

# (exercise, what the student got wrong, text in the solution, the wrong text)
MISTAKES = [
    ("01_lambert", "missing pi", "albedo * INV_PI", "albedo"),
    ("01_lambert", "cosine inside the BRDF", "albedo * INV_PI", "albedo * INV_PI * dot(N, L)"),
    (
        "01_lambert",
        "no horizon test",
        "if (dot(N, L) <= 0.0 || dot(N, V) <= 0.0) return vec3(0.0);",
        "",
    ),
    ("02_phong", "N.H instead of R.V", "max(dot(R, V), 0.0)", "max(dot(N, normalize(L + V)), 0.0)"),
    (
        "02_phong",
        "R mirrored the wrong way",
        "vec3 R = 2.0 * NoL * N - L;",
        "vec3 R = reflect(L, N);",
    ),
    ("02_phong", "R.V not clamped", "max(dot(R, V), 0.0)", "dot(R, V)"),
    ("02_phong", "diffuse without 1/pi", "kd * INV_PI +", "kd +"),
    ("03_blinn_phong", "H not normalized", "normalize(L + V)", "(L + V)"),
    (
        "03_blinn_phong",
        "R.V instead of N.H",
        "max(dot(N, H), 0.0)",
        "max(dot(reflect(-L, N), V), 0.0)",
    ),
    ("03_blinn_phong", "half of the exponent", "pow(NoH, ke)", "pow(NoH, 0.5 * ke)"),
    (
        "04_phong_illumination",
        "no ambient term",
        "vec3 color = ka * ambient;",
        "vec3 color = vec3(0.0);",
    ),
    (
        "04_phong_illumination",
        "ambient without ka",
        "vec3 color = ka * ambient;",
        "vec3 color = ambient;",
    ),
    (
        "04_phong_illumination",
        "only the first light",
        "if (l >= count) break;",
        "if (l >= 1) break;",
    ),
    ("04_phong_illumination", "lights behind the surface", "if (NoL <= 0.0) continue;", ""),
    ("04_phong_illumination", "count ignored (all 8 slots lit)", "if (l >= count) break;", ""),
    ("04_phong_illumination", "N.V for N.L (L and V swapped)", "kd * NoL", "kd * dot(N, V)"),
    ("05_ward", "alpha_x and alpha_y swapped", "dot(H, X) / alpha_x", "dot(H, X) / alpha_y"),
    ("05_ward", "missing sqrt", "sqrt(NoL * NoV)", "(NoL * NoV)"),
    ("05_ward", "missing pi", "4.0 * PI * alpha_x", "4.0 * alpha_x"),
    ("05_ward", "alpha not squared", "sqr(dot(H, X) / alpha_x)", "sqr(dot(H, X)) / alpha_x"),
    (
        "06_microfacet_distributions",
        "Beckmann normalised with pi",
        "(4.0 * m2 * c2 * c2)",
        "(PI * m2 * c2 * c2)",
    ),
    ("06_microfacet_distributions", "m not squared", "/ m2)", "/ m)"),
    (
        "06_microfacet_distributions",
        "Blinn exponent sign",
        "log(2.0) / -log(cos(beta))",
        "log(2.0) / log(cos(beta))",
    ),
    ("06_microfacet_distributions", "Blinn not normalised", "(e + 2.0) / 8.0 *", ""),
    (
        "06_microfacet_distributions",
        "Gaussian with sqrt(2)/beta",
        "exp(-log(2.0) * sqr(alpha / beta))",
        "exp(-2.0 * sqr(alpha / beta))",
    ),
    (
        "06_microfacet_distributions",
        "Gaussian normaliser by a coarse midpoint rule over [0, pi/2]",
        "float top = min(0.5 * PI, 6.0 * beta);",
        "float top = 0.5 * PI;",
    ),
    (
        "06_microfacet_distributions",
        "degrees for radians",
        "float alpha = angle_from_cos(NoH);",
        "float alpha = degrees(angle_from_cos(NoH));",
    ),
    (
        "07_geometric_attenuation",
        "G without its min with 1",
        "min(1.0, min(g * NoV, g * NoL))",
        "min(g * NoV, g * NoL)",
    ),
    (
        "07_geometric_attenuation",
        "max of the two terms",
        "min(1.0, min(g * NoV, g * NoL))",
        "min(1.0, max(g * NoV, g * NoL))",
    ),
    ("07_geometric_attenuation", "factor 2 missing", "2.0 * NoH", "NoH"),
    (
        "07_geometric_attenuation",
        "N.H and V.H swapped",
        "2.0 * NoH / max(VoH, EPS)",
        "2.0 * VoH / max(NoH, EPS)",
    ),
    ("08_fresnel", "fourth power", "k2 * k2 * k", "k2 * k2"),
    ("08_fresnel", "missing (1 - f0)", "(vec3(1.0) - f0) *", ""),
    ("08_fresnel", "dielectric without 1/2", "0.5 * a * a", "a * a"),
    ("08_fresnel", "wrong g", "ior * ior - 1.0 + c * c", "ior * ior - c * c"),
    ("09_cook_torrance", "4 instead of pi", "(PI * NoL * NoV)", "(4.0 * NoL * NoV)"),
    ("09_cook_torrance", "diffuse without 1/pi", "kd * INV_PI +", "kd +"),
    ("09_cook_torrance", "Fresnel of N.V", "fresnel_F(VoH)", "fresnel_F(NoV)"),
    ("09_cook_torrance", "H not normalized", "normalize(L + V)", "(L + V)"),
    ("10_importance_sampling", "pdf without its Jacobian", "/ (4.0 * VoH)", ""),
    (
        "10_importance_sampling",
        "half vector left local",
        "return h.x * X + h.y * Y + h.z * N;",
        "return h;",
    ),
    (
        "10_importance_sampling",
        "no square root",
        "sqrt(max(1.0 - cos_t * cos_t, 0.0))",
        "(1.0 - cos_t * cos_t)",
    ),
]

REWRITES = [
    ("01_lambert", "albedo * INV_PI", "albedo / PI"),
    ("02_phong", "vec3 R = 2.0 * NoL * N - L;", "vec3 R = reflect(-L, N);"),
    ("03_blinn_phong", "normalize(L + V)", "(L + V) / length(L + V)"),
    (
        "04_phong_illumination",
        "for (int l = 0; l < 8; ++l) {\n        if (l >= count) break;",
        "for (int l = 0; l < count; ++l) {",
    ),
    (
        "05_ward",
        "-(sqr(dot(H, X) / alpha_x) + sqr(dot(H, Y) / alpha_y)) / (NoH * NoH)",
        "-(sqr(dot(H, X)) / (alpha_x * alpha_x) + sqr(dot(H, Y)) / (alpha_y * alpha_y)) / sqr(NoH)",
    ),
    (
        "06_microfacet_distributions",
        "exp(-tan2_from_cos(NoH) / m2)",
        "exp(min(1.0 - 1.0 / c2, 0.0) / m2)",
    ),
    ("07_geometric_attenuation", "min(1.0, min(g * NoV, g * NoL))", "min(1.0, g * min(NoV, NoL))"),
    ("08_fresnel", "k2 * k2 * k", "pow(k, 5.0)"),
    (
        "09_cook_torrance",
        "ks * F * (D * G / (PI * NoL * NoV))",
        "ks * F * D * G * INV_PI / (NoL * NoV)",
    ),
    ("10_importance_sampling", "pow(max(u.x, 1e-30)", "pow(max(1.0 - u.x, 1e-30)"),
]

HIDDEN_SEED = 7


def variant(tmp: Path, exercise, label: str, old: str, new: str) -> Path:
    text = exercise.solution.read_text(encoding="utf-8")
    assert old in text, f"{exercise.name}: {old!r} is not in the solution"
    path = (
        tmp / f"{exercise.name}-{label.replace(' ', '_').replace('/', '_')}" / exercise.student_file
    )
    path.parent.mkdir(parents=True)
    at = text.rfind(old)  # the code, not the header's formula, which comes first
    path.write_text(text[:at] + new + text[at + len(old) :], encoding="utf-8")
    return path


@pytest.fixture(scope="module")
def graded(tmp_path_factory) -> dict[tuple, Task]:
    """Every variant graded once: solution, stub, mistakes, rewrites, hidden mode."""
    tmp = tmp_path_factory.mktemp("variants")
    tasks: dict[tuple, Task] = {}
    for exercise in EXERCISES.values():
        tasks["solution", exercise.name] = Task(exercise, exercise.solution)
        tasks["stub", exercise.name] = Task(exercise, exercise.stub)
        tasks["hidden", exercise.name] = Task(exercise, exercise.solution, HIDDEN_SEED)
    for name, label, old, new in MISTAKES:
        tasks["mistake", name, label] = Task(
            EXERCISES[name], variant(tmp, EXERCISES[name], label, old, new)
        )
        if label in ("missing pi", "G without its min with 1"):
            tasks["hidden-mistake", name, label] = Task(
                EXERCISES[name], tasks["mistake", name, label].submission, HIDDEN_SEED
            )
    for number, (name, old, new) in enumerate(REWRITES):
        tasks["rewrite", name] = Task(
            EXERCISES[name], variant(tmp, EXERCISES[name], f"rw{number}", old, new)
        )
    with Pool(2, timeout=20.0) as pool:
        pool.run(list(tasks.values()))
    return tasks


def failures(task: Task) -> str:
    return "; ".join(f"{r.name}: {r.message}" for r in task.checks() if not r.passed)


@pytest.mark.parametrize("name", sorted(EXERCISES))
def test_solution_full_marks_and_stub_less(graded, name):
    solution = graded["solution", name]
    assert solution.score == solution.max_score > 0, failures(solution)
    assert graded["stub", name].score < solution.max_score
    hidden = graded["hidden", name]
    assert hidden.score == hidden.max_score, failures(hidden)


@pytest.mark.parametrize("name,label", [(m[0], m[1]) for m in MISTAKES])
def test_plausible_mistake_fails_a_check(graded, name, label):
    task = graded["mistake", name, label]
    assert len(task.results) == len(task.exercise.checks)
    assert task.score < task.max_score, f"{name} with '{label}' got full marks"
    if ("hidden-mistake", name, label) in graded:
        assert graded["hidden-mistake", name, label].score < task.max_score


@pytest.mark.parametrize("name", [r[0] for r in REWRITES])
def test_equivalent_rewrite_passes(graded, name):
    task = graded["rewrite", name]
    assert task.score == task.max_score, failures(task)


def test_every_exercise_has_the_files_of_its_handout():
    for exercise in EXERCISES.values():
        stub = exercise.stub.read_text(encoding="utf-8")
        assert "TODO" in stub and (exercise.folder / "README.md").is_file(), exercise.name
        assert exercise.solution.is_file() and "TODO" not in exercise.solution.read_text()
        assert exercise.max_points == 10
        kinds = {c.kind for c in exercise.checks}
        if exercise.estimator:  # the estimate itself (14): its renders
            assert kinds == {"ibl_render"}, exercise.name
        elif exercise.sampler_for:  # a sampler: its distribution, its pdf, its renders
            assert {"chi_square", "pdf_integral", "ibl_render"} <= kinds, exercise.name
        elif kinds == {"properties"}:  # tests of the models linked with them (11)
            assert len({c.options["target"] for c in exercise.checks}) >= 5, exercise.name
        elif kinds == {"sh"}:  # the harmonics and a lobe's coefficients (15)
            projected = {c.options["target"] for c in exercise.checks} - {""}
            assert len(projected) >= 2 and len(projected) < len(exercise.checks), exercise.name
        elif kinds == {"object"}:  # a spatially varying BRDF on the textured object (13)
            assert all(c.options["textures"] for c in exercise.checks), exercise.name
            assert len({c.options["shape"] for c in exercise.checks}) >= 2, exercise.name
        else:
            assert "probe" in kinds and "sphere" in kinds
        assert all(c.pairs >= 256 for c in exercise.checks if c.kind == "probe")


def test_regenerated_references_match_the_committed_ones(tmp_path):
    from lab.grading.checks import VALUES_FILE, read_png
    from lab.grading.references import make_references

    shutil.copytree(ROOT / "exercises", tmp_path / "exercises")
    shutil.copytree(ROOT / "solutions", tmp_path / "solutions")
    make_references(tmp_path / "exercises")
    for exercise in EXERCISES.values():
        mine = tmp_path / "exercises" / exercise.name / "references"
        with np.load(exercise.references / VALUES_FILE) as old, np.load(mine / VALUES_FILE) as new:
            assert sorted(old.files) == sorted(new.files)
            for key in old.files:
                np.testing.assert_allclose(new[key], old[key], rtol=1e-4, atol=1e-6, err_msg=key)
        for check in exercise.checks:
            if check.kind in ("sphere", "object"):
                old_image = read_png(exercise.references / f"{check.name}.png").astype(int)
                new_image = read_png(mine / f"{check.name}.png").astype(int)
                assert np.abs(old_image - new_image).max() <= 1, check.name


def test_solutions_pass_on_softpipe(tmp_path):
    """A second rasterizer (Mesa softpipe) against the llvmpipe references."""
    env = {**os.environ, "GALLIUM_DRIVER": "softpipe"}
    probe = subprocess.run(
        [
            sys.executable,
            "-c",
            "from lab.gl import get_context; print(get_context().info['GL_RENDERER'])",
        ],
        env=env,
        capture_output=True,
        text=True,
        check=True,
    )
    assert "softpipe" in probe.stdout
    out = tmp_path / "results.json"
    done = subprocess.run(
        [
            sys.executable,
            "-c",
            MAIN,
            "grade",
            str(ROOT / "exercises"),
            "--from",
            str(ROOT / "solutions"),
            "--json",
            str(out),
        ],
        env=env,
        capture_output=True,
        text=True,
        cwd=ROOT,
    )
    import json

    results = json.loads(out.read_text())
    failed = [t["name"] + ": " + t["output"] for t in results["tests"] if t["status"] != "passed"]
    assert done.returncode == 0 and not failed, failed
    assert results["score"] == 10 * len(EXERCISES)

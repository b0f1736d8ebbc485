"""Exercise 10 judged by statistics: over SEEDS hidden-mode settings the solution and every
correct sampler kept with it (solutions/10_importance_sampling/correct) score full marks and
the stub 0; samplers that do not importance-sample the lobe (inefficient/: uniform, cosine,
one that ignores ke) lose the render's points; and the false-fail rate of a correct program,
summed over the exercise's statistical checks, is below 1 in 10,000 grades.

Kept cheap for CI: no diagnosis; per setting and check only the render's reference (the
solution's estimator) is made, since the chi-square and pdf-integral verdicts rest on the
student's own sampler and pdf alone; the seeds are dealt out to worker processes (one
OpenGL context each), about 2.3 s of CPU per seed in all.
"""

from __future__ import annotations

import math
import multiprocessing
import os
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path
from statistics import NormalDist

import numpy as np
import pytest

from lab.grading import sampling
from lab.grading.checks import Grader, Submission, hidden_variant, prepare
from lab.grading.exercise import load_exercise
from lab.grading.kinds import kind_of
from lab.ibl import chisquare

ROOT = Path(__file__).resolve().parents[1]
EXERCISE = load_exercise(ROOT / "exercises" / "10_importance_sampling")
SOLVED = EXERCISE.solution.parent
SEEDS = 50
RATE = 1e-4  # the false-fail rate per grade the checks must stay below


@pytest.fixture(scope="module")
def grader(ctx) -> Grader:
    return Grader()  # no explainer: the diagnosis is not what is tested here


def ready(paths: dict[str, Path]) -> dict[str, Submission]:
    out = {}
    for name, path in paths.items():
        done = prepare(EXERCISE, path)
        assert not done.error, f"{name}: {done.error}"
        out[name] = done
    return out


def correct() -> dict[str, Path]:
    found = {f"correct/{p.stem}": p for p in sorted((SOLVED / "correct").glob("*.glsl"))}
    assert {"correct/one_minus_u", "correct/swapped_u", "correct/mixture"} <= set(found)
    return found


def results(grader: Grader, programs: dict[str, Submission], seed: int | None) -> dict:
    """{program: {check name: CheckResult}} at one setting (None: the committed one)."""
    out: dict[str, dict] = {name: {} for name in programs}
    solution = grader.solution_model(EXERCISE)
    for index, check in enumerate(EXERCISE.checks):
        live = seed is not None
        drawn = hidden_variant(check, solution, seed, index) if live else check
        needs = check.kind == "ibl_render" or not live  # only the render compares with it
        expected = grader.expected(EXERCISE, drawn, live=live) if needs else None
        for name, prog in programs.items():
            out[name][check.name] = grader.grade(
                EXERCISE, drawn, prog.model, prog.code, expected, live
            )
    return out


def summaries(seeds: list[int]) -> dict[int, dict]:
    """In a worker process (its own grader and context): {seed: {program: {check: (points,
    message, largest |z| of a render)}}} for the solution, the stub and the correct ones."""
    grader = Grader()
    programs = ready({"solution": EXERCISE.solution, "stub": EXERCISE.stub, **correct()})
    out = {}
    for seed in seeds:
        out[seed] = {
            name: {c: (r.points, r.message, r.extra.get("largest_z")) for c, r in checks.items()}
            for name, checks in results(grader, programs, seed).items()
        }
    return out


@pytest.fixture(scope="module")
def hidden(ctx) -> dict[int, dict]:
    """Every program's results at SEEDS hidden settings (the one costly part of this file),
    the seeds dealt out to as many workers as there are cores (at most 4)."""
    workers = max(1, min(4, os.cpu_count() or 1))
    deals = [list(range(1 + k, SEEDS + 1, workers)) for k in range(workers)]
    spawn = multiprocessing.get_context("spawn")  # a fresh OpenGL context in each worker
    with ProcessPoolExecutor(workers, mp_context=spawn) as pool:
        parts = list(pool.map(summaries, deals))
    out = {seed: setting for part in parts for seed, setting in part.items()}
    assert sorted(out) == list(range(1, SEEDS + 1))
    return out


def test_solution_and_correct_variants_score_full_and_the_stub_zero(hidden):
    full = EXERCISE.max_points
    for seed, setting in hidden.items():
        for name, checks in setting.items():
            points = sum(p for p, _, _ in checks.values())
            said = {check: message for check, (_, message, _) in checks.items()}
            assert points == (0 if name == "stub" else full), (seed, name, said)


def test_render_z_scores_of_correct_samplers_are_calibrated(hidden):
    """The render's bias test divides by the estimators' own noise: for correct samplers
    (unbiased, other random numbers than the reference's) its z-scores must look like a
    standard normal, or the stated alpha would not hold."""
    z = []
    for setting in hidden.values():
        for name, checks in setting.items():
            if name.startswith("correct/"):
                z.append(checks["ibl_render.grey_room"][2])
    z = np.array(z)
    # The largest of 9 |z| per render: for N(0, 1) its median is about 1.9, and it exceeds
    # 3.5 with probability 9 * 4.7e-4 = 0.4%.
    assert 1.4 < float(np.median(z)) < 2.5, np.median(z)
    assert (z > 3.5).mean() < 0.05, np.sort(z)[-5:]


@pytest.mark.parametrize("name", ["uniform", "cosine", "ignore_ke"])
def test_samplers_that_do_not_follow_the_lobe_lose_the_render(grader, name):
    """Unbiased samplers with exact pdfs pass the chi-square and the pdf integral, and lose
    the render's points, half the exercise's: at equal samples their error is more than
    twice the solution's."""
    programs = ready({name: SOLVED / "inefficient" / f"{name}.glsl"})
    for seed in (None, 7, 8):
        checks = results(grader, programs, seed)[name]
        render = checks.pop("ibl_render.grey_room")
        assert not render.passed and "× the solution's noise" in render.message, render.message
        assert "biased" not in render.message  # it converges to the right image
        assert all(r.passed for r in checks.values()), {n: r.message for n, r in checks.items()}
        assert sum(r.points for r in checks.values()) == EXERCISE.max_points / 2


def pearson_rejections(probabilities: np.ndarray, samples: int, level: float, draws: int):
    """The share of `draws` multinomial samples from the exact bin probabilities that the
    pooled Pearson test (chisquare.pearson) rejects at `level`: the chi-square
    approximation's own error, with no sampler or quadrature in the way."""
    rng = np.random.default_rng(5)
    p = np.append(probabilities, max(1.0 - probabilities.sum(), 0.0))
    counts = rng.multinomial(samples, p / p.sum(), size=draws)
    expected = probabilities * samples
    missing = samples - expected.sum()
    rejected = 0
    for row in counts:
        rejected += chisquare.pearson(row[:-1], expected, row[-1], missing)[2] < level
    return rejected / draws


def test_false_fail_rate_of_a_correct_program_is_below_one_in_ten_thousand(grader):
    """The rate, by multiplicity, with each factor checked:

    - chi_square: a draw rejects a correct sampler with probability alpha (Šidák over
      views) if the chi-square approximation holds: checked by simulating the pooled test
      on exact multinomial counts at a check's hardest view (at most 1.5 alpha); a
      rejection within chance is drawn again, so the check fails with (1.5 alpha)^2, plus
      views x DECISIVE x 10 for a first draw so far out that no second is drawn;
    - pdf_integral: the failed share is within Z_INTEGRAL standard errors but for
      2 (1 - Phi(Z)) per view;
    - ibl_render: Bonferroni over its z-tests, alpha.
    """
    solution = grader.solution_model(EXERCISE)
    ibl = sampling.ibl_renderer(grader.renderer)
    rate, parts = 0.0, {}
    for check in EXERCISE.checks:
        o, kind = check.options, kind_of(check)
        if check.kind == "chi_square":
            views = kind.views(check)
            level = chisquare.sidak(o["alpha"], len(views))
            theta, phi = views[1]  # the grazing view: bins of few samples, failed samples
            frame = chisquare.random_frame(check.seed * 31 + 1)
            probabilities = chisquare.bin_probabilities(
                ibl, solution, check.params, chisquare.view_direction(theta, phi), frame=frame
            ).ravel()
            draws = 20_000
            seen = pearson_rejections(probabilities, o["samples"], level, draws)
            assert seen <= 1.5 * level + 3 * math.sqrt(level / draws), (check.name, seen, level)
            parts[check.name] = (1.5 * o["alpha"]) ** 2 + len(views) * sampling.DECISIVE * 10
        elif check.kind == "pdf_integral":
            tail = 2.0 * (1.0 - NormalDist().cdf(sampling.Z_INTEGRAL))
            parts[check.name] = len(kind.views(check)) * tail
        elif check.kind == "ibl_render":
            parts[check.name] = o["alpha"]
        rate += parts.get(check.name, 0.0)
    print(f"false-fail rate of a correct program per grade: {rate:.2g} ({parts})")
    assert set(parts) == {c.name for c in EXERCISE.checks}  # every check is statistical
    assert rate < RATE


def test_no_bias_the_checks_could_see_at_twenty_times_their_samples(grader):
    """The chi-square's pdf side is a quadrature: pooled with the failed samples, its
    missing mass once read as phantom failures (p = 1e-41 at ke = 200). At 2,000,000
    samples, twenty times a check's, the solution at a sharp lobe and a grazing view passes."""
    solution = grader.solution_model(EXERCISE)
    ibl = sampling.ibl_renderer(grader.renderer)
    params = {"kd": (0.0, 0.0, 0.0), "ks": (1.0, 1.0, 1.0), "ke": 200.0}
    for theta in (10.0, 70.0):
        V, frame = chisquare.view_direction(theta, 40.0), chisquare.random_frame(77)
        expected = chisquare.bin_probabilities(ibl, solution, params, V, frame=frame).ravel()
        observed, failed, n = np.zeros(expected.size), 0.0, 0
        for k in range(20):
            out = ibl.brdf_samples(solution, params, np.repeat(V[None], 100_000, 0), 90 + k, frame)
            valid = out[:, 3] > 0.0
            observed += chisquare.histogram(out[valid, :3]).ravel()
            failed, n = failed + float((~valid).sum()), n + len(out)
        p = chisquare.pearson(observed, expected * n, failed, n - expected.sum() * n)[2]
        assert p > 1e-3, (theta, p)

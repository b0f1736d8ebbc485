"""Grading speed: latency of one exercise in a fresh process, and grade-all throughput."""

from __future__ import annotations

import os
import random
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from lab.grading.exercise import find_exercises

ROOT = Path(__file__).resolve().parents[2]
MAIN = "import sys; from lab.cli import main; sys.exit(main(sys.argv[1:]))"
BARE = "import moderngl; moderngl.create_context(standalone=True, backend='egl')"

# Wrong answers a student might hand in, as (text in the solution, replacement).
WRONG = [("INV_PI", "1.0"), ("normalize(L + V)", "(L + V)"), ("NoL", "NoV"), ("0.5", "0.25")]
BROKEN = ["", "vec3 BRDF(vec3 L) { return L }\n", "// @model x\nfloat f() { return 1.0; }\n"]


def _cpu() -> float:
    """CPU seconds (user + system) of the finished child processes so far."""
    import resource

    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def _run(command: list[str]) -> tuple[float, float]:
    """(wall seconds, CPU seconds of the command and all its processes)."""
    cpu, start = _cpu(), time.perf_counter()
    subprocess.run(command, cwd=ROOT, capture_output=True, check=False)
    return time.perf_counter() - start, _cpu() - cpu


def _seconds(command: list[str], repeat: int) -> tuple[float, float, float]:
    """Median and best wall seconds, and median CPU seconds, of `repeat` runs (the machine
    is shared: the best run is the least disturbed, the CPU time the least noisy)."""
    runs = [_run(command) for _ in range(repeat)]
    walls = [w for w, _ in runs]
    return statistics.median(walls), min(walls), statistics.median(c for _, c in runs)


def chosen_exercises(names: str = "") -> list:
    """The shipped exercises whose names start with one of the comma-separated `names`
    (all of them when empty)."""
    every = find_exercises(ROOT / "exercises")
    wanted = [n.strip() for n in names.split(",") if n.strip()]
    chosen = [e for e in every if not wanted or any(e.name.startswith(w) for w in wanted)]
    if not chosen:
        raise SystemExit(f"grade-bench: no exercise starts with {names!r}")
    return chosen


def make_class(
    folder: Path, students: int, seed: int = 1, exercises: list | None = None
) -> dict[str, int]:
    """Submissions for `students` students: about half correct, 30 % wrong, 20 % broken."""
    rng = random.Random(seed)
    counts = {"correct": 0, "wrong": 0, "broken": 0}
    exercises = exercises or find_exercises(ROOT / "exercises")
    for number in range(students):
        for exercise in exercises:
            text = exercise.solution.read_text(encoding="utf-8")
            roll = rng.random()
            if roll < 0.5:
                kind = "correct"
            elif roll < 0.8:
                old, new = rng.choice([w for w in WRONG if w[0] in text] or [("", "")])
                text, kind = text.replace(old, new) if old else text + "\n#error\n", "wrong"
            else:
                text, kind = rng.choice(BROKEN), "broken"
            counts[kind] += 1
            path = folder / f"student{number:03d}" / exercise.name / exercise.student_file
            path.parent.mkdir(parents=True, exist_ok=True)
            path.write_text(text, encoding="utf-8")
    return counts


def _wrongs(text: str) -> list[str]:
    """The solution with each of the WRONG edits (and two more) that applies to its code."""
    found = []
    for old, new in [*WRONG, ("4.0", "2.0"), ("2.0", "1.0")]:
        at = text.rfind(old)  # the code, not the header's formula
        if at >= 0:
            found.append(text[:at] + new + text[at + len(old) :])
    return found


def _best(grader, exercise, path: Path, seed: int | None, repeat: int) -> tuple[float, list]:
    """Seconds to grade, the best of a few (other processes share the CPUs), and results."""
    list(grader.run(exercise, path, seed))  # compiles, loads, caches
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        results = list(grader.run(exercise, path, seed))
        times.append(time.perf_counter() - start)
    return min(times), results


def diagnosis_cost(repeat: int = 5) -> list[tuple]:
    """Per exercise: seconds to grade a wrong file without and with the diagnosis (warm, as
    in a worker that has graded before) and in hidden mode without and with it (mistakes and
    mutants rendered live; also the first such grade, which compiles them)."""
    from lab.grading.checks import Grader
    from lab.grading.explain import Explainer

    plain = Grader()
    diagnosing = Grader()
    diagnosing.explainer = Explainer(diagnosing)
    figures = []
    folder = Path(tempfile.mkdtemp(prefix="brdf-diagnosis-bench-"))
    try:
        for exercise in find_exercises(ROOT / "exercises"):
            path = folder / exercise.name / exercise.student_file
            path.parent.mkdir(parents=True)
            for text in _wrongs(exercise.solution.read_text(encoding="utf-8")):
                path.write_text(text, encoding="utf-8")
                results = list(plain.run(exercise, path))
                # Wrong values, not a compile error (which has nothing to diagnose).
                if not all(r.passed for r in results) and not any(r.errors for r in results):
                    break
            else:
                continue

            plain_s, _ = _best(plain, exercise, path, None, repeat)
            diagnosed_s, results = _best(diagnosing, exercise, path, None, repeat)
            hidden_plain_s, _ = _best(plain, exercise, path, 7, repeat)
            # The first hidden grade compiles the live variants (once per worker).
            start = time.perf_counter()
            list(diagnosing.run(exercise, path, 7))
            cold_s = time.perf_counter() - start
            hidden_s, _ = _best(diagnosing, exercise, path, 7, repeat)
            failed = [r for r in results if not r.passed]
            said = sum(1 for r in failed if r.diagnosis)
            figures.append(
                (exercise.name, plain_s, diagnosed_s, hidden_plain_s, hidden_s, cold_s)
                + (len(failed), said)
            )
    finally:
        shutil.rmtree(folder, ignore_errors=True)
    return figures


# A model with a loop in every evaluation (a 24-term series), for the loop guard's cost.
LOOP_MODEL = """// @model series
// @param kd color 0.5 0.5 0.5 | albedo
vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {
    float x = max(dot(N, L), 0.0) * max(dot(N, V), 0.0), term = 1.0, sum = 0.0;
    for (int k = 1; k <= 24; k++) {
        sum += term;
        term *= x / float(k);
    }
    return kd * sum / (3.14159265 * 2.718281828);
}
"""


def loop_guard_cost(size: int = 512, repeat: int = 31) -> dict[str, tuple[float, float]]:
    """Per model (the series with its loop, phong without one), guarded and unguarded:
    (best wall ms, median CPU ms of all the driver's threads) per size² sphere. The two
    variants alternate, so a busy machine disturbs both alike."""
    from dataclasses import replace

    from lab.models import load_model, parse_model
    from lab.render import Renderer

    renderer = Renderer()
    figures = {}
    for name, model in (
        ("series", parse_model(LOOP_MODEL, ROOT / "series.glsl")),
        ("phong", load_model("phong")),
    ):
        variants = {"guarded": model, "bare": replace(model, loop_limit=0)}
        walls: dict[str, list[float]] = {k: [] for k in variants}
        cpus: dict[str, list[float]] = {k: [] for k in variants}
        for variant in variants.values():
            renderer.sphere(variant, size=size, readback=False)  # compile, warm up
        for _ in range(repeat):
            for key, variant in variants.items():
                wall, cpu = time.perf_counter(), time.process_time()
                renderer.sphere(variant, size=size, readback=False)
                walls[key].append(time.perf_counter() - wall)
                cpus[key].append(time.process_time() - cpu)
        for key in variants:
            figures[f"{name} {key}"] = (
                1000 * min(walls[key]),
                1000 * statistics.median(cpus[key]),
            )
    return figures


def similarity_seconds(students: int = 200, exercises: list | None = None) -> tuple[float, int]:
    """Seconds for the similarity report of a made-up class (texts only), and pairs listed."""
    from lab.grading import similarity

    exercises = exercises or find_exercises(ROOT / "exercises")
    folder = Path(tempfile.mkdtemp(prefix="brdf-similarity-bench-"))
    try:
        make_class(folder, students, exercises=exercises)
        start = time.perf_counter()
        files = {}
        for student in sorted(folder.iterdir()):
            files[student.name] = {
                e.name: ((student / e.name / e.student_file).read_text(encoding="utf-8"), None)
                for e in exercises
            }
        matches = similarity.compare_class(files, exercises)
        similarity.write_html(matches, folder / "similarity.html")
        return time.perf_counter() - start, len(matches)
    finally:
        shutil.rmtree(folder, ignore_errors=True)


def run(submissions: int = 200, workers: int = 2, repeat: int = 5, only: str = "") -> None:
    """Print the figures the issue asks for (the class: the exercises named by `only`)."""
    exercises = chosen_exercises(only)
    count = len(exercises)
    for name, plain, diagnosed, hidden_plain, hidden, cold, failed, said in diagnosis_cost():
        print(
            f"wrong {name:28s} {plain:5.3f} s, diagnosed {diagnosed:5.3f} s "
            f"({diagnosed - plain:+.3f} s, {said} of {failed} failed checks named), "
            f"hidden mode {hidden_plain:5.3f} s, diagnosed {hidden:5.3f} s "
            f"({hidden - hidden_plain:+.3f} s; first in a worker {cold:5.3f} s)"
        )
    lambert = ROOT / "exercises" / "01_lambert"
    solution = ROOT / "solutions" / "01_lambert" / "lambert.glsl"
    print(f"machine: {os.cpu_count()} cores, load average {os.getloadavg()[0]:.1f} (shared)")
    bare, bare_best, bare_cpu = _seconds([sys.executable, "-c", BARE], repeat)
    grade = [sys.executable, "-c", MAIN, "grade", str(lambert), "--submission", str(solution)]
    one, one_best, one_cpu = _seconds(grade, repeat)
    every, _, every_cpu = _seconds(
        [*grade[:4], str(ROOT / "exercises"), "--from", str(ROOT / "solutions")], 3
    )
    print(
        f"bare python + moderngl context:       median {bare:6.3f} s, best {bare_best:6.3f} s, "
        f"CPU {bare_cpu:.3f} s"
    )
    print(
        f"grade one exercise (01_lambert):      median {one:6.3f} s (+{one - bare:.3f} s), "
        f"best {one_best:6.3f} s (+{one_best - bare_best:.3f} s), "
        f"CPU {one_cpu:.3f} s (+{one_cpu - bare_cpu:.3f} s)"
    )
    print(
        f"grade every exercise of one student:  median {every:6.3f} s (+{every - bare:.3f} s), "
        f"CPU {every_cpu:.3f} s"
    )
    guard = loop_guard_cost()
    for name, what in (("series", "a 24-step loop"), ("phong", "phong (no loop)")):
        (wall, cpu), (wall0, cpu0) = guard[f"{name} guarded"], guard[f"{name} bare"]
        print(
            f"loop guard, 512² sphere, {what}: best {wall:.2f} ms vs {wall0:.2f} ms unguarded "
            f"({100 * (wall / wall0 - 1):+.1f}%), CPU {cpu:.2f} ms vs {cpu0:.2f} ms "
            f"({100 * (cpu / cpu0 - 1):+.1f}%)"
        )
    seconds, pairs = similarity_seconds(200, exercises)
    print(
        f"similarity report, 200 students x {count} exercises (texts): {seconds:.1f} s, "
        f"{pairs} pairs"
    )
    folder = Path(tempfile.mkdtemp(prefix="brdf-grade-bench-"))
    try:
        counts = make_class(folder / "class", submissions, exercises=exercises)
        for exercise in exercises:  # grade-all grades every exercise in its --exercises
            shutil.copytree(exercise.folder, folder / "exercises" / exercise.name)
            solved = exercise.solution.parent  # the solutions/ beside it, as in the repository
            shutil.copytree(solved, folder / "solutions" / solved.name)
        cpu, start = _cpu(), time.perf_counter()
        subprocess.run(
            [
                sys.executable,
                "-c",
                MAIN,
                "grade-all",
                str(folder / "class"),
                "--exercises",
                str(folder / "exercises"),
                "--out",
                str(folder / "grades"),
                "--workers",
                str(workers),
                "--similarity",
            ],
            cwd=ROOT,
            capture_output=True,
            check=False,
        )
        seconds, cpu = time.perf_counter() - start, _cpu() - cpu
        gradebook = (folder / "grades" / "gradebook.csv").read_text().splitlines()
    finally:
        shutil.rmtree(folder, ignore_errors=True)
    n = submissions * count
    print(
        f"grade-all {submissions} students x {count} exercises ({counts['correct']} correct, "
        f"{counts['wrong']} wrong, {counts['broken']} broken files), {workers} workers: "
        f"{seconds:.1f} s ({n / seconds:.1f} files/s), CPU {cpu:.1f} s "
        f"({1000 * cpu / n:.0f} ms per file; {cpu / workers:.1f} s of wall on {workers} idle "
        f"cores); gradebook rows: {len(gradebook) - 1}"
    )

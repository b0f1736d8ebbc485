"""Sub-commands of the auto-grader: grade, grade-all, gradescope-zip, grade-bench."""

from __future__ import annotations

import os
import time
from pathlib import Path

from lab.errors import UsageError


def _exercises(paths: list[str]):
    """The exercises under `paths`, each validated with its mistakes.toml (UsageError)."""
    from lab.grading import mistakes
    from lab.grading.exercise import ExerciseError, find_exercises
    from lab.grading.installed import resolve

    found = []
    try:
        for path in paths:
            found += find_exercises(resolve(path))
        for exercise in found:
            mistakes.validate(exercise)
    except ExerciseError as err:
        raise UsageError(str(err)) from None
    return found


def locate(student: Path, exercise) -> Path:
    """A student's file for an exercise: NN_topic/FILE, exercises/NN_topic/FILE or FILE,
    else the one file of that name anywhere in the student's folder (an upload that kept
    its own folder, lab1/FILE), links not followed."""
    candidates = [
        student / exercise.name / exercise.student_file,
        student / "exercises" / exercise.name / exercise.student_file,
        student / exercise.student_file,
    ]
    for candidate in candidates:
        try:
            if candidate.exists() or candidate.is_symlink():
                return candidate
        except OSError:  # a name too long for the file system: the read will say so
            continue
    found = _anywhere(student, exercise.student_file)
    return found[0] if len(found) == 1 else candidates[-1]


def _anywhere(student: Path, name: str, limit: int = 2000) -> list[Path]:
    """Files called `name` below `student` (links not followed; at most `limit` entries
    looked at, so a huge upload costs nothing)."""
    import os

    found, seen = [], 0
    for folder, dirs, files in os.walk(student, followlinks=False):
        dirs[:] = [d for d in dirs if not d.startswith((".", "__MACOSX"))]
        seen += len(files) + len(dirs)
        if name in files:
            found.append(Path(folder) / name)
        if seen > limit:
            break
    return found


def _output(path: str | None) -> Path | None:
    """A result file we can write, checked before any grading starts."""
    from lab.errors import check_output

    return None if path is None else check_output(path)


def cmd_grade(args) -> int:
    try:
        return _grade(args)
    except UsageError as err:
        _write_error_results(args, str(err))
        raise


def _write_error_results(args, message: str) -> None:
    """Even a usage error leaves result files, so Gradescope and Classroom show the reason."""
    import json

    results = {
        "json": {"score": 0.0, "execution_time": 0.0, "output": message, "tests": []},
        "classroom": {"version": 1, "status": "error", "max_score": 0, "tests": []},
    }
    for key, data in results.items():
        path = getattr(args, key, None)
        if path and Path(path).parent.is_dir() and not Path(path).is_dir():
            Path(path).write_text(json.dumps(data, indent=2) + "\n", encoding="utf-8")


def _grade(args) -> int:
    from lab.grading.runner import Pool

    if args.make_references:
        from lab.grading.exercise import ExerciseError
        from lab.grading.installed import resolve
        from lab.grading.references import make_references

        _exercises(args.exercise)
        try:
            for path in args.exercise:
                for written in make_references(resolve(path)):
                    print(f"wrote {written}")
        except ExerciseError as err:
            raise UsageError(str(err)) from None
        return 0
    # The worker starts first: it loads numpy and OpenGL and makes its context while this
    # process reads the exercises and the report code (one exercise: latency is the point).
    with Pool(1, args.timeout) as pool:
        return _grade_with(pool, args)


def _grade_with(pool, args) -> int:
    from lab.grading.runner import Task

    exercises = _exercises(args.exercise)
    if args.submission and len(exercises) != 1:
        raise UsageError("--submission grades one exercise: give one EXERCISE_DIR (or use --from)")
    missing = [e for e in exercises if not e.solution.is_file()] if args.seed is not None else []
    if missing:
        raise UsageError(seed_needs(missing[0]))
    outputs = {k: _output(getattr(args, k)) for k in ("json", "html", "classroom")}
    tasks = []
    for exercise in exercises:
        root = None
        if args.submission:
            submission = Path(args.submission)
        elif args.from_dir:
            root = Path(args.from_dir)
            submission = locate(root, exercise)
        else:
            submission = exercise.stub
        tasks.append(Task(exercise, submission, args.seed, root=root))
    start = time.monotonic()
    pool.run(tasks, meanwhile=_load_report)  # the report code loads while the worker grades
    seconds = time.monotonic() - start
    from lab.grading import report

    report.terminal(tasks)
    if outputs["json"]:
        report.write_json(report.gradescope(tasks, seconds), outputs["json"])
    if outputs["html"]:
        outputs["html"].write_text(report.html_report(tasks), encoding="utf-8")
    result = report.classroom(tasks)
    if outputs["classroom"]:
        report.write_json(result, outputs["classroom"])
    report.write_github_output(result)
    return 0 if all(t.passed for t in tasks) else 1


def seed_needs(exercise) -> str:
    """Why --seed cannot grade `exercise` here, and what works instead."""
    from lab.resources import data_dir

    shipped = exercise.folder.resolve().parent == data_dir("exercises").resolve()
    return (
        f"--seed (hidden mode) renders the solutions live, with random parameters, and "
        f"{exercise.solution} is not there: an install of brdf-lab carries no solutions "
        "(students must not read them); they come with a clone, the sdist or the course's "
        "definitions archive, as solutions/NN_topic beside exercises/NN_topic (instructors: "
        "brdf-lab grade DEFS/exercises/NN_topic --from STUDENT_DIR --seed N). Without --seed "
        "the grader runs in practice mode against the committed references: brdf-lab grade "
        f"{exercise.name if shipped else exercise.folder} --submission YOUR_FILE"
    )


def _load_report() -> None:
    import lab.grading.report  # noqa: F401


def cmd_grade_all(args) -> int:
    from rich.progress import Progress

    from lab.grading import report
    from lab.grading.runner import Pool, Task
    from lab.grading.students import file_stem, find_students, printable

    root = Path(args.submissions)
    if not root.is_dir():
        raise UsageError(f"{root}: not a folder (give one sub-folder per student)")
    exercises = _exercises(args.exercises)
    students = find_students(root)
    if not students:
        raise UsageError(f"{root}: no student sub-folders in it")
    out = Path(args.out)
    try:
        (out / "reports").mkdir(parents=True, exist_ok=True)
    except OSError as err:
        raise UsageError(f"cannot create {out}: {err.strerror}") from None
    tasks: dict[str, list[Task]] = {}
    owner: dict[str, str] = {}
    for number, student in enumerate(students):
        if student.refused:
            print(f"not graded: {printable(student.name)}: {student.refused}")
            tasks[student.name] = [
                refused_task(e, student.path, student.refused) for e in exercises
            ]
            continue
        mine = []
        for e in exercises:
            key = f"{number}/{e.name}"
            owner[key] = student.name
            mine.append(Task(e, locate(student.path, e), args.seed, key=key, root=student.path))
        tasks[student.name] = mine
    remaining = {name: len(ts) for name, ts in tasks.items()}
    start = time.monotonic()
    graded = [t for ts in tasks.values() for t in ts if t.key]

    def write_reports(student: str) -> None:
        mine = tasks[student]
        stem = out / "reports" / file_stem(student)
        try:  # one student's report never stops the class
            html = report.html_report(mine, f"Grading report: {printable(student)}")
            stem.with_suffix(".html").write_text(html, encoding="utf-8")
            report.write_json(
                report.gradescope(mine, sum(t.seconds for t in mine)), stem.with_suffix(".json")
            )
        except (OSError, ValueError) as err:
            print(f"could not write the report of {printable(student)}: {err}")

    for name, ts in tasks.items():
        if not any(t.key for t in ts):
            write_reports(name)
    with Progress() as progress, Pool(args.workers, args.timeout) as pool:
        bar = progress.add_task(f"grading {len(students)} students", total=len(graded))

        def done(task: Task) -> None:
            progress.advance(bar)
            student = owner[task.key]
            remaining[student] -= 1
            if remaining[student] == 0:  # write as we go: a long run leaves partial results
                write_reports(student)

        pool.run(graded, done)
    seconds = time.monotonic() - start
    report.gradebook(list(tasks.items()), [e.name for e in exercises], out / "gradebook.csv")
    if args.similarity:
        similarity_report(tasks, exercises, out)
    full = sum(1 for ts in tasks.values() if all(t.passed for t in ts))
    print(
        f"graded {len(students)} students x {len(exercises)} exercises in {seconds:.1f} s; "
        f"{full} with full marks; wrote {out / 'gradebook.csv'} and {out / 'reports'}/ "
        "(report files are named slug-hash; the gradebook's 'report' column names each)"
    )
    return 0 if full == len(students) else 1


def similarity_report(tasks: dict, exercises, out: Path) -> None:
    """similarity.html and similarity.csv in `out`: pairs of students, and students and the
    library, with much code in common or the same wrong values."""
    from lab.grading import similarity
    from lab.grading.exercise import SubmissionError, read_submission

    start = time.monotonic()
    files: dict[str, dict] = {}
    for student, mine in tasks.items():
        for task in mine:
            if not task.key:
                continue  # refused (a link): nothing of theirs to read
            try:  # the text the worker graded, read once (else, refused there: read here)
                text = task.text or read_submission(task.submission, task.root)
            except SubmissionError:
                continue
            files.setdefault(student, {})[task.exercise.name] = (text, task)
    matches = similarity.compare_class(files, exercises)
    similarity.write_csv(matches, out / "similarity.csv")
    similarity.write_html(matches, out / "similarity.html")
    print(
        f"similarity: {len(matches)} pairs listed in {out / 'similarity.html'} "
        f"({time.monotonic() - start:.1f} s)"
    )


def refused_task(exercise, path: Path, why: str):
    """A task that is not graded: every check scores 0 with the reason."""
    from lab.grading.checks import CheckResult
    from lab.grading.runner import Task

    task = Task(exercise, path)
    for check in exercise.checks:
        task.results[check.name] = CheckResult(
            check.name, check.kind, check.points, status="error", message=why
        )
    return task


def cmd_gradescope_zip(args) -> int:
    from lab.grading.package import gradescope_zip

    exercises = _exercises(args.exercise)
    out = _output(args.output)
    wheel = Path(args.wheel) if args.wheel else None
    gradescope_zip(exercises, out, seed=args.seed, hidden=not args.reference_mode, wheel=wheel)
    print(f"wrote {out}: upload it as the autograder of a Gradescope programming assignment")
    return 0


def cmd_bench(args) -> int:
    from lab.grading import bench

    if not (bench.ROOT / "solutions").is_dir() or not (bench.ROOT / "exercises").is_dir():
        raise UsageError(
            "grade-bench grades a made-up class built from the solutions, which an install "
            "of brdf-lab does not carry (students must not read them): run it in a clone, "
            "python -m lab.cli grade-bench"
        )
    bench.run(submissions=args.submissions, workers=args.workers, only=args.exercises)
    return 0


def register(sub) -> None:
    workers = min(2, os.cpu_count() or 1)
    p = sub.add_parser(
        "grade",
        help="grade a student's shader against an exercise",
        epilog="exit status: 0 every check passed, 1 a check failed (a grade: the result "
        "files are written), 2 usage error (result files carry the reason), 3 internal error",
    )
    p.add_argument(
        "exercise",
        nargs="+",
        metavar="EXERCISE_DIR",
        help="exercise folder(s), a folder of them, or an installed exercise's number or "
        "name (02, phong)",
    )
    p.add_argument("--submission", metavar="FILE", help="the file to grade (default: the stub)")
    p.add_argument(
        "--from",
        dest="from_dir",
        metavar="DIR",
        help="find each exercise's file in DIR (NN_topic/FILE or FILE)",
    )
    p.add_argument("--json", metavar="results.json", help="write Gradescope results.json")
    p.add_argument("--html", metavar="report.html", help="write a self-contained HTML report")
    p.add_argument("--classroom", metavar="FILE", help="write the GitHub Classroom result JSON")
    p.add_argument("--seed", type=int, help="hidden mode: random parameters and lights")
    p.add_argument("--timeout", type=float, default=10.0, help="seconds per check (default 10)")
    p.add_argument(
        "--make-references",
        action="store_true",
        help="(instructor) render references/ from solutions/ and exit",
    )
    p.set_defaults(func=cmd_grade)

    p = sub.add_parser(
        "grade-all",
        help="grade a class: one sub-folder per student",
        epilog="exit status: 0 every student has full marks, 1 someone lacks some (the "
        "gradebook and reports are complete either way), 2 usage error",
    )
    p.add_argument("submissions", metavar="SUBMISSIONS_DIR")
    p.add_argument("--exercises", nargs="+", default=["exercises"], metavar="DIR")
    p.add_argument("--out", default="grades", help="folder for gradebook.csv and reports/")
    p.add_argument("--workers", type=int, default=workers, help=f"processes (default {workers})")
    p.add_argument("--seed", type=int, help="hidden mode: random parameters and lights")
    p.add_argument("--timeout", type=float, default=10.0, help="seconds per check (default 10)")
    p.add_argument(
        "--similarity",
        action="store_true",
        help="also write similarity.html/.csv: shared code between students and the library",
    )
    p.set_defaults(func=cmd_grade_all)

    p = sub.add_parser("gradescope-zip", help="build a Gradescope autograder zip")
    p.add_argument("exercise", nargs="+", metavar="EXERCISE_DIR")
    p.add_argument("-o", "--output", default="autograder.zip")
    p.add_argument(
        "--seed",
        type=int,
        help="one seed for every submission (default: each submission's own, from Gradescope)",
    )
    p.add_argument(
        "--reference-mode",
        action="store_true",
        help="grade against the committed references (practice; default: hidden mode)",
    )
    p.add_argument("--wheel", metavar="FILE.whl", help="the lab's wheel (default: build it)")
    p.set_defaults(func=cmd_gradescope_zip)

    p = sub.add_parser("grade-bench", help="grading latency and grade-all throughput")
    p.add_argument("--submissions", type=int, default=200, help="students in the made-up class")
    p.add_argument("--workers", type=int, default=workers)
    p.add_argument(
        "--exercises",
        default="",
        metavar="01,02,...",
        help="the class's exercises: names or their starts, comma-separated (default: all)",
    )
    p.set_defaults(func=cmd_bench)

    from lab.grading import authoring, installed

    authoring.register(sub)
    installed.register(sub)

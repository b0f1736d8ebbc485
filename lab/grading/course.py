"""A GitHub Classroom template repository: `brdf-lab course init DIR` and `course check DIR`.

The repository holds what students see: the chosen exercises (handout, stub, checks and
references for practice at home), a README, a .gitignore and the Classroom workflow. The
workflow grades with the course's own definitions, an archive pinned by its SHA-256 (by
default the sdist of this lab release, which carries exercises/ and solutions/), in hidden
mode seeded by the commit: editing the student's copy of the checks changes nothing.
"""

from __future__ import annotations

import hashlib
import io
import re
import shutil
from pathlib import Path

from lab import __version__
from lab.errors import UsageError
from lab.resources import data_dir

TEMPLATES = Path(__file__).resolve().parent / "templates"
WORKFLOW = Path(".github") / "workflows" / "classroom.yml"
PYPI_SDIST = "https://files.pythonhosted.org/packages/source/b/brdf-lab/brdf_lab-{v}.tar.gz"
OUTPUTS = ("classroom-result.json", "grading-report.html", "results.json")
GITIGNORE = """\
# brdf-lab: grading outputs and local environments
{outputs}
.venv/
__pycache__/
out/
.DS_Store
"""
README = """\
# {title}

Exercises of the BRDF lab. Each folder in `exercises/` holds a handout (`README.md`) and
the one GLSL file you edit. Push your work: GitHub grades every push (the Actions tab
shows the result; download `grading-report` for the details).

## Set-up on your computer

    python3 -m pip install "brdf-lab=={version}"

(in a virtual environment, or with `pipx install brdf-lab=={version}`). Then:

    brdf-lab watch exercises/{first}/{stub}    # live preview, reloads on save
    brdf-lab grade exercises/{first}             # check your work against the references

## How your work is graded

The grader on GitHub does not read the `exercise.toml` and `references/` in this
repository: it uses the course's own copy (the archive named in
`.github/workflows/classroom.yml`, checked against its SHA-256), and it grades in hidden
mode, with random parameters and lights chosen from your commit. Its log names the seed
N; to run the same checks at home, unpack that archive into a folder DEFS and run

    brdf-lab grade DEFS/exercises/NN_topic --from exercises --seed N

A file that passes with the references but fails with a seed has a mistake that only
shows for other parameter values.

Exercises: {names}.
"""


def _exercise_names(source: Path, wanted: list[str] | None) -> list[str]:
    """Folder names of the chosen exercises: all, or each matching a name or its NN prefix."""
    from lab.grading.exercise import ExerciseError, find_exercises

    try:
        available = [e.name for e in find_exercises(source)]
    except (ExerciseError, OSError) as err:
        raise UsageError(f"{source}: {err}") from None
    if not wanted:
        return available
    chosen = []
    for want in wanted:
        hits = [n for n in available if n == want or n.split("_")[0] == want]
        if len(hits) != 1:
            raise UsageError(
                f"--exercises {want!r} names no exercise in {source}: one of {', '.join(available)}"
            )
        chosen.append(hits[0])
    return chosen


def fetch(source: str) -> tuple[str, bytes]:
    """(URL for the workflow, bytes) of a definitions archive given as a URL or a path."""
    import urllib.error
    import urllib.request

    if "://" not in source:
        path = Path(source).resolve()
        if not path.is_file():
            raise UsageError(f"--definitions {source}: no such file")
        return path.as_uri(), path.read_bytes()
    try:
        with urllib.request.urlopen(source, timeout=60) as answer:
            return source, answer.read()
    except (urllib.error.URLError, OSError, ValueError) as err:
        raise UsageError(
            f"cannot download the definitions {source} ({err}): pass --definitions with the "
            "URL or path of an archive (.tar.gz) holding exercises/ and solutions/"
        ) from None


def archive_members(data: bytes) -> set[str]:
    """Paths inside a .tar.gz archive below its one top folder (tar --strip-components=1)."""
    import tarfile

    try:
        with tarfile.open(fileobj=io.BytesIO(data), mode="r:gz") as archive:
            names = archive.getnames()
    except (tarfile.TarError, OSError, EOFError) as err:
        raise UsageError(f"the definitions archive is not a .tar.gz file: {err}") from None
    return {n.split("/", 1)[1] for n in names if "/" in n}


def init(
    target: Path,
    exercises: list[str] | None = None,
    definitions: str | None = None,
    source: Path | None = None,
    title: str = "BRDF lab",
    published_url: str | None = None,
) -> list[str]:
    """Write the template repository into `target`; returns the exercise names."""
    from lab.grading.exercise import load_exercise

    source = source or data_dir("exercises")
    names = _exercise_names(source, exercises)
    if target.exists() and any(target.iterdir()):
        raise UsageError(f"{target} is not empty: give a new or empty folder")
    url, data = fetch(definitions or PYPI_SDIST.format(v=__version__))
    url = published_url or url
    members = archive_members(data)
    for name in names:
        exercise = load_exercise(source / name)
        for needed in (
            f"exercises/{name}/exercise.toml",
            f"solutions/{name}/{exercise.student_file}",
        ):
            if needed not in members:
                raise UsageError(
                    f"the definitions archive {url} lacks {needed}: the workflow grades from it"
                )
    for name in names:
        shutil.copytree(
            source / name, target / "exercises" / name, ignore=shutil.ignore_patterns("__pycache__")
        )
    workflow = (TEMPLATES / "classroom.yml").read_text(encoding="utf-8")
    for key, value in {
        "__LAB_VERSION__": __version__,
        "__DEFINITIONS_URL__": url,
        "__DEFINITIONS_SHA256__": hashlib.sha256(data).hexdigest(),
        "__EXERCISES__": " ".join(names),
    }.items():
        workflow = workflow.replace(key, value)
    (target / WORKFLOW).parent.mkdir(parents=True, exist_ok=True)
    (target / WORKFLOW).write_text(workflow, encoding="utf-8")
    first = load_exercise(source / names[0])
    (target / "README.md").write_text(
        README.format(
            title=title,
            version=__version__,
            first=first.name,
            stub=first.student_file,
            names=", ".join(names),
        ),
        encoding="utf-8",
    )
    (target / ".gitignore").write_text(
        GITIGNORE.format(outputs="\n".join(OUTPUTS)), encoding="utf-8"
    )
    return names


def workflow_settings(text: str) -> dict[str, str]:
    """The workflow's env: pins (BRDF_LAB_VERSION, DEFINITIONS_URL, ...)."""
    return dict(re.findall(r'^  ([A-Z_0-9]+): "([^"]*)"$', text, flags=re.M))


def check(target: Path) -> list[str]:
    """What is missing or wrong in a template repository (empty: complete)."""
    from lab.grading.exercise import ExerciseError, load_exercise

    problems = []
    for needed in ("README.md", ".gitignore", str(WORKFLOW)):
        if not (target / needed).is_file():
            problems.append(f"{needed} is missing ('brdf-lab course init' writes it)")
    if (target / "solutions").exists():
        problems.append("solutions/ is in the repository: students would see it; remove it")
    if (target / ".gitignore").is_file():
        ignored = (target / ".gitignore").read_text(encoding="utf-8").split()
        problems += [f".gitignore does not ignore {o}" for o in OUTPUTS if o not in ignored]
    if not (target / WORKFLOW).is_file():
        return problems
    text = (target / WORKFLOW).read_text(encoding="utf-8")
    env = workflow_settings(text)
    if re.search(r"__[A-Z0-9_]+__", text):
        problems.append(f"{WORKFLOW} still has template placeholders")
    if not re.fullmatch(r"\d+(\.\d+)*([a-z]+\d*)?", env.get("BRDF_LAB_VERSION", "")):
        problems.append(f"{WORKFLOW}: BRDF_LAB_VERSION does not pin a release")
    if not re.fullmatch(r"[0-9a-f]{64}", env.get("DEFINITIONS_SHA256", "")):
        problems.append(f"{WORKFLOW}: DEFINITIONS_SHA256 is not a SHA-256 checksum")
    if not env.get("DEFINITIONS_URL", "").startswith(("https://", "http://")):
        problems.append(
            f"{WORKFLOW}: DEFINITIONS_URL {env.get('DEFINITIONS_URL')!r} is not a web address "
            "GitHub's runners can download: publish the archive (e.g. as a release asset) "
            "and give its address with --definitions-url"
        )
    if "sha256sum -c" not in text or '--seed "$seed"' not in text:
        problems.append(f"{WORKFLOW} does not check the definitions or grade in hidden mode")
    names = env.get("EXERCISES", "").split()
    if not names:
        problems.append(f"{WORKFLOW}: EXERCISES lists no exercise")
    clone_solutions = data_dir("exercises").parent / "solutions"
    for name in names:
        folder = target / "exercises" / name
        try:
            exercise = load_exercise(folder)
        except (ExerciseError, OSError) as err:
            problems.append(f"exercises/{name}: {err}")
            continue
        for needed in ("README.md", exercise.student_file):
            if not (folder / needed).is_file():
                problems.append(f"exercises/{name}/{needed} is missing")
        solved = clone_solutions / name / exercise.student_file
        stub = folder / exercise.student_file
        if solved.is_file() and stub.is_file() and solved.read_bytes() == stub.read_bytes():
            problems.append(f"exercises/{name}/{exercise.student_file} is the solution")
    if (target / "exercises").is_dir():
        extra = sorted(p.name for p in (target / "exercises").iterdir() if p.name not in names)
        problems += [
            f"exercises/{n} is not graded: add it to EXERCISES in {WORKFLOW}" for n in extra
        ]
    return problems


def cmd_course(args) -> int:
    target = Path(args.dir)
    if args.action == "init":
        names = init(
            target, args.exercises, args.definitions, title=args.title, published_url=args.url
        )
        print(f"wrote the template repository {target} ({len(names)} exercises: {' '.join(names)})")
        print("push it to GitHub, mark it as a template and use it in a Classroom assignment")
        return 0
    if not target.is_dir():
        raise UsageError(f"{target}: no such folder")
    problems = check(target)
    for problem in problems:
        print(f"{target}: {problem}")
    if not problems:
        print(f"{target}: complete")
    return 1 if problems else 0


def register(subparsers) -> None:
    p = subparsers.add_parser("course", help="a GitHub Classroom template repository")
    actions = p.add_subparsers(dest="action", metavar="ACTION", required=True)
    init_parser = actions.add_parser("init", help="write a template repository for students")
    init_parser.add_argument("dir", metavar="DIR")
    init_parser.add_argument(
        "--exercises", nargs="+", metavar="NN", help="exercises to include (default: all)"
    )
    init_parser.add_argument(
        "--definitions",
        metavar="URL|FILE.tar.gz",
        help="the pinned archive the workflow grades with (default: this release's sdist on PyPI)",
    )
    init_parser.add_argument(
        "--definitions-url",
        dest="url",
        metavar="URL",
        help="where the workflow downloads the --definitions FILE from (its published copy)",
    )
    init_parser.add_argument("--title", default="BRDF lab", help="the README's title")
    init_parser.set_defaults(func=cmd_course)
    check_parser = actions.add_parser("check", help="verify that a template repository is complete")
    check_parser.add_argument("dir", metavar="DIR")
    check_parser.set_defaults(func=cmd_course)

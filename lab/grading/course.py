"""A GitHub Classroom template repository: `brdf-lab course pack`, `course init`, `course check`.

The repository holds what students see: the chosen exercises (handout, stub, checks and
references for practice at home), a README, a .gitignore and the Classroom workflow. The
workflow installs the grader from one pinned install line and grades with the course's
definitions (exercises/ and solutions/, built-in or the instructor's own), a private
archive read with a token from an Actions secret and checked against its SHA-256, in
hidden mode seeded by the commit: editing the student's copy of the checks changes nothing.
"""

from __future__ import annotations

import hashlib
import io
import os
import re
import shutil
import tarfile
import tempfile
from pathlib import Path

from lab.errors import UsageError
from lab.grading import sources
from lab.resources import data_dir

TEMPLATES = Path(__file__).resolve().parent / "templates"
WORKFLOW = Path(".github") / "workflows" / "classroom.yml"
OUTPUTS = ("classroom-result.json", "grading-report.html", "results.json")
GITIGNORE = """\
# brdf-lab: grading outputs and local environments
{outputs}
.venv/
__pycache__/
out/
.DS_Store
"""
HOW = "see the steps under 'GitHub Classroom' in brdf-lab's README"


# -- the definitions archive -----------------------------------------------------------------
def pack(out: Path, source: Path, wanted: list[str] | None = None) -> list[str]:
    """definitions.tar.gz from `source` (holding exercises/ and solutions/): every exercise
    validated, with its solution and rendered references; returns the exercise names."""
    from lab.grading import mistakes
    from lab.grading.exercise import ExerciseError, load_exercise

    names = _exercise_names(source / "exercises", wanted)
    for name in names:
        try:
            exercise = load_exercise(source / "exercises" / name)
            mistakes.validate(exercise)
        except ExerciseError as err:
            raise UsageError(str(err)) from None
        if not exercise.solution.is_file():
            raise UsageError(f"{exercise.solution} is missing: the grader renders it live")
        if not (exercise.references / "values.npz").is_file():
            raise UsageError(
                f"{exercise.references} has no references: run brdf-lab exercise check "
                f"{exercise.folder} first"
            )
    skip = shutil.ignore_patterns("__pycache__", "*.pyc", ".*")
    with tempfile.TemporaryDirectory() as tmp:
        top = Path(tmp) / "definitions"
        for name in names:
            for part in ("exercises", "solutions"):
                if (source / part / name).is_dir():
                    shutil.copytree(source / part / name, top / part / name, ignore=skip)
        with tarfile.open(out, "w:gz") as archive:
            archive.add(top, "definitions")
    return names


def unpack_definitions(data: bytes, into: Path) -> Path:
    """The archive's top folder, unpacked into `into` (safe paths only)."""
    try:
        with tarfile.open(fileobj=io.BytesIO(data), mode="r:gz") as archive:
            if hasattr(tarfile, "data_filter"):  # Python 3.10.12+, 3.11.4+
                archive.extractall(into, filter="data")
            else:  # pragma: no cover - older: refuse what the data filter would
                for member in archive.getmembers():
                    if member.name.startswith(("/", "..")) or ".." in Path(member.name).parts:
                        raise UsageError(f"the definitions archive holds {member.name!r}")
                    if not (member.isfile() or member.isdir()):
                        raise UsageError(f"the definitions archive holds a link {member.name!r}")
                archive.extractall(into)
    except (tarfile.TarError, OSError, EOFError) as err:
        raise UsageError(f"the definitions archive is not a .tar.gz file: {err}") from None
    tops = [p for p in into.iterdir() if p.is_dir()]
    if len(tops) != 1:
        raise UsageError("the definitions archive must hold one top folder (tar of a folder)")
    return tops[0]


def _exercise_names(source: Path, wanted: list[str] | None) -> list[str]:
    """Folder names of the chosen exercises: all, or each matching a name or its NN prefix."""
    from lab.grading.exercise import ExerciseError, find_exercises
    from lab.grading.installed import matches

    try:
        available = [e.folder for e in find_exercises(source)]
    except (ExerciseError, OSError) as err:
        raise UsageError(f"{source}: {err}") from None
    if not wanted:
        return [f.name for f in available]
    chosen = []
    for want in wanted:
        hits = matches(want, available)
        if len(hits) != 1:
            names = ", ".join(f.name for f in available)
            raise UsageError(f"--exercises {want!r} names no exercise in {source}: one of {names}")
        chosen.append(hits[0].name)
    return chosen


# -- course init --------------------------------------------------------------------------------
def init(
    target: Path,
    exercises: list[str] | None = None,
    definitions: str | None = None,
    title: str = "BRDF lab",
    published_url: str | None = None,
    install: str | None = None,
    secret: str = sources.TOKEN_SECRET,
) -> list[str]:
    """Write the template repository into `target`; returns the exercise names."""
    from lab.grading.exercise import load_exercise

    if target.exists() and any(target.iterdir()):
        raise UsageError(f"{target} is not empty: give a new or empty folder")
    if not definitions:
        raise UsageError(
            "course init needs the course's definitions (--definitions FILE|URL): a .tar.gz "
            "of exercises/ and solutions/, made with 'brdf-lab course pack definitions.tar.gz "
            f"--from DIR', kept private ({HOW})"
        )
    if not re.fullmatch(r"[A-Z_][A-Z0-9_]*", secret):
        raise UsageError(f"--token-secret {secret!r}: a secret's name is A-Z, 0-9 and _")
    line = sources.install_line(install)
    url, data = sources.fetch(definitions, os.environ.get(sources.TOKEN_SECRET))
    url = published_url or url
    with tempfile.TemporaryDirectory() as tmp:
        top = unpack_definitions(data, Path(tmp))
        if not (top / "exercises").is_dir():
            raise UsageError(
                f"the definitions archive {url} has no exercises/ in its top folder "
                f"{top.name}/: make it with 'brdf-lab course pack'"
            )
        names = _exercise_names(top / "exercises", exercises)
        for name in names:
            exercise = load_exercise(top / "exercises" / name)
            if not exercise.solution.is_file():
                raise UsageError(
                    f"the definitions archive {url} lacks solutions/{name}/"
                    f"{exercise.student_file}: the workflow grades with it"
                )
            shutil.copytree(
                top / "exercises" / name,
                target / "exercises" / name,
                ignore=shutil.ignore_patterns("__pycache__"),
            )
        first = load_exercise(target / "exercises" / names[0])
    workflow = (TEMPLATES / "classroom.yml").read_text(encoding="utf-8")
    for key, value in {
        "__INSTALL__": line,
        "__DEFINITIONS_URL__": url,
        "__DEFINITIONS_SHA256__": hashlib.sha256(data).hexdigest(),
        "__EXERCISES__": " ".join(names),
        "__TOKEN_SECRET__": secret,
    }.items():
        workflow = workflow.replace(key, value)
    (target / WORKFLOW).parent.mkdir(parents=True, exist_ok=True)
    (target / WORKFLOW).write_text(workflow, encoding="utf-8")
    readme = (TEMPLATES / "student_README.md").read_text(encoding="utf-8")
    (target / "README.md").write_text(
        readme.format(
            title=title,
            install=line,
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
    """The workflow's env: pins (BRDF_LAB_INSTALL, DEFINITIONS_URL, ...)."""
    return dict(re.findall(r'^  ([A-Z_0-9]+): "([^"]*)"$', text, flags=re.M))


def secret_name(text: str) -> str:
    found = re.search(r"DEFINITIONS_TOKEN: \$\{\{ secrets\.([A-Za-z0-9_]+) \}\}", text)
    return found.group(1) if found else ""


# -- course check -------------------------------------------------------------------------------
def check(target: Path, offline: bool = False) -> tuple[list[str], list[str]]:
    """(problems, notes) of a template repository: problems fail the check."""
    problems: list[str] = []
    notes: list[str] = []
    for needed in ("README.md", ".gitignore", str(WORKFLOW)):
        if not (target / needed).is_file():
            problems.append(f"{needed} is missing ('brdf-lab course init' writes it)")
    if (target / ".gitignore").is_file():
        ignored = (target / ".gitignore").read_text(encoding="utf-8").split()
        problems += [f".gitignore does not ignore {o}" for o in OUTPUTS if o not in ignored]
    if not (target / WORKFLOW).is_file():
        return problems + _leaks(target, [], None), notes
    text = (target / WORKFLOW).read_text(encoding="utf-8")
    env = workflow_settings(text)
    if re.search(r"__[A-Z0-9_]+__", text):
        problems.append(f"{WORKFLOW} still has template placeholders")
    problems += _install_problems(env.get("BRDF_LAB_INSTALL", ""), offline, notes)
    data = _definitions_problems(env, text, offline, problems, notes)
    if "sha256sum -c" not in text or '--seed "$seed"' not in text:
        problems.append(f"{WORKFLOW} does not check the definitions or grade in hidden mode")
    names = env.get("EXERCISES", "").split()
    if not names:
        problems.append(f"{WORKFLOW}: EXERCISES lists no exercise")
    readme = (target / "README.md").read_text("utf-8") if (target / "README.md").is_file() else ""
    url = env.get("DEFINITIONS_URL", "")
    if url and url in readme or re.search(r"(download|unpack)[^.]*definitions", readme, re.I):
        problems.append("README.md tells students where the definitions (solutions) are")
    problems += _leaks(target, names, data)
    return problems, notes


def _install_problems(line: str, offline: bool, notes: list[str]) -> list[str]:
    where = f"{WORKFLOW}: BRDF_LAB_INSTALL"
    if not line:
        return [f"{where} is missing: rerun course init with --install"]
    if sources.placeholder(line):
        return [f"{where} '{line}' has a placeholder ({sources.placeholder(line)})"]
    try:
        if sources.install_line(line) != line:
            raise UsageError("")
    except UsageError:
        return [f"{where} '{line}' pins no release: give a version, a wheel URL or git URL@tag"]
    if offline:
        notes.append(f"not checked (--offline): that '{line}' installs")
        return []
    problem = sources.install_problem(line)
    return [f"{where}: {problem}"] if problem else []


def _definitions_problems(env: dict, text: str, offline: bool, problems, notes) -> bytes | None:
    """Problems with the definitions' address, privacy and checksum; their bytes if read."""
    url = env.get("DEFINITIONS_URL", "")
    sha = env.get("DEFINITIONS_SHA256", "")
    if not re.fullmatch(r"[0-9a-f]{64}", sha):
        problems.append(f"{WORKFLOW}: DEFINITIONS_SHA256 is not a SHA-256 checksum")
    if not secret_name(text):
        problems.append(f"{WORKFLOW}: the download reads no token from an Actions secret")
    local = re.match(r"http://(127\.0\.0\.1|localhost)[:/]", url)  # a test's own server
    if sources.placeholder(url):
        problems.append(f"{WORKFLOW}: DEFINITIONS_URL {url!r} has a placeholder")
        return None
    if not (url.startswith("https://") or local):
        problems.append(
            f"{WORKFLOW}: DEFINITIONS_URL {url!r} is not a web address GitHub's runners can "
            f"download: publish the archive privately and give its address ({HOW})"
        )
        return None
    if offline:
        notes.append("not checked (--offline): that the definitions download, and are private")
        return None
    if sources.readable_without_token(url):
        problems.append(
            f"anyone can download {url}, solutions included: publish the definitions "
            f"privately and let the workflow read them with a token ({HOW})"
        )
    token = os.environ.get(sources.TOKEN_SECRET)
    if not token:
        problems.append(
            f"cannot check that the workflow can download {url}: set {sources.TOKEN_SECRET} "
            "to the token the Actions secret holds and run again (or pass --offline)"
        )
        return None
    try:
        _, data = sources.fetch(url, token)
    except UsageError as err:
        problems.append(str(err))
        return None
    if hashlib.sha256(data).hexdigest() != sha:
        problems.append(f"{url} is not the archive DEFINITIONS_SHA256 pins: rerun course init")
    return data


def _leaks(target: Path, names: list[str], data: bytes | None) -> list[str]:
    """Anything in the repository that hands students a solution or leaves an exercise
    ungraded (compared with the definitions' solutions where they were read)."""
    from lab.grading.exercise import ExerciseError, load_exercise

    problems = []
    if (target / "solutions").exists():
        problems.append("solutions/ is in the repository: students would see it; remove it")
    with tempfile.TemporaryDirectory() as tmp:
        solutions = data_dir("exercises").parent / "solutions"
        if data is not None:
            try:
                solutions = unpack_definitions(data, Path(tmp)) / "solutions"
            except UsageError as err:
                problems.append(str(err))
        solved = (
            {p.read_bytes() for p in solutions.glob("*/*.glsl")} if solutions.is_dir() else set()
        )
        for path in sorted(target.rglob("*.glsl")):
            if path.read_bytes() in solved:
                problems.append(f"{path.relative_to(target)} is a solution: remove it")
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
    if (target / "exercises").is_dir():
        extra = sorted(p.name for p in (target / "exercises").iterdir() if p.name not in names)
        problems += [
            f"exercises/{n} is not graded: add it to EXERCISES in {WORKFLOW}" for n in extra
        ]
    return problems


# -- the command line ---------------------------------------------------------------------------
def cmd_course(args) -> int:
    target = Path(args.dir)
    if args.action == "pack":
        source = Path(args.source) if args.source else data_dir("exercises").parent
        names = pack(target, source, args.exercises)
        print(f"wrote {target} ({len(names)} exercises with solutions: {' '.join(names)})")
        print(f"keep it private: a release asset of a private repository ({HOW})")
        return 0
    if args.action == "init":
        names = init(
            target,
            args.exercises,
            args.definitions,
            title=args.title,
            published_url=args.url,
            install=args.install,
            secret=args.token_secret,
        )
        print(f"wrote the template repository {target} ({len(names)} exercises: {' '.join(names)})")
        print("check it with 'brdf-lab course check DIR', push it to GitHub, mark it as a")
        print(f"template and use it in a Classroom assignment; the workflow reads the secret "
              f"{args.token_secret} ({HOW})")  # fmt: skip
        return 0
    if not target.is_dir():
        raise UsageError(f"{target}: no such folder")
    problems, notes = check(target, args.offline)
    for problem in problems:
        print(f"{target}: {problem}")
    for note in notes:
        print(f"{target}: note: {note}")
    if not problems:
        print(f"{target}: complete")
    return 1 if problems else 0


def register(subparsers) -> None:
    p = subparsers.add_parser("course", help="a GitHub Classroom template repository")
    actions = p.add_subparsers(dest="action", metavar="ACTION", required=True)
    pack_parser = actions.add_parser("pack", help="the private definitions archive of a course")
    pack_parser.add_argument("dir", metavar="OUT.tar.gz")
    pack_parser.add_argument(
        "--from", dest="source", metavar="DIR", help="folder with exercises/ and solutions/"
    )
    pack_parser.add_argument("--exercises", nargs="+", metavar="NN", help="default: all")
    pack_parser.set_defaults(func=cmd_course)
    init_parser = actions.add_parser("init", help="write a template repository for students")
    init_parser.add_argument("dir", metavar="DIR")
    init_parser.add_argument(
        "--exercises", nargs="+", metavar="NN", help="exercises to include (default: all)"
    )
    init_parser.add_argument(
        "--definitions",
        metavar="URL|FILE.tar.gz",
        help="the private archive the workflow grades with ('course pack' makes it); a URL is "
        f"read with the token in ${sources.TOKEN_SECRET}",
    )
    init_parser.add_argument(
        "--definitions-url",
        dest="url",
        metavar="URL",
        help="where the workflow downloads the --definitions FILE from (its private copy)",
    )
    init_parser.add_argument(
        "--install",
        metavar="VERSION|WHEEL_URL|GIT_URL@TAG",
        help=f"how the workflow installs the grader (default: {sources.default_install()})",
    )
    init_parser.add_argument(
        "--token-secret",
        default=sources.TOKEN_SECRET,
        metavar="NAME",
        help=f"the Actions secret holding the token (default {sources.TOKEN_SECRET})",
    )
    init_parser.add_argument("--title", default="BRDF lab", help="the README's title")
    init_parser.set_defaults(func=cmd_course)
    check_parser = actions.add_parser("check", help="verify that a template repository is complete")
    check_parser.add_argument("dir", metavar="DIR")
    check_parser.add_argument(
        "--offline", action="store_true", help="skip downloading the install and the definitions"
    )
    check_parser.set_defaults(func=cmd_course)

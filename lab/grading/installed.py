"""The exercises an install carries: `brdf-lab exercises list`, `exercises copy NN DIR`,
and the names `grade` accepts for them (`grade 02`, `grade phong`, `grade exercises/02_phong`
outside a clone).

A wheel keeps the exercises inside the package (lab.resources.data_dir), not where a
student works; `exercises copy` makes a working folder of them, as rustlings does.
"""

from __future__ import annotations

import shutil
from pathlib import Path

from lab.errors import UsageError
from lab.resources import data_dir, require_dir


def installed() -> list[Path]:
    """The folders of the exercises this lab carries, in order."""
    root = require_dir(data_dir("exercises"), "the exercises folder")
    return sorted(p.parent for p in root.glob("*/exercise.toml"))


def matches(name: str, folders: list[Path]) -> list[Path]:
    """Folders named `name`: in full (02_phong), by number (02, 2) or by topic (phong)."""
    name = name.strip().rstrip("/")
    hits = []
    for folder in folders:
        number, _, topic = folder.name.partition("_")
        if name in (folder.name, topic) or (
            name.isdigit() and number.isdigit() and int(name) == int(number)
        ):
            hits.append(folder)
    return hits


def resolve(argument: str) -> Path:
    """An exercise folder from what a user typed: an existing path as it is, else a folder
    of the working directory (or its exercises/) by name, number or topic, else one of the
    installed exercises so named (also `exercises/02_phong`, the README's form, outside a
    clone)."""
    path = Path(argument)
    if path.exists():
        return path
    if path.name == "exercises":  # the folder of them all, as in a clone
        return require_dir(data_dir("exercises"), "the exercises folder")
    # A student's working copy first (exercises copy NN .): `grade 02` in that folder
    # grades their file, not the untouched one of the install.
    here = [p.parent for top in (Path("."), Path("exercises")) for p in top.glob("*/exercise.toml")]
    local = matches(path.name, sorted(here)) if path.name and len(path.parts) == 1 else []
    if len(local) == 1:
        return local[0]
    folders = installed()
    hits = matches(path.name, folders) if path.name else []
    if len(hits) == 1:
        return hits[0]
    names = ", ".join(f.name for f in folders)
    if hits:
        raise UsageError(
            f"{argument!r} names several exercises ({', '.join(h.name for h in hits)})"
        )
    raise UsageError(
        f"{argument}: no such folder (so no exercise.toml), and no installed exercise is "
        f"called {path.name!r}; give an exercise folder, "
        f"or one of {names} (by number or topic: 02, phong); 'brdf-lab exercises list' shows them"
    )


def cmd_exercises(args) -> int:
    from lab.grading.exercise import ExerciseError, load_exercise

    folders = installed()
    if args.action == "list":
        print(f"exercises in {folders[0].parent if folders else data_dir('exercises')}:")
        for folder in folders:
            try:
                exercise = load_exercise(folder)
            except ExerciseError as err:
                print(f"  {folder.name:<30} (broken: {err})")
                continue
            print(
                f"  {folder.name:<30} {exercise.title}  [{exercise.student_file}, "
                f"{len(exercise.checks)} checks, {exercise.max_points:g} points]"
            )
        print("copy one to work on: brdf-lab exercises copy NN DIR (NN: its number, or 'all')")
        return 0
    chosen = folders if args.which == ["all"] else []
    for which in [] if chosen else args.which:
        hits = matches(which, folders)
        if len(hits) != 1:
            raise UsageError(
                f"{which!r} names no single installed exercise: one of "
                f"{', '.join(f.name for f in folders)} (or 'all')"
            )
        chosen += hits
    target = Path(args.dir)
    if target.exists() and not target.is_dir():
        raise UsageError(f"{target}: exists and is not a folder")
    for folder in chosen:
        if (target / folder.name).exists():
            raise UsageError(
                f"{target / folder.name} exists already: your work is kept; copy into "
                "another folder, or move that one away first"
            )
    for folder in chosen:
        shutil.copytree(folder, target / folder.name, ignore=shutil.ignore_patterns("__pycache__"))
        print(f"copied {folder.name} to {target / folder.name}")
    first = load_exercise(target / chosen[0].name)
    print(f"edit {first.stub}, then: brdf-lab watch {first.stub}")
    print(f"grade it: brdf-lab grade {first.folder}")
    return 0


def register(sub) -> None:
    p = sub.add_parser("exercises", help="list the exercises or copy them to work on")
    actions = p.add_subparsers(dest="action", metavar="ACTION", required=True)
    actions.add_parser("list", help="the installed exercises").set_defaults(func=cmd_exercises)
    c = actions.add_parser("copy", help="copy exercises into a working folder")
    c.add_argument("which", nargs="+", metavar="NN", help="numbers, names or topics, or 'all'")
    c.add_argument("dir", metavar="DIR", help="the working folder (made if missing)")
    c.set_defaults(func=cmd_exercises)

"""A class of submissions for grade-all: every entry listed, safe names for its files.

Whatever a student folder is called (long, unicode, a newline, a leading dash or dot)
it is graded and keeps its real name in the gradebook; the files written for it get a
short slug plus a hash, inside the output folder. A folder that is a link is listed
with the reason and no points: it could be another student's work or the solutions.
"""

from __future__ import annotations

import hashlib
import os
import re
from dataclasses import dataclass
from pathlib import Path

FORMULA_START = ("=", "+", "-", "@", "\t", "\r")  # OWASP's CSV-injection list


@dataclass
class Student:
    """One entry of the submissions folder; `refused` says why it is not graded."""

    name: str
    path: Path
    refused: str = ""


def find_students(root: Path) -> list[Student]:
    """Every entry of `root`, sorted by name: folders to grade, links and files refused."""
    students = []
    for entry in sorted(os.scandir(root), key=lambda e: e.name):
        path = Path(entry.path)
        if entry.is_symlink():
            try:
                target = os.readlink(path)
            except OSError:
                target = "?"
            why = f"the folder is a symbolic link (to {target}); links are not graded"
            students.append(Student(entry.name, path, why))
        elif entry.is_dir():
            students.append(Student(entry.name, path))
        else:
            why = "not a folder: each student's files go in a folder of their own"
            students.append(Student(entry.name, path, why))
    return students


def file_stem(name: str) -> str:
    """A file name for a student's reports: a short ASCII slug plus a hash of the real name,
    so that two names never share a file and no name can leave the output folder."""
    slug = re.sub(r"[^A-Za-z0-9_]+", "-", name).strip("-_")[:40] or "student"
    digest = hashlib.sha256(name.encode("utf-8", "surrogateescape")).hexdigest()[:10]
    return f"{slug}-{digest}"


def cell(text: str) -> str:
    """A spreadsheet cell that is never read as a formula (OWASP: prefix a quote)."""
    return "'" + text if text.startswith(FORMULA_START) else text


def printable(name: str) -> str:
    """The name for a terminal line: control characters shown as escapes."""
    return "".join(c if c.isprintable() else repr(c)[1:-1] for c in name)

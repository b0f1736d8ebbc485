"""Errors and input checks every front end shares (CLI, app, grader, web, measured).

This module sits at the bottom of the house: it imports nothing from the lab, so any
layer may raise these errors and the front ends decide how to show them.
"""

from __future__ import annotations

import math
from pathlib import Path


class UsageError(Exception):
    """Bad input from the user: printed as one line, exit status 2."""


def parse_pair(text: str, what: str) -> tuple[float, float]:
    try:
        first, second = (float(x) for x in text.split(","))
    except ValueError:
        raise UsageError(
            f"{what} {text!r} is malformed: write THETA,PHI in degrees, e.g. 30,0"
        ) from None
    return first, second


def parse_light(text: str) -> tuple[float, float]:
    theta, phi = parse_pair(text, "--light")
    if not 0.0 <= theta <= 90.0:
        raise UsageError(f"--light theta {theta:g} is outside 0..90 degrees")
    return theta, phi


def parse_rgb(text: str, what: str) -> tuple[float, float, float]:
    try:
        numbers = [float(x) for x in text.split(",")]
    except ValueError:
        numbers = []
    if len(numbers) == 1:
        numbers *= 3
    if len(numbers) != 3 or not all(math.isfinite(x) and x >= 0 for x in numbers):
        raise UsageError(f"{what} {text!r} is malformed: write R,G,B (or one grey value), >= 0")
    return tuple(numbers)


def check_output(path: str, suffix: str | None = None) -> Path:
    """A path we can write (with the given suffix, if any), or a UsageError saying why not."""
    out = Path(path)
    parent = out.parent if str(out.parent) else Path(".")
    if out.is_dir():
        raise UsageError(f"output {out} is a directory: give a file name")
    if suffix and out.suffix.lower() != suffix:
        raise UsageError(f"output {out} must end in {suffix} (the file is written as {suffix[1:]})")
    if not parent.is_dir():
        raise UsageError(f"cannot write {out}: folder {parent} does not exist")
    existed = out.exists()
    try:
        with open(out, "ab"):
            pass
    except OSError as err:
        raise UsageError(f"cannot write {out}: {err.strerror}") from None
    if not existed:
        out.unlink()  # only a probe: a failure later must not leave an empty file behind
    return out

"""A check as `exercise.toml` declares it, and the error for a broken exercise folder.

The bottom of the grading package: the check kinds (lab.grading.kinds) read these, and
lab.grading.exercise builds on them.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING

if TYPE_CHECKING:  # lab.render (numpy, moderngl) loads only where lights are read
    from lab.render import Light


class ExerciseError(ValueError):
    """A broken exercise folder (instructor side): a usage error."""


@dataclass
class Check:
    """One graded check of an exercise, as `exercise.toml` declares it."""

    name: str
    kind: str  # a registered check kind: probe | sphere | polar | ...
    points: float
    params: dict = field(default_factory=dict)
    view: str = "sphere"
    lights: list[Light] = field(default_factory=list)
    ambient: tuple[float, float, float] = (0.0, 0.0, 0.0)
    size: int = 128
    theta_i: float = 45.0
    phi_i: float = 0.0
    pairs: int = 256
    seed: int = 1
    rtol: float = 2e-3
    atol: float = 1e-4
    threshold: float = 5.0  # per channel, in 1/255 after tone mapping
    max_fraction: float = 0.001
    options: dict = field(default_factory=dict)  # the keys a kind adds (CheckKind.fields)


def parse_lights(raw, where: str) -> list[Light]:
    """[[theta, phi], [theta, phi, [r, g, b]], ...] from exercise.toml."""
    from lab.render import Light

    lights = []
    for item in raw:
        if not isinstance(item, list) or len(item) not in (2, 3):
            raise ExerciseError(f"{where}: each light is [theta, phi] or [theta, phi, [r, g, b]]")
        rgb = tuple(float(c) for c in item[2]) if len(item) == 3 else (1.0, 1.0, 1.0)
        lights.append(Light(float(item[0]), float(item[1]), rgb))
    return lights

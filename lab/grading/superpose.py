"""Light by light: a failed render with several lights (or an ambient light) is rendered
again, student's and solution's, with each light alone and with the ambient light alone.

Reflected radiance is linear in the lights (the reflection equation sums over them), so
the renders say which light the student's code mishandles (a light below the surface that
still adds its highlight, an ambient term added once per light), or, where each is right
alone, that the contributions do not add up. A fact about the values, never a guess at
the code: it is said beside the other evidence, not instead of it."""

from __future__ import annotations

from dataclasses import replace

from lab.grading.kinds import kind_of
from lab.grading.spec import Check, infer_purpose

DARK = (0.0, 0.0, 0.0)
WHERE = {  # a sphere light's angle from the view axis, in words (spec.PURPOSES)
    "front": "in front",
    "highlight": "in front",
    "grazing": "at grazing",
    "below": "just behind the horizon",
    "back": "behind the sphere",
}


def parts(check: Check) -> list[tuple[str, Check]]:
    """The check's renders with one light (or the ambient light) on: (label, check). The
    other lights stay in their places, switched off, so `count` is what it was."""
    lights = list(check.lights)
    ambient = any(c > 0.0 for c in check.ambient)
    if len(lights) + ambient < 2:
        return []
    off = [replace(light, rgb=DARK) for light in lights]
    out = []
    if ambient:
        out.append(("the ambient light alone", replace(check, lights=off)))
    for i, light in enumerate(lights):
        where = WHERE[infer_purpose(light.theta)]
        one = [light if j == i else dark for j, dark in enumerate(off)]
        out.append((f"light {i + 1} alone ({where})", replace(check, lights=one, ambient=DARK)))
    return out


def light_by_light(renderer, check: Check, mine, solution) -> str:
    """Which lights alone give the solution's picture and which do not, in words; '' when
    the check has one light, or every part is wrong alike (nothing is singled out)."""
    kind = kind_of(check)
    if kind.purpose_of != "lights":
        return ""
    wrong, right = [], []
    for label, part in parts(check):
        got = kind.stored(kind.render(renderer, mine, part), part)
        want = kind.stored(kind.render(renderer, solution, part), part)
        (wrong if kind.differs(part, got, want) else right).append(label)
    if not wrong and right:
        return (
            "light by light, each light alone and the ambient light alone give the "
            "solution's picture, but all together do not: the lights' contributions must "
            "add up (+=), each once, with the ambient term once"
        )
    if not wrong or not right:
        return ""
    others = "the other" if len(right) == 1 else f"the other {len(right)}"
    return (
        f"light by light, {_join(wrong)} {'differs' if len(wrong) == 1 else 'differ'} from "
        f"the solution's picture; {others} alone {'matches' if len(right) == 1 else 'match'}"
    )


def _join(items: list[str]) -> str:
    return items[0] if len(items) == 1 else ", ".join(items[:-1]) + " and " + items[-1]

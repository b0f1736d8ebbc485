"""How a student's function call differs from the solution's call in the same place, when
their arguments agree: another function (min where max belongs, sin for cos) or the same
function with its arguments the other way round (pow(ke, x) for pow(x, ke)).

Both are read from the traces (lab.grading.trace): a call's arguments are the values it
depends on, so "the arguments agree" is a comparison of values, not of names, and holds
however the student spelt them."""

from __future__ import annotations

import re

from lab.grading.relations import Quantity, matches
from lab.grading.trace import Point, Trace

CALL = re.compile(r"[A-Za-z_]\w*")  # a head that names a function, not an operator
# Constructors are conversions, not operations a slip would exchange.
CONSTRUCTORS = {"vec2", "vec3", "vec4", "float", "int", "bool", "mat2", "mat3", "mat4"}


def _is_call(point: Point) -> bool:
    return bool(CALL.fullmatch(point.head)) and point.head not in CONSTRUCTORS


def arguments(text: str, head: str) -> list[str] | None:
    """The argument texts of the first call of `head` in `text` (a statement or an
    expression), split at its top-level commas; None where there is no such call."""
    match = re.search(rf"\b{re.escape(head)}\s*\(", text)
    if match is None:
        return None
    depth, args, current = 1, [], ""
    for char in text[match.end() :]:
        if char == "(":
            depth += 1
        elif char == ")":
            depth -= 1
            if depth == 0:
                return args + [current.strip()]
        if char == "," and depth == 1:
            args.append(current.strip())
            current = ""
        else:
            current += char
    return None


def _literals(args: list[str]) -> list[float | None]:
    """Each argument's value where it is a number literal, else None."""
    out: list[float | None] = []
    for a in args:
        try:
            out.append(float(a.rstrip("fF")))
        except ValueError:
            out.append(None)
    return out


def _same_shape(p: Point, s: Point) -> bool:
    """The two calls take as many arguments, with the same number literals in the same
    places (min(x, 0.0) and max(x, 0.0); not acos(x) and clamp(x, 0.0, 1.0))."""
    mine, theirs = arguments(p.text, p.head), arguments(s.text, s.head)
    if mine is None or theirs is None or len(mine) != len(theirs):
        return False
    a, b = _literals(mine), _literals(theirs)
    pairs = zip(a, b, strict=True)
    return all((x is None) == (y is None) and (x is None or x == y) for x, y in pairs)


def _args_agree(student: Trace, mine: list[int], solution: Trace, theirs: list[int]) -> bool:
    """Do the student's argument values (slots, in order) match the solution's, one by one?"""
    if len(mine) != len(theirs) or not mine:
        return False
    for a, b in zip(mine, theirs, strict=True):
        v, r, _ = student.value(a)
        w, s, _ = solution.value(b)
        if not r.any() or not s.any() or not matches(v, r, Quantity("", w, s)):
            return False
    return True


def difference(p: Point, student: Trace, candidates: list[Point], solution: Trace) -> str:
    """'calls min where the solution calls max' or 'has the arguments of pow the other way
    round', for a call p whose arguments equal those of one of the solution's `candidates`
    (its points in the same part: the same variable, the same function's result); ''."""
    if not _is_call(p):
        return ""
    args = [d for d in p.deps if d not in p.partial]
    for s in candidates:
        if not _is_call(s):
            continue
        theirs = [d for d in s.deps if d not in s.partial]
        if not _same_shape(p, s):
            continue
        if s.head != p.head and _args_agree(student, args, solution, theirs):
            return f"calls {p.head}(…) where the solution calls {s.head}(…) with the same arguments"
        if (
            s.head == p.head
            and len(args) == 2
            and _args_agree(student, args[::-1], solution, theirs)
            and not _args_agree(student, args, solution, theirs)
        ):
            return f"has the two arguments of {p.head}(…) the other way round"
    return ""


def downstream(fault: Point, points: list[Point], good: dict[int, bool], limit: int = 6):
    """The values computed from the fault that are wrong too, in program order (at most
    `limit`): where a constant or a value the solution never names went wrong, what is
    computed from it may show how."""
    consumers: dict[int, list[Point]] = {}
    for p in points:
        for d in p.deps:
            consumers.setdefault(d, []).append(p)
    seen, order, frontier = {fault.slot}, [], [fault]
    while frontier and len(order) < limit:
        nxt = []
        for f in frontier:
            for c in consumers.get(f.slot, []):
                if c.slot not in seen and not good.get(c.slot, True):
                    seen.add(c.slot)
                    order.append(c)
                    nxt.append(c)
        frontier = nxt
    return sorted(order, key=lambda p: (p.line, p.start))[:limit]


def into_callee(fault: Point, faults: list[Point], points: list[Point], order) -> Point:
    """Where a faulty call's cause lies: a call of the student's own function whose arguments
    agree with the solution (`fault`, a fault only by its result) is followed into that
    function, to its first faulty value (`order` ranks faults as locate does), helper into
    helper; a value inside the helper that departs on its own is the slip, not the call.
    In a loop the values are its last pass's, where a helper's result may happen to agree
    (a Gaussian's tail is 0 either way): there the helpers called on the fault's line are
    followed too, when a value inside one of them departs from the solution's."""
    seen = {fault.slot}
    while True:
        heads = {fault.head} if _is_call(fault) else set()
        if fault.loop is not None:
            heads |= {p.head for p in points if p.line == fault.line and _is_call(p)}
        heads.discard(fault.function)  # a recursion GLSL forbids anyway
        inner = [p for p in faults if p.function in heads and p.slot not in seen]
        if not inner:
            return fault
        fault = min(inner, key=order)
        seen.add(fault.slot)

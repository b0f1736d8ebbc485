"""Where a wrong program first parts from the solution, and how, from both programs' traces.

Each value the student's code computes (lab.grading.trace) is matched by its values with
the solution's named quantities (its variables and subexpressions, such as N·H or
4·N·L·N·V). A value is right when it matches one, or when something computed from it
does (a helper value the solution never names). The first value that is not right while
everything it reads is right is the likely fault: its line is quoted, and where its
values stand in a simple relation to a solution quantity (opposite sign, a constant
factor, a power, a missing clamp, 1 − x, another direction's dot product) that relation
is said. Where none holds, only the line is named: the evidence does not show a cause.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field

import numpy as np

from lab.grading import calls
from lab.grading.compare import fmt_rgb
from lab.grading.mistakes import SPOKEN
from lab.grading.relations import (
    AGREE,
    MIN_ROWS,
    Matcher,
    Quantity,
    agree,
    matches,
    named_factor,
    relation,
    shared_rows,
    term,
    varies,
)
from lab.grading.trace import Point, Trace, geometry

EXIT_START = "your function differs from the solution's only where"
CHAIN = {"*": "product", "/": "product", "+": "sum", "-": "sum"}


@dataclass
class Finding:
    """The likely fault: the student's point, and the relation found (or '')."""

    point: Point
    statement: Point
    relation: str
    calls: list[Point] = field(default_factory=list)  # where a parameter's function is called
    through: Point | None = None  # a later value computed from the fault that shows how
    through_relation: str = ""  # ... in words (its relation to what it stands for)


def spoken(text: str) -> str:
    """Code as a hint reads it: NoH as N·H, INV_PI as 1/π."""
    return re.sub(r"\b(\w+)\b", lambda m: SPOKEN.get(m.group(1), m.group(1)), text)


def _plain(name: str) -> str:
    """A variable name reduced for comparison: NdotH, n_dot_h and NoH all read 'noh'."""
    return name.lower().replace("_", "").replace("dot", "o")


def quantities(trace: Trace) -> list[Quantity]:
    """The solution's traced values, with their names."""
    out = []
    for point in trace.traced.points:
        values, ran, _ = trace.value(point.slot)
        label = SPOKEN.get(point.name, point.name) if point.name else spoken(point.text)
        if point.statement and not point.name:
            label = spoken(point.text.removeprefix("return").strip().rstrip(";"))
        # what a named quantity is computed as: `vec3 H = normalize(L + V);` -> the right side
        text = spoken(point.text.split("=", 1)[1].strip().rstrip(";")) if "=" in point.text else ""
        out.append(Quantity(label, values, ran, point.name, text if point.name else ""))
    return out


def _good(
    points: list[Point],
    right: dict[int, bool],
    ran: dict[int, bool],
    telling: dict[int, bool],
) -> dict[int, bool]:
    """Right, or read by something good: a helper value the solution never names is good
    when what is computed from it matches (and changes with it: a constant, such as F = 1
    with Fresnel switched off, vouches for nothing it reads)."""
    consumers: dict[int, list[int]] = {}
    for p in points:
        for d in p.deps:
            if d not in p.partial:
                consumers.setdefault(d, []).append(p.slot)
    good: dict[int, bool] = {}
    for p in sorted(points, key=lambda p: -p.slot):
        good[p.slot] = (
            right[p.slot]
            or not ran[p.slot]
            or any(good.get(c, False) and telling[c] for c in consumers.get(p.slot, []))
        )
    return good


def locate(student: Trace, solution: Trace) -> Finding | None:
    """The student's first value that departs from every solution quantity while what it
    reads does not, with its relation to the quantity it most likely means; None when the
    results agree on these pairs or no such value stands out."""
    mine_f, mine_ran, _ = student.value(0)
    want_f, want_ran, _ = solution.value(0)
    both = mine_ran & want_ran
    if both.sum() < MIN_ROWS or agree(mine_f[both], want_f[both]).mean() >= AGREE:
        return None
    known = quantities(solution)
    matcher = Matcher(known)
    points = student.traced.points
    right, ran, values, telling = {}, {}, {}, {}
    for p in points:
        v, r, _ = student.value(p.slot)
        values[p.slot], ran[p.slot] = (v, r), bool(r.any())
        telling[p.slot] = ran[p.slot] and varies(v[r])
        if not ran[p.slot]:
            right[p.slot] = False
            continue
        hits = matcher.which(v, r)
        # A value kept under one of the solution's names (H) but equal to another of its
        # quantities (L + V) is no match: the name says what was meant.
        same_name = {
            i
            for i, q in enumerate(known)
            if p.name
            and q.name
            and _plain(q.name) == _plain(p.name)
            and shared_rows(r, q) is not None
        }
        # A function's result must match the solution's result of that function.
        results = {
            i
            for i, s in enumerate(solution.traced.points)
            if not p.name
            and p.statement
            and s.statement
            and not s.name
            and s.function == p.function
        }
        pool = results or set(range(len(known)))
        right[p.slot] = bool(hits & pool) and (not same_name or bool(hits & same_name))
    good = _good(points, right, ran, telling)
    faults = [
        p
        for p in points
        if ran[p.slot] and not good[p.slot] and all(good.get(d, True) for d in p.deps)
    ]
    if not faults:
        return None

    def order(p: Point) -> tuple:
        return (student.step(p.slot), p.line, p.start)

    fault = calls.into_callee(min(faults, key=order), faults, points, order)
    by_slot = {p.slot: p for p in points}
    # a * b * c is parsed (a * b) * c: a partial product the solution never forms is no
    # fault of its own, the whole chain is judged.
    while fault.head in CHAIN:
        parent = next(
            (
                p
                for p in points
                if fault.slot in p.deps
                and not p.statement
                and p.head in CHAIN
                and CHAIN[p.head] == CHAIN[fault.head]
                and p.line == fault.line
                and not good[p.slot]
            ),
            None,
        )
        if parent is None:
            break
        fault = parent
    statement = _statement_of(fault, points)
    # The fault itself, or else what is computed from it on the same line, may show a
    # relation to what was meant.
    chain, current = [fault], fault
    while True:
        parent = next(
            (
                p
                for p in points
                if current.slot in p.deps and p.line == fault.line and not good[p.slot]
            ),
            None,
        )
        if parent is None or parent in chain:
            break
        chain.append(parent)
        current = parent
    geo = _geometry(student)
    theirs = solution.traced.points
    for p in chain:
        v, r = values[p.slot]
        meant = _counterparts(p, statement, theirs, known)
        said = _describe(p, v, r, meant, known, geo)
        said = said or calls.difference(p, student, _parts(p, statement, theirs, False), solution)
        if said:
            return _with_calls(Finding(p, statement, said), points)
    found = Finding(fault, statement if statement is not None else by_slot[fault.slot], "")
    if not telling[fault.slot]:  # a wrong constant shows as a factor where it is used
        found.through, found.through_relation = _scaled_later(
            fault, points, good, values, theirs, known
        )
    return _with_calls(found, points)


def _scaled_later(fault: Point, points: list[Point], good, values, theirs, known):
    """The first later value computed from a wrong constant that is a named factor (2, π,
    1/2...) or the sign off what it stands for, with that relation; (None, '') if none.
    Only a factor: other effects of a constant (a lobe's shape) say nothing of its cause."""
    for d in calls.downstream(fault, points, good):
        if d.line == fault.line or d.loop is not None:
            continue
        v, r = values[d.slot]
        for q in _counterparts(d, _statement_of(d, points), theirs, known):
            joint = shared_rows(r, q) if q.values.shape[1] == v.shape[1] else None
            phrase = relation(v[joint], q.values[joint]) if joint is not None else ""
            if phrase.startswith("has the opposite sign") or named_factor(phrase):
                return d, phrase.format(q=q.label)
    return None, ""


def same_slip(student: Trace, mine: Finding, other: Trace, theirs: Finding) -> bool:
    """Is the student's first wrong value (or its statement's) the other program's first
    wrong value: the same slip, written another way?"""
    values, ran, _ = other.value(theirs.point.slot)
    if not ran.any() or not varies(values[ran]):
        return False  # a constant proves nothing
    wanted = Quantity(theirs.point.text, values, ran)
    for p in {mine.point.slot: mine.point, mine.statement.slot: mine.statement}.values():
        v, r, _ = student.value(p.slot)
        if matches(v, r, wanted):
            return True
    return False


def same_value(student: Trace, mine: Finding, other: Trace, theirs: Finding) -> bool:
    """Do the two faults' values agree: the student's first wrong value (or its
    statement's) with the other program's first wrong value (or its statement's)?"""
    for q in {theirs.point.slot: theirs.point, theirs.statement.slot: theirs.statement}.values():
        values, ran, _ = other.value(q.slot)
        if not ran.any():
            continue
        wanted = Quantity(q.text, values, ran)
        for p in {mine.point.slot: mine.point, mine.statement.slot: mine.statement}.values():
            v, r, _ = student.value(p.slot)
            if matches(v, r, wanted):
                return True
    return False


def target(finding: Finding) -> str:
    """What a fault is a fault in: the variable its line sets (by its plain name), else the
    function whose result it is."""
    statement = finding.statement or finding.point
    name = statement.name or finding.point.name
    return _plain(name) if name else f"{statement.function}()"


def _with_calls(finding: Finding, points: list[Point]) -> Finding:
    if finding.point.head == "parameter":
        finding.calls = [p for p in points if p.head == finding.point.function]
    return finding


def _geometry(trace: Trace) -> list[Quantity]:
    if not trace.directions:
        return []  # rows of normals or random numbers: no L and V to name
    rows = len(trace.angles)
    everywhere = np.ones(rows, bool)
    out = []
    for label, values in geometry(trace.angles).items():
        out.append(Quantity(label, values.reshape(rows, -1), everywhere))
    return out


def _counterparts(
    p: Point, statement: Point | None, solution: list[Point], known: list[Quantity]
) -> list[Quantity]:
    """The solution's quantities that play p's part: the variable of the same name, the
    same function's result, and within those the subexpressions of the same operation."""
    by_slot = {s.slot: q for s, q in zip(solution, known, strict=True)}
    return [by_slot[s.slot] for s in _parts(p, statement, solution)]


def _parts(
    p: Point, statement: Point | None, solution: list[Point], same_head: bool = True
) -> list[Point]:
    """The solution's points that play p's part (see _counterparts); `same_head` False:
    every point within the counterpart statements, whatever its operation."""
    if statement is None:
        return []
    if statement.name:
        pool = [
            s
            for s in solution
            if s.statement and s.name and _plain(s.name) == _plain(statement.name)
        ]
    else:
        pool = [
            s for s in solution if s.statement and not s.name and s.function == statement.function
        ][-1:]
    if not same_head:
        return pool + [
            s for s in solution for t in pool if t.start <= s.start and s.end <= t.end and s != t
        ]
    if p is not statement:
        pool = [
            s
            for s in solution
            for t in pool
            if t.start <= s.start and s.end <= t.end and not s.statement and s.head == p.head
        ]
    return pool


def _describe(
    p: Point,
    v: np.ndarray,
    r: np.ndarray,
    meant: list[Quantity],
    known: list[Quantity],
    geo: list[Quantity],
) -> str:
    """A relation of the point's values to a quantity it plays the part of, in words."""
    named = next((q.label for q in meant), "")
    if meant and p.name and _plain(meant[0].name) == _plain(p.name) and meant[0].text:
        named = meant[0].text  # "H equals L + V, not normalize(L + V)", not "... not H"
    for q in geo:  # another direction's dot product, an angle for its cosine...
        if matches(v, r, q) and q.label != named:
            return f"equals {q.label}" + (f", not {named}" if named else "")
    if not varies(v[r]):
        return ""  # a constant (4.0 * ke): what is computed from it tells more
    for q in meant:
        joint = shared_rows(r, q) if q.values.shape[1] == v.shape[1] else None
        if joint is None:
            continue
        phrase = relation(v[joint], q.values[joint])
        if phrase:
            return phrase.format(q=q.label)
        phrase = term(v[joint], q.values[joint], joint, known + geo, q)
        if phrase:
            return phrase
    return ""


def _statement_of(point: Point, points: list[Point]) -> Point | None:
    if point.statement:
        return point
    return next(
        (p for p in points if p.statement and p.start <= point.start and point.end <= p.end), None
    )


def sentence(finding: Finding, source: str, label: str) -> str:
    """The finding in words, quoting the student's own line."""
    lines = source.splitlines()
    line = finding.point.line
    quoted = " ".join(lines[line - 1].split()) if 0 < line <= len(lines) else finding.point.text
    where = f"{label}:{line}"
    expr = finding.point.text if not finding.point.statement else ""
    if finding.point.head == "parameter":
        calls = sorted({p.line for p in finding.calls})
        at = f" (called at line {', '.join(map(str, calls))})" if calls else ""
        what = f"the argument {finding.point.name} of {finding.point.function}{at}"
        said = finding.relation or "matches none of the solution's quantities"
        return f"{label}:{line}: {what} {said}"
    loop = finding.point.loop
    if loop is not None:  # a loop's values are its last pass's: the cause may lie before
        return (
            f"{label}:{loop[0]}-{loop[1]}: in this loop, line {line} (`{quoted}`) gives "
            "the first value that matches none of the solution's at the loop's last pass "
            "(the cause may be earlier in the loop, such as a light it should skip or stop at)"
        )
    if finding.relation:
        what = f"`{expr}`" if expr else "its value"
        return f"{where} (`{quoted}`): {what} {finding.relation}"
    inside = (
        f", in `{expr}`"
        if expr and expr not in quoted[: len(expr) + 40]
        else (f", at `{expr}`" if expr else "")
    )
    said = (
        f"{where} (`{quoted}`){inside} is your first value that matches none of the "
        "solution's, though all it uses agrees with the solution"
    )
    later = finding.through
    if later is not None and 0 < later.line <= len(lines):
        shown = " ".join(lines[later.line - 1].split())
        what = f"`{later.text}`" if not later.statement else "its value"
        said += f"; computed from it, line {later.line} (`{shown}`): {what} "
        said += finding.through_relation
    return said


def returned(trace: Trace, function: str) -> tuple[np.ndarray, np.ndarray] | None:
    """What `function` returned at each pair (its last call there) and where it ran."""
    values, ran = None, None
    for point in trace.traced.points:
        if point.function != function or not point.statement or point.name:
            continue
        v, r, _ = trace.value(point.slot)
        if values is None:
            values, ran = np.zeros_like(v), np.zeros(len(v), bool)
        if v.shape != values.shape:
            continue
        values[r] = v[r]
        ran |= r
    return None if values is None else (values, ran)


def _shown(values: np.ndarray) -> str:
    """A value as the grader's rows print it (a grey colour as one number)."""
    return fmt_rgb(values) if values.shape[-1] == 3 else f"{float(values[0]):.4g}"


def term_rows(student: Trace, solution: Trace, functions: list[str]) -> str:
    """For term exercises: where one of the student's functions (F, D, G) returns other
    values than the solution's, its value and its arguments beside the solution's at the
    pair where they differ most ('' where they agree)."""
    out = []
    for function in functions:
        mine, want = returned(student, function), returned(solution, function)
        if mine is None or want is None or mine[0].shape != want[0].shape:
            continue
        both = mine[1] & want[1]
        wrong = both & ~agree(mine[0], want[0])
        if not wrong.any():
            continue
        error = np.abs(mine[0] - want[0]).max(axis=-1) / (1e-4 + np.abs(want[0]).max(axis=-1))
        row = int(np.flatnonzero(wrong)[np.argmax(error[wrong])])
        args = []
        for point in student.traced.points:
            if point.function == function and point.head == "parameter":
                v, r, _ = student.value(point.slot)
                if r[row]:
                    args.append(f"{point.name} = {_shown(v[row])}")
        angles = ", ".join(f"{a:.1f}°" for a in student.angles[row])
        out.append(
            f"your {function}({', '.join(args)}) returns {_shown(mine[0][row])} where the "
            f"solution's returns {_shown(want[0][row])} (at θi, φi, θo, φo = {angles}; "
            f"{int(wrong.sum())} of {int(both.sum())} pairs differ)"
        )
    return "; ".join(out)


def _start(point: Point) -> int:
    return point.start


def early_exit(student: Trace, solution: Trace) -> str:
    """Where the results differ only at pairs for which the solution leaves its function
    early with a constant (`return vec3(0.0)` below the horizon) and the student's code
    does not: that exit is missing or its test is wrong. '' otherwise."""
    mine, mine_ran, _ = student.value(0)
    want, want_ran, _ = solution.value(0)
    both = mine_ran & want_ran
    wrong = both & ~agree(mine, want)
    if wrong.sum() < 3:
        return ""
    returns = [p for p in solution.traced.points if p.statement and not p.name]
    returns = [p for p in returns if p.head != "parameter"]
    for point in returns:
        if point is max((p for p in returns if p.function == point.function), key=_start):
            continue  # a function's last return is where it ends, not an early exit
        values, ran, _ = solution.value(point.slot)
        called = np.zeros_like(ran)  # where its function ran at all: an early exit is a
        for other in solution.traced.points:  # part of those pairs, not all of them
            if other.function == point.function:
                called |= solution.value(other.slot)[1]
        if not ran.any() or not (called & ~ran).any() or varies(values[ran]):
            continue
        if (wrong & ~ran).sum() > 0.05 * wrong.sum() or wrong[ran].mean() < 0.25:
            continue
        geo = geometry(student.angles)
        below_l, below_v = geo["N·L"] <= 0.0, geo["N·V"] <= 0.0
        if (wrong <= below_v).all() and not (wrong <= below_l).all():
            where, rows = "V is below the surface (N·V ≤ 0)", below_v
        elif (wrong <= below_l).all() and not (wrong <= below_v).all():
            where, rows = "L is below the surface (N·L ≤ 0)", below_l
        elif (wrong <= (below_l | below_v)).all():
            where, rows = "L or V is below the surface", below_l | below_v
        else:
            where, rows = f"the solution's test before `{point.text}` holds", ran
        value = _shown(values[ran][0])
        return (
            f"{EXIT_START} {where}: there it should return {value} ({int(wrong.sum())} "
            f"of the {int((rows & both).sum())} such pairs differ); that early exit, or its "
            "test, is missing"
        )
    return ""

"""Every intermediate value of a shader function, at the grader's direction pairs.

A submission's functions are parsed with tree-sitter's GLSL grammar; each value a line
computes (a declaration's initial value, what an assignment leaves in its variable, a
returned value) and each arithmetic subexpression gets a numbered slot. The instrumented
code records the value of one slot, picked per pixel row by the `grade_trace` view, so
one draw yields every intermediate at every pair: what lab.grading.localise compares with
the solution's own intermediates, after Clara (Gulwani, Radiček and Zuleger, PLDI 2018),
which matches a student's variables with a reference's by their values on the same inputs.
"""

from __future__ import annotations

import functools
import math
import re
import warnings
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from lab.models import Model
    from lab.render import Renderer

VIEW = "grade_trace"
SAMPLER_VIEW = "grade_trace_sampler"
ILLUMINATION_VIEW = "grade_trace_illumination"
# The grading view an exercise's checks use, and the trace harness for its function.
HARNESS = {"grade_illumination": ILLUMINATION_VIEW}
MAX_SLOTS = 400  # rows of the trace image; a longer program is traced in part
MAX_PAIRS = 1024  # columns: one texture row of direction pairs
ARITHMETIC = {"+", "-", "*", "/"}


def prelude(slots: int) -> str:
    """The recorder, on one line so that the file's line numbers stay its own. Row k of the
    trace view takes slot k's value; row slots + k the step at which slot k last ran (a
    count of recorded values): the program's order of execution."""
    records = [
        ("float", "vec4(v, 0.0, 0.0, 1.0)"),
        ("vec2", "vec4(v, 0.0, 2.0)"),
        ("vec3", "vec4(v, 3.0)"),
        ("vec4", "vec4(v.xyz, 4.0)"),
        ("int", "vec4(float(v), 0.0, 0.0, 1.0)"),
        ("bool", "vec4(v ? 1.0 : 0.0, 0.0, 0.0, 1.0)"),
    ]
    return " ".join(
        [
            "int lab_trace_slot = -1; vec4 lab_trace_value = vec4(0.0); int lab_trace_step = 0;",
            *(
                f"{t} lab_tr(int k, {t} v) {{ lab_trace_step += 1; "
                f"if (k == lab_trace_slot) lab_trace_value = {rec}; "
                f"if (k + {slots} == lab_trace_slot) "
                "lab_trace_value = vec4(float(lab_trace_step), 0.0, 0.0, 1.0); return v; }"
                for t, rec in records
            ),
        ]
    )


@dataclass
class Point:
    """One traced value: a line's result (`name` is the variable it sets, '' for a return)
    or a subexpression (`statement` False)."""

    slot: int
    line: int  # 1-based, in the file
    text: str  # the source of the expression (a statement's: the whole statement)
    function: str
    statement: bool
    name: str = ""
    start: int = 0  # byte offsets of the expression in the code
    end: int = 0
    deps: list[int] = field(default_factory=list)  # slots whose values this one reads
    head: str = ""  # the operation: a called function's name or an operator
    partial: list[int] = field(default_factory=list)  # deps read through a swizzle (h.z)
    loop: tuple[int, int] | None = None  # first and last line of the loop it is in


@dataclass
class Traced:
    """A program's instrumented code and its points (slot k is points[k - 1])."""

    code: str
    points: list[Point]


@functools.lru_cache(maxsize=1)
def _parser():
    import tree_sitter
    import tree_sitter_glsl

    with warnings.catch_warnings():
        # tree-sitter-glsl 0.2 hands its grammar over as an int, which tree-sitter 0.22+
        # still takes but calls deprecated (the tests turn warnings into errors)
        warnings.simplefilter("ignore", DeprecationWarning)
        language = tree_sitter.Language(tree_sitter_glsl.language())
    return tree_sitter.Parser(language)


def parse(code: str):
    """The tree-sitter syntax tree of GLSL `code`."""
    return _parser().parse(code.encode("utf-8"))


def _function_name(node) -> str:
    declarator = node.child_by_field_name("declarator")
    while declarator is not None and declarator.type != "function_declarator":
        declarator = declarator.child_by_field_name("declarator")
    name = declarator.child_by_field_name("declarator") if declarator is not None else None
    return name.text.decode() if name is not None else ""


def _is_value(node) -> bool:
    """An expression worth a slot: arithmetic, a call with a variable argument, a negation,
    a choice; not a name, a literal or a comparison."""
    if node.type == "binary_expression":
        operator = node.child_by_field_name("operator")
        op = operator.text.decode() if operator is not None else node.children[1].text.decode()
        return op in ARITHMETIC
    if node.type == "call_expression":
        args = node.child_by_field_name("arguments")
        name = node.child_by_field_name("function")
        if name is None or name.text.decode().startswith("lab_"):
            return False
        return args is not None and any(_reads(a) for a in args.named_children)
    if node.type == "unary_expression":
        return node.children[0].text.decode() == "-"
    return node.type == "conditional_expression"


def _reads(node) -> bool:
    """Does the expression read a name (not only literals)?"""
    if node.type == "identifier":
        return True
    return any(_reads(c) for c in node.named_children if c.type != "field_identifier")


class _Instrumenter:
    """Walks the functions of a parsed program, numbering points and noting the edits."""

    def __init__(self, code: str, last_line: int) -> None:
        self.source = code.encode("utf-8")
        self.last_line = last_line
        self.points: list[Point] = []
        self.edits: dict[tuple[int, int, str], str] = {}  # node -> template with {}
        self.defined: dict[str, int] = {}  # variable -> slot of its last assignment
        self.function = ""
        self.loop: tuple[int, int] | None = None  # the lines of the outermost loop we are in

    def run(self, tree) -> None:
        for node in tree.root_node.named_children:
            if node.type != "function_definition" or node.start_point[0] + 1 > self.last_line:
                continue
            body = node.child_by_field_name("body")
            if body is None:
                continue
            self.function, self.defined = _function_name(node), {}
            self.parameters(node, body)
            self.block(body)

    def parameters(self, function, body) -> None:
        """Each value parameter is a point at the body's start: a helper called with the
        wrong argument shows there."""
        declarator = function.child_by_field_name("declarator")
        params = declarator.child_by_field_name("parameters") if declarator else None
        if params is None:
            return
        records = []
        for param in params.named_children:
            name = param.child_by_field_name("declarator")
            words = param.text.decode().split()
            if name is None or name.type != "identifier" or {"out", "inout"} & set(words):
                continue
            slot = self._add(param, name, name.text.decode(), [])
            self.points[-1].head = "parameter"
            self.defined[name.text.decode()] = slot
            records.append(f"lab_tr({slot}, {name.text.decode()});")
        if records:
            self.edits[_key(body)] = "{" + " ".join(records) + " {} }"

    def block(self, node) -> None:
        for child in node.named_children:
            self.statement(child)

    def statement(self, node) -> None:
        if len(self.points) >= MAX_SLOTS:
            return
        kind = node.type
        if kind == "compound_statement":
            self.block(node)
        elif kind == "declaration":
            if any(c.type == "type_qualifier" and b"const" in c.text for c in node.children):
                return  # a constant expression cannot hold a call
            for init in node.named_children:
                value = init.child_by_field_name("value")
                if init.type == "init_declarator" and value is not None:
                    name = init.child_by_field_name("declarator").text.decode()
                    slot = self.expression(value, node, name)
                    self.defined[name] = slot
        elif kind == "expression_statement":
            expr = node.named_children[0] if node.named_children else None
            if expr is not None and expr.type == "assignment_expression":
                self.assignment(node, expr)
        elif kind == "return_statement":
            if node.named_children:
                self.expression(node.named_children[0], node, "")
        elif kind in ("if_statement", "for_statement", "while_statement", "do_statement"):
            outer = self.loop
            if kind != "if_statement":  # a value in a loop is the one of its last pass
                self.loop = outer or (node.start_point[0] + 1, node.end_point[0] + 1)
            for child in node.named_children:
                if child.type.endswith("statement"):
                    self.statement(child)
                elif child.type == "else_clause":
                    self.block(child)
            self.loop = outer

    def assignment(self, node, expr) -> None:
        left, right = expr.child_by_field_name("left"), expr.child_by_field_name("right")
        if left is None or right is None:
            return
        target = left
        while target.type in ("field_expression", "subscript_expression"):
            target = target.named_children[0]
        if target.type != "identifier":
            return
        name = target.text.decode()
        operator = expr.children[1].text.decode()
        deps = [self.sub(right, node)]
        if operator != "=" or left is not target:  # x += e, v.x = e: the old x counts
            deps.append(self.defined.get(name, 0))
        slot = self._add(node, node, name, deps)
        self.edits[_key(node)] = "{ {} lab_tr(" + str(slot) + ", " + left.text.decode() + "); }"
        self.defined[name] = slot

    def expression(self, node, statement, name: str) -> int:
        """A statement's value: its expression gets the statement's slot."""
        deps = self._deps(node, statement)
        slot = self._add(statement, node, name, deps)
        self.edits[_key(node)] = f" lab_tr({slot}, ({{}}))"
        return slot

    def sub(self, node, statement) -> int:
        """The slot of a subexpression (0: a name's definition or a trusted input)."""
        while node.type == "parenthesized_expression" and node.named_children:
            node = node.named_children[0]
        if node.type == "identifier":
            return self.defined.get(node.text.decode(), 0)
        if node.type == "field_expression" and node.named_children:
            # h.z reads one component of h: a right h.z does not vouch for all of h
            return -abs(self.sub(node.named_children[0], statement))
        if not _is_value(node):
            deps = self._deps(node, statement)
            return deps[0] if len(deps) == 1 else 0
        slot = self._add(None, node, "", self._deps(node, statement))
        self.edits[_key(node)] = f" lab_tr({slot}, ({{}}))"
        return slot

    def _deps(self, node, statement) -> list[int]:
        if node.type == "identifier":
            return [self.defined.get(node.text.decode(), 0)]
        out = []
        for child in node.named_children:
            if child.type in ("field_identifier", "number_literal", "argument_list"):
                if child.type == "argument_list":
                    out += [self.sub(a, statement) for a in child.named_children]
                continue
            if node.type == "call_expression" and child == node.child_by_field_name("function"):
                continue
            out.append(self.sub(child, statement))
        return [d for d in out if d]

    def _add(self, statement, node, name: str, deps: list[int]) -> int:
        slot = len(self.points) + 1
        shown = statement if statement is not None else node
        self.points.append(
            Point(
                slot=slot,
                line=node.start_point[0] + 1,
                text=tidy(shown.text.decode()),
                function=self.function,
                statement=statement is not None,
                name=name,
                start=node.start_byte,
                end=node.end_byte,
                deps=[abs(d) for d in deps if d],
                partial=[-d for d in deps if d < 0],
                head=_head(node),
                loop=self.loop,
            )
        )
        return slot

    def emit(self, node) -> str:
        pieces, pos = [], node.start_byte
        for child in node.children:
            pieces.append(self.source[pos : child.start_byte].decode())
            pieces.append(self.emit(child))
            pos = child.end_byte
        pieces.append(self.source[pos : node.end_byte].decode())
        text = "".join(pieces)
        template = self.edits.get(_key(node))
        return template.replace("{}", text, 1) if template else text


def tidy(code: str) -> str:
    """Code as a person writes it (the preprocessor's output spaces tokens oddly):
    `h.x * X`, `(1.0 - f0) * k`, `-V`."""
    text = " ".join(code.split())
    text = re.sub(r"\s*\.\s*(?=[A-Za-z_])", ".", text)
    text = re.sub(r"\s*([*/+]|==|<=|>=|&&|\|\|)\s*", r" \1 ", text)
    text = re.sub(r"(?<=[\w)\]])(?<![0-9][eE])\s*-\s*", " - ", text)
    text = re.sub(r"(^|[(,=?:]|return)\s*-\s+", r"\1 -", text)
    text = re.sub(r"\(\s+", "(", text)
    text = re.sub(r"\s+([),;\]])", r"\1", text)
    text = re.sub(r"\s*,\s*", ", ", text)
    return " ".join(text.split()).replace("( -", "(-").replace(", -  ", ", -")


def _head(node) -> str:
    """What an expression does: the called function's name, or its operator."""
    while node.type == "parenthesized_expression" and node.named_children:
        node = node.named_children[0]
    if node.type == "call_expression":
        name = node.child_by_field_name("function")
        return name.text.decode() if name is not None else ""
    if node.type in ("binary_expression", "unary_expression") and node.child_count > 1:
        return node.children[1 if node.type == "binary_expression" else 0].text.decode()
    return node.type


def _key(node) -> tuple[int, int, str]:
    return (node.start_byte, node.end_byte, node.type)


def instrument(code: str, last_line: int = 1 << 30) -> Traced:
    """`code` with every function defined up to `last_line` instrumented."""
    tree = parse(code)
    walker = _Instrumenter(code, last_line)
    walker.run(tree)
    body = walker.emit(tree.root_node)
    # Keep whatever precedes the tree's root (nothing, usually) and put the recorder
    # on the first line with the file's own first line.
    return Traced(prelude(len(walker.points)) + " " + body, walker.points)


@dataclass
class Trace:
    """What a traced program computed: `values[k]` is slot k's (pairs, 4) array (xyz and
    the component count in w, 0 where it did not run); `values[0]` is f_r."""

    traced: Traced
    values: np.ndarray
    angles: np.ndarray
    directions: bool = True  # rows are direction pairs (L, V), not normals or random numbers

    def value(self, slot: int) -> tuple[np.ndarray, np.ndarray, int]:
        """Slot's values (pairs, components), the rows where it ran, its component count."""
        raw = self.values[slot]
        ran = raw[:, 3] > 0.5
        count = int(round(float(np.median(raw[ran, 3])))) if ran.any() else 1
        count = min(max(count, 1), 3)
        return raw[:, :count].astype(np.float64), ran, count

    def step(self, slot: int) -> float:
        """When slot ran, in the program's order (median over the pairs; inf if never)."""
        raw = self.values[len(self.traced.points) + slot]
        ran = raw[:, 3] > 0.5
        return float(np.median(raw[ran, 0])) if ran.any() else math.inf


def run(
    renderer: Renderer,
    model: Model,
    values: dict,
    angles_deg: np.ndarray,
    last_line: int = 1 << 30,
    kept: dict | None = None,
    view: str = "",
) -> Trace | None:
    """Trace `model` at direction pairs (theta_i, phi_i, theta_o, phi_o in degrees); None
    where its code cannot be parsed or instrumented code does not compile.

    A sampling exercise's model (one with `sampler_code`) is traced in its sampler: the
    first two columns of a row are then the random numbers u, not angles. `kept` holds
    instrumented code already made, by (code, last line). `view`: the trace harness, where
    the exercise's function is not a BRDF (ILLUMINATION_VIEW: rows are normals)."""
    import moderngl

    from lab.glsl import ShaderCompileError

    sampler = getattr(model, "sampler_code", None)
    view = view or (VIEW if sampler is None else SAMPLER_VIEW)
    code = model.code if sampler is None else sampler
    traced = kept.get((code, last_line)) if kept is not None else None
    try:
        traced = traced or instrument(code, last_line)
    except (ImportError, RecursionError, UnicodeError):
        return None
    if kept is not None:  # `kept`: a submission's instrumented code, made once
        kept[(code, last_line)] = traced
    instrumented = replace(model, code=traced.code)
    if sampler is not None:  # the sampler alone, with the library's frame helpers
        instrumented.includes = ["terms/sampling.glsl"]
        instrumented.sampler_code = None
    angles = np.asarray(angles_deg, np.float64).reshape(-1, 4)[:MAX_PAIRS]
    data = np.radians(angles)
    if sampler is not None:
        data[:, :2] = angles[:, :2]
    rows = 2 * len(traced.points) + 1
    texture = renderer.ctx.texture(
        (len(angles), 1), 4, data.astype(np.float32).tobytes(), dtype="f4"
    )
    texture.filter = (moderngl.NEAREST, moderngl.NEAREST)
    previous = renderer._last  # the checks' loop guard reads the last view drawn: theirs
    try:
        texture.use(0)
        fbo = renderer._run(instrumented, view, values, (len(angles), rows), {"u_angles": 0})
        data = np.frombuffer(fbo.read(components=4, dtype="f4"), np.float32)
    except (ShaderCompileError, moderngl.Error):
        return None
    finally:
        renderer._last = previous
        texture.release()
    values = data.reshape(rows, len(angles), 4).copy()
    return Trace(traced, values, angles, directions=view in (VIEW,))


def normal_rows(seed: int = 13, n: int = 256) -> np.ndarray:
    """Rows (theta, phi, 0, 0) of normals over the visible half of a sphere (in degrees)."""
    rng = np.random.default_rng(seed)
    theta = np.degrees(np.arccos(rng.uniform(0.05, 1.0, n)))
    zeros = np.zeros(n)
    return np.stack([theta, rng.uniform(0.0, 360.0, n), zeros, zeros], axis=1)


def sampler_rows(seed: int = 11, n: int = 256) -> np.ndarray:
    """Rows (u.x, u.y, theta_o, phi_o) for tracing a sampler: random numbers over the unit
    square, views from the normal to near grazing."""
    rng = np.random.default_rng(seed)
    theta_o = np.degrees(np.arccos(rng.uniform(0.1, 1.0, n)))
    return np.stack([rng.random(n), rng.random(n), theta_o, rng.uniform(0, 360, n)], axis=1)


def pairs(seed: int = 7, n: int = 192) -> np.ndarray:
    """Direction pairs for tracing a check that has none of its own (a sphere): spread over
    the hemisphere, a third near the mirror direction, a few below the horizon."""
    rng = np.random.default_rng(seed)
    theta_i = np.degrees(np.arccos(rng.uniform(0.08, 1.0, n)))
    theta_o = np.degrees(np.arccos(rng.uniform(0.08, 1.0, n)))
    phi_i = rng.uniform(0.0, 360.0, n)
    phi_o = rng.uniform(0.0, 360.0, n)
    near = slice(n // 2, n // 2 + n // 3)
    theta_o[near] = np.clip(theta_i[near] + rng.normal(0.0, 3.0, n // 3), 1.0, 85.0)
    phi_o[near] = phi_i[near] + 180.0 + rng.normal(0.0, 5.0, n // 3)
    below = slice(n - n // 12, n)
    theta_i[below] = 180.0 - theta_i[below]
    return np.stack([theta_i, phi_i % 360.0, theta_o, phi_o % 360.0], axis=1)


def geometry(angles_deg: np.ndarray) -> dict[str, np.ndarray]:
    """The quantities every BRDF is built from, in float64 at the pairs, by their names."""
    a = np.radians(np.asarray(angles_deg, np.float64))

    def unit(theta, phi):
        return np.stack(
            [np.sin(theta) * np.cos(phi), np.sin(theta) * np.sin(phi), np.cos(theta)], axis=-1
        )

    L, V = unit(a[:, 0], a[:, 1]), unit(a[:, 2], a[:, 3])
    half = L + V
    H = half / np.maximum(np.linalg.norm(half, axis=-1, keepdims=True), 1e-30)
    R = 2.0 * L[:, 2:3] * np.array([0.0, 0.0, 1.0]) - L
    dot = functools.partial(np.einsum, "ij,ij->i")
    out = {
        "N·L": L[:, 2],
        "N·V": V[:, 2],
        "L·V": dot(L, V),
        "N·H": H[:, 2],
        "V·H": dot(V, H),
        "H": H,
        "R": R,
        "R·V": dot(R, V),
        "L + V": half,
        "θh": np.arccos(np.clip(H[:, 2], -1.0, 1.0)),
        "θi": np.arccos(np.clip(L[:, 2], -1.0, 1.0)),
        "θo": np.arccos(np.clip(V[:, 2], -1.0, 1.0)),
    }
    out["tan²θh"] = (1.0 - out["N·H"] ** 2) / np.maximum(out["N·H"] ** 2, 1e-30)
    return out


DEGREES = 180.0 / math.pi

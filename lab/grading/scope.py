"""What a submission may name: its own code, GLSL's built-ins, and the API its handout gives.

The grader assembles a student's file into a program with the lab's shader library and
harness (the loop guard, the host lines, the views). Without this check every library
function would be in scope: exercise 10 could call the library's own sampler. Here the
preprocessed file (no comments, macros expanded) is read token by token: a name that the
program's library part declares and the file uses, without declaring it itself and without
the exercise's `api` listing it, is refused before anything renders; so is a global of the
file that the library part also declares (the two would clash, or an overload would make the
library's reachable), and any identifier in the harness's namespace.

The harness namespace is the prefix `lab_` (any case): the library's private helpers, the
loop guard's counters and the host's macros all use it. GLSL reserves identifiers containing
`__`, but WebGL (ANGLE) rejects them outright while Mesa only warns, so the web page could not
use such names; the prefix is refused in submissions instead, and so is `__`.
"""

from __future__ import annotations

import re
from collections.abc import Iterable
from dataclasses import dataclass, field
from functools import cache
from pathlib import Path

from lab.constants import glsl_defines
from lab.glsl import DEFAULT_PREAMBLE, FLAG_OUTPUT, LOOP_GUARD, VIEW_DIR, VIEW_INCLUDE, label_of
from lab.grading.submission import SourceError
from lab.models import SHADER_DIR, load_model

HARNESS_PREFIX = "lab_"
TOKEN = re.compile(
    r"(?P<number>0[xX][0-9a-fA-F]+[uU]?|(?:\d+\.\d*|\.\d+|\d+)(?:[eE][+-]?\d+)?[fFuU]?)"
    r"|(?P<name>[A-Za-z_]\w*)|(?P<newline>\n)|(?P<punct>[^\s\w])"
)
COMMENTS = re.compile(r"//[^\n]*|/\*.*?(?:\*/|\Z)", re.S)
DEFINE = re.compile(r"^[ \t]*#[ \t]*define[ \t]+([A-Za-z_]\w*)", re.M)
DIRECTIVE_LINE = re.compile(r"^[ \t]*#[^\n]*", re.M)
QUALIFIERS = frozenset(
    "const in out inout uniform highp mediump lowp flat smooth noperspective invariant "
    "centroid precise".split()
)
KEYWORDS = frozenset(
    "if else for while do break continue return discard switch case default true false "
    "struct layout precision".split()
)
TYPES = frozenset(
    ["void", "bool", "int", "uint", "float", "double"]
    + [f"{p}vec{n}" for p in ("", "b", "i", "u", "d") for n in (2, 3, 4)]
    + [f"{p}mat{n}" for p in ("", "d") for n in (2, 3, 4)]
    + [f"{p}mat{n}x{m}" for p in ("", "d") for n in (2, 3, 4) for m in (2, 3, 4)]
    + [f"{p}sampler{s}" for p in ("", "i", "u") for s in ("2D", "3D", "Cube", "2DArray")]
)
# Host lines that glsl.assemble_fragment and lab.ibl.integrator write around the model.
HOST_NAMES = ("IS_DELTA", "AMBIENT_REFLECTANCE", "DELTA_REFLECTANCE")
SAMPLER_HOST_NAMES = ("HAS_SAMPLER", "SAMPLE_BRDF", "PDF_BRDF")
ESTIMATOR_HOST_NAMES = ("random2",)  # lab.ibl.integrator.ESTIMATOR_LINE gives an estimator


@dataclass
class Token:
    text: str
    line: int
    kind: str


@dataclass
class Reading:
    """A file's top-level names (name -> line) and its uses of names it does not declare in
    the scope of the use ((name, line), in order)."""

    globals: dict[str, int] = field(default_factory=dict)
    uses: list[tuple[str, int]] = field(default_factory=list)
    declared: list[tuple[str, int]] = field(default_factory=list)  # every declaration


def tokenize(code: str) -> list[Token]:
    """Tokens of comment-free GLSL without directive lines, each with its 1-based line."""
    tokens, line = [], 1
    for match in TOKEN.finditer(code):
        kind = match.lastgroup or "punct"
        if kind == "newline":
            line += 1
            continue
        tokens.append(Token(match.group(), line, kind))
    return tokens


def _matching(tokens: list[Token], start: int) -> int:
    """Index of the bracket closing the one at `start` (or the last index)."""
    pairs = {"(": ")", "{": "}", "[": "]"}
    opening, closing, depth = tokens[start].text, pairs[tokens[start].text], 0
    for index in range(start, len(tokens)):
        if tokens[index].text == opening:
            depth += 1
        elif tokens[index].text == closing:
            depth -= 1
            if depth == 0:
                return index
    return len(tokens) - 1


class _Reader:
    """One pass over a file's tokens: declarations by scope, and the uses they leave open."""

    def __init__(self, tokens: list[Token]):
        self.tokens = tokens
        self.types = set(TYPES)
        self.reading = Reading()
        self.scopes: list[set[str]] = [set()]

    def declare(self, token: Token, top: bool) -> None:
        self.scopes[-1].add(token.text)
        self.reading.declared.append((token.text, token.line))
        if top:
            self.reading.globals.setdefault(token.text, token.line)

    def use(self, token: Token) -> None:
        if not any(token.text in scope for scope in self.scopes):
            self.reading.uses.append((token.text, token.line))

    def is_type(self, token: Token) -> bool:
        return token.kind == "name" and token.text in self.types

    def run(self) -> Reading:
        index = 0
        while index < len(self.tokens):
            index = self.top_item(index)
        return self.reading

    def top_item(self, start: int) -> int:
        """Read one top-level item (struct, declaration, prototype or function)."""
        tokens, index = self.tokens, start
        if tokens[index].text == "struct" and index + 1 < len(tokens):
            self.types.add(tokens[index + 1].text)
            self.declare(tokens[index + 1], top=True)
            if index + 2 < len(tokens) and tokens[index + 2].text == "{":
                index = _matching(tokens, index + 2) + 1  # members are fields, not names
            return self.statement(index, top=True, declaring=True)
        end = index
        while end < len(tokens) and tokens[end].text not in (";", "{", "("):
            end += 1
        if end < len(tokens) and tokens[end].text == "(" and end > start:
            name = tokens[end - 1]
            close = _matching(tokens, end)
            after = close + 1
            if tokens[start].text in ("layout", "precision") or name.text in self.types:
                return self.statement(start, top=True, declaring=True)
            self.declare(name, top=True)
            if after < len(tokens) and tokens[after].text == "{":
                self.scopes.append(set())
                self.parameters(end, close)
                body_end = _matching(tokens, after)
                self.block(after + 1, body_end)
                self.scopes.pop()
                return body_end + 1
            return after + 1 if after < len(tokens) and tokens[after].text == ";" else after
        return self.statement(start, top=True, declaring=True)

    def parameters(self, open_index: int, close: int) -> None:
        """Declare each parameter's name (the last name before `,`, `)` or `[`)."""
        last = None
        for index in range(open_index + 1, close + 1):
            token = self.tokens[index]
            if token.text in (",", ")") or token.text == "[":
                if last is not None:
                    self.declare(last, top=False)
                last = None
                if token.text == "[":
                    continue
            elif token.kind == "name" and token.text not in QUALIFIERS and not self.is_type(token):
                last = token

    def block(self, start: int, end: int) -> None:
        index = start
        while index < end:
            token = self.tokens[index]
            if token.text == "{":
                self.scopes.append(set())
                index += 1
            elif token.text == "}":
                if len(self.scopes) > 1:
                    self.scopes.pop()
                index += 1
            else:
                index = self.statement(index, top=False, declaring=False, stop=end)

    def statement(self, start: int, top: bool, declaring: bool, stop: int | None = None) -> int:
        """Read tokens up to `;` (or a block's brace): declarations and uses."""
        tokens = self.tokens
        stop = len(tokens) if stop is None else stop
        index, depth, declaring_at = start, 0, 0 if declaring else None
        expect_name = declaring
        while index < stop:
            token = tokens[index]
            text = token.text
            if text in ("{", "}") and depth == 0 and not top:
                return index
            if text == ";" and depth == 0:
                return index + 1
            if text in ("(", "["):
                depth += 1
            elif text in (")", "]"):
                depth -= 1
            elif text == ";" and declaring_at is not None and depth == declaring_at:
                declaring_at, expect_name = None, False  # for (int i = 0; ...
            elif text == "," and declaring_at is not None and depth == declaring_at:
                expect_name = True
            elif text == "=" and declaring_at is not None:
                expect_name = False
            elif token.kind == "name":
                previous = tokens[index - 1].text if index > 0 else ""
                following = tokens[index + 1].text if index + 1 < len(tokens) else ""
                if previous == ".":
                    pass  # a field or a swizzle
                elif self.is_type(token) and following not in ("(",):
                    if not (following == "[" and depth > 0 and declaring_at is None):
                        declaring_at, expect_name = depth, True
                elif text in QUALIFIERS or text in KEYWORDS:
                    pass
                elif expect_name and declaring_at is not None:
                    self.declare(token, top=top)
                    expect_name = False
                else:
                    self.use(token)
            index += 1
        return index


def read_code(code: str) -> Reading:
    """The names a comment-free GLSL text declares at top level, and those it uses."""
    return _Reader(tokenize(DIRECTIVE_LINE.sub("", code))).run()


def library_declarations(text: str) -> list[str]:
    """Top-level names a library text declares, its `#define` macros included."""
    plain = COMMENTS.sub(lambda m: "\n" * m.group().count("\n"), text)
    return [*DEFINE.findall(plain), *read_code(plain).globals]


@cache
def _file_names(path: Path) -> tuple[str, ...]:
    return tuple(library_declarations(path.read_text(encoding="utf-8")))


def _views() -> list[Path]:
    views = sorted(VIEW_DIR.glob("*.glsl"))
    included = [
        SHADER_DIR / rel for v in views for rel in VIEW_INCLUDE.findall(v.read_text("utf-8"))
    ]
    return list(dict.fromkeys([*views, *included]))


@cache
def program_names(
    includes: tuple[str, ...], models: tuple[str, ...], sampler: bool, estimator: bool = False
) -> dict[str, str]:
    """Every name the lab's part of an exercise's programs declares -> where (a file under
    shaders/ or the harness): the library files `includes`, the code of the library `models`,
    the sampling terms for a sampler, the loop guard, the host lines and the views."""
    names: dict[str, str] = {}

    def add(found: Iterable[str], where: str) -> None:
        for name in found:
            names.setdefault(name, where)

    add(library_declarations(glsl_defines()), "the lab's constants")
    add(library_declarations("\n".join(DEFAULT_PREAMBLE.values())), "the lab's views")
    files = ["terms/common.glsl", *includes]
    for name in models:
        model = load_model(name)
        add(library_declarations(model.code), label_of(model.path))
    if sampler:
        files += ["terms/sampling.glsl", "terms/environment.glsl"]
        add(SAMPLER_HOST_NAMES, "the lab's sampler host")
    if estimator:
        add(ESTIMATOR_HOST_NAMES, "the lab's estimator host")
    for relative in dict.fromkeys(files):
        path = SHADER_DIR / relative
        add(_file_names(path), label_of(path))
    add(library_declarations(LOOP_GUARD + "\n" + FLAG_OUTPUT), "the loop guard")
    add(["LAB_LOOP_LIMIT"], "the loop guard")
    add(HOST_NAMES, "the lab's host code")
    for path in _views():
        add(_file_names(path), label_of(path))
    return names


def exercise_names(exercise) -> dict[str, str]:
    """program_names for an exercise (lab.grading.exercise.Exercise): what its programs hold
    besides the student's file."""
    if exercise.sampler_for:
        model = load_model(exercise.sampler_for)
        estimator = bool(getattr(exercise, "estimator", False))
        return program_names(tuple(model.includes), (exercise.sampler_for,), True, estimator)
    if exercise.wrapper:
        wrapper = load_model(exercise.wrapper)
        includes = tuple(i for i in wrapper.includes if i != exercise.replaces)
        return program_names(includes, (exercise.wrapper,), False)
    from lab.models import parse_model

    stub = parse_model(exercise.stub.read_text(encoding="utf-8"), exercise.stub)
    return program_names(tuple(stub.includes), (), False)


def reserved(name: str, declared: bool) -> str:
    """Why a student may not write `name` ('' if they may)."""
    if name.lower().startswith(HARNESS_PREFIX):
        return (
            f"names starting with '{HARNESS_PREFIX}' belong to the lab's harness (its loop "
            "guard and private helpers)"
        )
    if "__" in name:
        return "GLSL reserves names containing '__' (two underscores), and WebGL rejects them"
    if declared and (name.startswith("gl_") or name.lower().startswith(("webgl_", "_webgl_"))):
        return "GLSL and WebGL reserve names starting with 'gl_', 'webgl_' and '_webgl_'"
    return ""


def check_names(code: str, label: str, library: dict[str, str], api: Iterable[str]) -> None:
    """Refuse (ScopeError) the first reserved name, library clash or library name outside
    `api` that the preprocessed `code` writes (uses are checked after declarations)."""
    for token in tokenize(code):
        if token.text == "discard":  # the pixel is thrown away: no value to grade there
            raise ScopeError(
                f"{label}:{token.line}: remove 'discard': the exercise's function returns a "
                "value for every input (return vec3(0.0) where the answer is zero); discard "
                "throws the grader's pixel away",
                token.line,
            )
    reading = read_code(code)
    api = list(api)
    given = ", ".join(api) if api else "nothing of the library"
    for name, line in sorted(reading.declared + reading.uses, key=lambda item: item[1]):
        why = reserved(name, (name, line) in reading.declared)
        if why:
            raise ScopeError(f"{label}:{line}: rename '{name}': {why}", line)
    for name, line in sorted(reading.globals.items(), key=lambda item: item[1]):
        if name not in library:
            continue
        where = library[name]
        if name in api:
            raise ScopeError(
                f"{label}:{line}: remove your definition of {name}: the lab gives it ({where}) "
                "and the grader's program already contains it; call the lab's",
                line,
            )
        raise ScopeError(
            f"{label}:{line}: rename your {name} (for example my_{name}): the lab's library "
            f"({where}) has a {name} too, which the grader's program contains with your file, "
            "and the two would clash",
            line,
        )
    for name, line in reading.uses:
        if name in library and name not in api and name not in reading.globals:
            raise ScopeError(
                f"{label}:{line}: {name} is part of the lab's library ({library[name]}), not of "
                f"this exercise's API: write it yourself in your file (the API is {given}, "
                "the header's parameters and GLSL's built-in functions)",
                line,
            )


class ScopeError(SourceError):
    """A submission names something it may not; `line` is 1-based in the student's file."""

"""Assemble complete GLSL programs from a model, its terms and a view template.

Every line of an assembled program remembers the file and line it came from, so a
compile error is reported against the model file the user edits, whatever driver
(Mesa, NVIDIA, AMD, Apple, ANGLE) produced it.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from pathlib import Path

from lab.constants import (
    LOOP_TOTAL,
    LOOP_TOTAL_FLAG,
    LOOP_TOTAL_WARNING,
    LOOP_WARNING,
    glsl_defines,
)
from lab.models import SHADER_DIR, Model, ModelError, Value

TARGETS = ("330", "300es")
VIEW_DIR = SHADER_DIR / "views"
# A view template's line naming a file (under shaders/) that goes in before it.
VIEW_INCLUDE = re.compile(r"^[ \t]*//[ \t]*@include[ \t]+(\S+)[ \t]*$", re.MULTILINE)

VERSION_LINES = {
    "330": ["#version 330 core"],
    "300es": ["#version 300 es", "precision highp float;", "precision highp int;"],
}

# View constants used when the caller gives no preamble (e.g. one light for the sphere).
DEFAULT_PREAMBLE = {"sphere": "const int LIGHT_COUNT = 1;"}

# A vertex shader shared by every view: one triangle that covers the viewport.
VERTEX_SHADER = """
void main() {
    vec2 corner = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
    gl_Position = vec4(corner * 2.0 - 1.0, 0.0, 1.0);
}
"""

# Directives a model file may not contain: the host writes them.
FORBIDDEN_DIRECTIVE = re.compile(r"^\s*#\s*(version|extension|include|line)\b")

# The loop guard: every loop of a model counts its iterations (per shader invocation) and
# stops past the bound, recording its line in lab_loop_line. A GPU freezes on a loop that
# never ends, and Mesa's llvmpipe silently ends every loop once all of them together have
# run 65,535 passes in one invocation: the guard also counts the passes of all loops and
# stops them before that (its line then carries LOOP_TOTAL_FLAG), so both are named.
LOOP_HEAD = re.compile(r"\b(for|while)\s*\(")
COMMENTS = re.compile(r"//[^\n]*|/\*.*?(?:\*/|\Z)", re.S)
LOOP_GUARD = """int lab_loop_line = 0;
int lab_loop_total = 0;
bool lab_loop_step(inout int count, int line) {
    count += 1;
    lab_loop_total += 1;
    if (count <= LAB_LOOP_LIMIT && lab_loop_total <= LAB_LOOP_TOTAL) return true;
    bool together = count <= LAB_LOOP_LIMIT;
    if (lab_loop_line == 0) lab_loop_line = together ? line + LAB_LOOP_TOTAL_FLAG : line;
    return false;
}"""
FLAG_OUTPUT = """#undef main
layout(location = 1) out vec4 lab_loop_flag;
void main() {
    lab_view_main();
    lab_loop_flag = vec4(float(lab_loop_line), 0.0, 0.0, 1.0);
}"""

# Where drivers put the line number in an info log; the first group is the line.
LOG_LINE_PATTERNS = [
    re.compile(r"^\s*(?:ERROR|WARNING):\s*\d+:(\d+):\s*(.*)$"),  # ANGLE, Apple, glslang
    re.compile(r"^\s*\d+:(\d+)\(\d+\):\s*(.*)$"),  # Mesa
    re.compile(r"^\s*\d+\((\d+)\)\s*:\s*(.*)$"),  # NVIDIA
]


@dataclass
class Source:
    """An assembled shader: its text and, for each line, where that line came from."""

    origins: list[tuple[str, int]] = field(default_factory=list)
    lines: list[str] = field(default_factory=list)

    def add(self, text: str, label: str, first_line: int = 1) -> None:
        for offset, line in enumerate(text.splitlines()):
            self.lines.append(line)
            self.origins.append((label, first_line + offset))

    @property
    def text(self) -> str:
        return "\n".join(self.lines) + "\n"

    def origin(self, line: int) -> tuple[str, int]:
        """(file, line) of the assembled program's 1-based `line`."""
        if 1 <= line <= len(self.origins):
            return self.origins[line - 1]
        return ("<assembled>", line)


@dataclass
class CompileError:
    file: str
    line: int
    message: str

    def __str__(self) -> str:
        return f"{self.file}:{self.line}: {self.message}"


class ShaderCompileError(Exception):
    """The driver rejected a program; `errors` point into the original files."""

    def __init__(self, errors: list[CompileError], log: str):
        self.errors = errors
        self.log = log
        super().__init__("\n".join(str(e) for e in errors) or log.strip())


def label_of(path: Path) -> str:
    """A short name for messages: relative to the project for library files."""
    try:
        return str(path.resolve().relative_to(SHADER_DIR.parent))
    except ValueError:
        return str(path)


def check_portable(code: str, label: str) -> None:
    """Reject directives that the host owns (they would break the assembled program)."""
    for number, line in enumerate(code.splitlines(), start=1):
        match = FORBIDDEN_DIRECTIVE.match(line)
        if match:
            raise ModelError(
                f"remove the '#{match.group(1)}' line: the lab adds version lines itself and "
                "shared terms are included with a '// @include' header line",
                label,
                number,
            )


def _closing(text: str, start: int) -> int | None:
    """Index of the parenthesis closing the one at `start`, or None."""
    depth = 0
    for index in range(start, len(text)):
        if text[index] == "(":
            depth += 1
        elif text[index] == ")":
            depth -= 1
            if depth == 0:
                return index
    return None


# A loop the guard stops in an exercise's sampler file reports its line plus this, so the
# grader can tell it from a line of the model file (lab.grading.exercise.sampler_model).
SAMPLER_LINE_BASE = 1_000_000


def guard_loops(code: str, counter: str = "lab_loop_", line_base: int = 0) -> tuple[str, list[int]]:
    """`code` with each loop's condition preceded by `lab_loop_step(counter, line) && `;
    also returns the loops' lines. Positions within a line shift, lines never do, so
    compile errors keep their line numbers. A do-while is guarded at its `while`.
    `counter` names the counters (`counter` + k) and `line_base` is added to the reported
    line, for a second guarded file in one program."""
    blank = COMMENTS.sub(lambda m: re.sub(r"[^\n]", " ", m.group(0)), code)
    inserts: list[tuple[int, str]] = []
    lines: list[int] = []
    for match in LOOP_HEAD.finditer(blank):
        start = match.end() - 1
        end = _closing(blank, start)
        if end is None:
            continue  # the compiler will report the unbalanced parenthesis
        line = blank.count("\n", 0, match.start()) + 1
        guard = f"lab_loop_step({counter}{len(lines)}, {line_base + line})"
        if match.group(1) == "for":
            depth, semis = 0, []
            for index in range(start + 1, end):
                depth += {"(": 1, ")": -1}.get(blank[index], 0)
                if blank[index] == ";" and depth == 0:
                    semis.append(index)
            if len(semis) != 2:
                continue
            first, second = semis[0] + 1, semis[1]
        else:
            first, second = start + 1, end
        if blank[first:second].strip():
            inserts += [(first, f"{guard} && ("), (second, ")")]
        else:
            inserts.append((first, guard))
        lines.append(line)
    for position, text in sorted(inserts, key=lambda item: item[0], reverse=True):
        code = code[:position] + text + code[position:]
    return code, lines


def loop_warning(model: Model, line: int) -> str:
    """The loop guard's message for the desktop lab and `watch` (the page's too)."""
    line, together = loop_cause(line)
    template = LOOP_TOTAL_WARNING if together else LOOP_WARNING
    return template.format(
        file=label_of(model.path),
        line=line,
        limit=f"{model.loop_limit:,}",
        total=f"{LOOP_TOTAL:,}",
        where="",
    )


def loop_guard_prelude(loops: int, limit: int) -> str:
    """The guard's counters and step function for `loops` loops, bound `limit` each."""
    counters = [f"int lab_loop_{k} = 0;" for k in range(loops)]
    bounds = [
        f"#define LAB_LOOP_LIMIT {int(limit)}",
        f"#define LAB_LOOP_TOTAL {LOOP_TOTAL}",
        f"#define LAB_LOOP_TOTAL_FLAG {LOOP_TOTAL_FLAG}",
    ]
    return "\n".join([*bounds, LOOP_GUARD, *counters])


def loop_cause(line: int) -> tuple[int, bool]:
    """A guard flag's line, and whether the loops together ran out (else that loop alone)."""
    return (line - LOOP_TOTAL_FLAG, True) if line >= LOOP_TOTAL_FLAG else (line, False)


def uniform_declarations(model: Model, enums: dict[str, str] | None = None) -> list[str]:
    """Uniforms for the parameters; enums become constants (one program per choice)."""
    lines = []
    for p in model.params.values():
        if p.kind == "enum":
            for index, choice in enumerate(p.choices):
                lines.append(f"const int {p.name.upper()}_{choice.upper()} = {index};")
            chosen = (enums or {}).get(p.name, p.default)
            lines.append(f"const int {p.name} = {p.name.upper()}_{chosen.upper()};")
        else:
            glsl_type = {"float": "float", "color": "vec3", "bool": "bool"}[p.kind]
            lines.append(f"uniform {glsl_type} {p.name};")
    return lines


def _add_include(source: Source, relative: str, seen: set[str], model: Model) -> None:
    path = (SHADER_DIR / relative).resolve()
    if relative in seen:
        return
    if not path.is_file() or SHADER_DIR.resolve() not in path.parents:
        line = next(
            (
                n
                for n, text in enumerate(model.code.splitlines(), 1)
                if "@include" in text and relative in text
            ),
            None,
        )
        raise ModelError(
            f"@include {relative}: no such file under shaders/ "
            "(see shaders/terms for the shared terms)",
            label_of(model.path),
            line,
        )
    seen.add(relative)
    source.add(path.read_text(encoding="utf-8"), label_of(path))


def assemble_fragment(
    model: Model,
    view: str,
    target: str = "330",
    preamble: str = "",
    enums: dict[str, str] | None = None,
) -> Source:
    """The fragment shader for `model` in `view` (a template in shaders/views).

    `preamble` holds view constants (such as the light count); `enums` picks each enum
    parameter's choice, compiled in as a constant so unused branches cost nothing.
    """
    if target not in TARGETS:
        raise ValueError(f"unknown GLSL target {target!r}: use one of {TARGETS}")
    model_label = label_of(model.path)
    check_portable(model.code, model_label)
    source = Source()
    source.add("\n".join(VERSION_LINES[target]), "<version>")
    source.add(glsl_defines(), "<constants>")
    preamble = preamble or DEFAULT_PREAMBLE.get(view, "")
    if preamble:
        source.add(preamble, "<preamble>")
    seen: set[str] = set()
    _add_include(source, "terms/common.glsl", seen, model)
    source.add("\n".join(uniform_declarations(model, enums)), f"{model_label} (parameters)")
    for include in model.includes:
        _add_include(source, include, seen, model)
    code, loops = guard_loops(model.code) if model.loop_limit > 0 else (model.code, [])
    source.add(loop_guard_prelude(len(loops), model.loop_limit), "<loop guard>")
    source.add(code, model_label)
    source.add(f"const bool IS_DELTA = {'true' if model.delta else 'false'};", "<host>")
    source.add(f"vec3 AMBIENT_REFLECTANCE() {{ return {model.ambient or 'vec3(1.0)'}; }}", "<host>")
    if not model.delta:
        source.add(
            "vec3 DELTA_REFLECTANCE(vec3 L, vec3 N, vec3 X, vec3 Y) { return vec3(0.0); }",
            "<host>",
        )
    view_path = VIEW_DIR / f"{view}.glsl"
    add_view(source, view_path.read_text(encoding="utf-8"), label_of(view_path))
    return source


def add_view(source: Source, text: str, label: str) -> None:
    """Add a view template, after the files its `// @include PATH` lines name (code that
    views share, such as the object's shapes); a fragment view also writes the loop guard's
    flag (the loop's line, 0 if none stopped) to a second colour output that the renderer
    can read back."""
    for relative in VIEW_INCLUDE.findall(text):
        path = SHADER_DIR / relative
        if not path.is_file():
            raise FileNotFoundError(f"{label}: @include {relative}: no such file under shaders/")
        source.add(path.read_text(encoding="utf-8"), label_of(path))
    output = "out vec4 frag_color;"
    if output not in text or "void main()" not in text:
        source.add(text, label)
        return
    text = text.replace(output, "layout(location = 0) " + output, 1)
    source.add("#define main lab_view_main", "<loop guard>")
    source.add(text, label)
    source.add(FLAG_OUTPUT, "<loop guard>")


def vertex_source(target: str = "330") -> str:
    return "\n".join(VERSION_LINES[target]) + "\n" + VERTEX_SHADER


def header(target: str = "330") -> str:
    """The version lines and the lab's constants: the start of a stand-alone shader."""
    return "\n".join(VERSION_LINES[target]) + "\n" + glsl_defines() + "\n"


def translate_log(log: str, source: Source) -> list[CompileError]:
    """Driver info log -> errors located in the original files."""
    errors = []
    for raw in log.splitlines():
        for pattern in LOG_LINE_PATTERNS:
            match = pattern.match(raw)
            if match:
                file, line = source.origin(int(match.group(1)))
                errors.append(CompileError(file, line, match.group(2).strip()))
                break
    return errors


def uniform_values(model: Model, values: dict[str, Value]) -> dict[str, object]:
    """Parameter values as the GL uniforms take them (enums become their index)."""
    out: dict[str, object] = {}
    for name, value in values.items():
        param = model.params[name]
        if param.kind == "enum":
            continue  # compiled in as a constant
        if param.kind == "bool":
            out[name] = bool(value)
        elif param.kind == "color":
            out[name] = tuple(float(c) for c in value)
        else:
            out[name] = float(value)
    return out

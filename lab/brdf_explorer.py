"""Read BRDF Explorer `.brdf` files (Disney's format) as lab models.

The format, as we read it:

    analytic                      first non-comment line
    ::begin parameters
    float NAME MIN MAX DEFAULT
    bool NAME 0|1
    color NAME R G B
    ::end parameters
    ::begin shader
    ... GLSL defining vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) ...
    ::end shader

Lines starting with `#` are comments in every section. The shaders were written for
`#version 410` and some use int literals where floats are meant, so they are compiled
with the highest GLSL version the context offers; errors point at the .brdf file's lines.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path

from lab import glsl
from lab.models import SHADER_DIR, Model, ModelError, Param

# Names a shader declares at global scope (constants, variables, functions).
DECLARATION = re.compile(
    r"^\s*(?:const\s+)?(?:float|int|uint|bool|[biu]?vec[234]|mat[234])\s+([A-Za-z_]\w*)\s*[=;(\[]",
    re.MULTILINE,
)


@dataclass
class ExplorerModel(Model):
    """A model read from a .brdf file; `shader_line` is where its GLSL starts in the file."""

    shader_line: int = 1


def _numbers(tokens: list[str], path: Path, line: int, what: str) -> list[float]:
    try:
        return [float(t) for t in tokens]
    except ValueError:
        got = " ".join(tokens)
        raise ModelError(f"{what}: expected numbers, got {got!r}", path, line) from None


def _parameter(text: str, path: Path, line: int) -> Param:
    tokens = text.split()
    kind = tokens[0]
    if kind not in ("float", "bool", "color") or len(tokens) < 2:
        raise ModelError(
            f"unknown parameter line {text!r}: write 'float NAME MIN MAX DEFAULT', "
            "'bool NAME 0|1' or 'color NAME R G B'",
            path,
            line,
        )
    name, args = tokens[1], tokens[2:]
    if not re.match(r"[A-Za-z_]\w*$", name):
        raise ModelError(f"parameter name {name!r} is not a GLSL identifier", path, line)
    if kind == "float":
        if len(args) != 3:
            raise ModelError(f"float {name}: write 'float {name} MIN MAX DEFAULT'", path, line)
        low, high, default = _numbers(args, path, line, f"float {name}")
        # BRDF Explorer is lenient; we widen the range rather than refuse the file.
        low, high = min(low, high, default), max(low, high, default)
        if low == high:
            high = low + 1.0
        # Wide positive ranges (exponents) move evenly on a log slider.
        scale = "log" if low > 0 and high / low >= 100 else "linear"
        return Param(name, "float", default, "", low, high, scale, line=line)
    if kind == "bool":
        if len(args) != 1 or args[0] not in ("0", "1"):
            raise ModelError(f"bool {name}: write 'bool {name} 0' or 'bool {name} 1'", path, line)
        return Param(name, "bool", args[0] == "1", "", line=line)
    if len(args) != 3:
        raise ModelError(f"color {name}: write 'color {name} R G B'", path, line)
    rgb = tuple(_numbers(args, path, line, f"color {name}"))
    return Param(name, "color", rgb, "", min(0.0, *rgb), max(1.0, *rgb), line=line)


def parse_brdf(text: str, path: str | Path) -> ExplorerModel:
    """Parse the text of a .brdf file; raises ModelError naming the file and line."""
    path = Path(path)
    lines = text.splitlines()
    params: dict[str, Param] = {}
    shader: list[str] = []
    shader_line = 0
    section = None
    seen_analytic = False
    for number, raw in enumerate(lines, start=1):
        stripped = raw.strip()
        if stripped.startswith("#"):
            if section == "shader":
                shader.append("")  # keep the shader's line numbers aligned with the file
            continue
        if stripped.startswith("::"):
            words = stripped[2:].split()
            if len(words) != 2 or words[0] not in ("begin", "end"):
                raise ModelError(f"malformed section line {stripped!r}", path, number)
            if words[0] == "begin":
                if section is not None:
                    raise ModelError(f"::begin {words[1]} inside ::begin {section}", path, number)
                section = words[1]
                if section == "shader":
                    shader_line = number + 1
            else:
                if words[1] != section:
                    raise ModelError(f"::end {words[1]} without ::begin {words[1]}", path, number)
                section = None
            continue
        if section == "shader":
            shader.append(raw)
            continue
        if not stripped:
            continue
        if not seen_analytic:
            if stripped != "analytic":
                raise ModelError(
                    f"expected 'analytic' as the first line, not {stripped!r} (only analytic "
                    "BRDF Explorer files can be opened)",
                    path,
                    number,
                )
            seen_analytic = True
            continue
        if section == "parameters":
            param = _parameter(stripped, path, number)
            if param.name in params:
                raise ModelError(f"parameter {param.name} is declared twice", path, number)
            params[param.name] = param
        elif section is None:
            raise ModelError(f"text outside any section: {stripped!r}", path, number)
        # Sections we do not use (BRDF Explorer has a few) are skipped.
    if section is not None:
        message = f"::begin {section} is never closed with ::end {section}"
        raise ModelError(message, path, len(lines))
    if not seen_analytic:
        raise ModelError("empty file: a .brdf file starts with the line 'analytic'", path, 1)
    if not shader_line:
        raise ModelError("no '::begin shader' section with the BRDF function", path, len(lines))
    code = "\n".join(shader)
    if not re.search(r"\bvec3\s+BRDF\s*\(", code):
        raise ModelError("the shader section defines no 'vec3 BRDF(vec3 L, vec3 V, ...)'", path,
                         shader_line)
    name = re.sub(r"\W", "_", path.stem)
    return ExplorerModel(
        name=name, path=path, code=code, title=f"BRDF Explorer model {path.name}",
        params=params, shader_line=shader_line,
    )


def read_brdf(path: str | Path) -> ExplorerModel:
    """Read a .brdf file from disk."""
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8", errors="replace")
    except OSError as err:
        raise ModelError(f"cannot read the file: {err.strerror}", path) from None
    return parse_brdf(text, path)


def glsl_version(ctx) -> int:
    """The highest GLSL version (e.g. 450) of a moderngl context; at least 330."""
    return max(330, int(getattr(ctx, "version_code", 330)))


def assemble(
    model: ExplorerModel, view: str, version: int, preamble: str = "", enums: dict | None = None
) -> glsl.Source:
    """The fragment shader for a .brdf model in `view`, lines mapped back to the file."""
    label = str(model.path)
    source = glsl.Source()
    source.add(f"#version {version} core", "<version>")
    if preamble:
        source.add(preamble, "<preamble>")
    common = (SHADER_DIR / "terms" / "common.glsl").read_text(encoding="utf-8")
    # .brdf files often declare PI themselves; rename ours while it is declared.
    clashes = sorted(set(DECLARATION.findall(common)) & set(DECLARATION.findall(model.code)))
    for name in clashes:
        source.add(f"#define {name} lab_{name}", "<host>")
    source.add(common, glsl.label_of(SHADER_DIR / "terms" / "common.glsl"))
    for name in clashes:
        source.add(f"#undef {name}", "<host>")
    source.add("\n".join(glsl.uniform_declarations(model, enums)), f"{label} (parameters)")
    source.add(model.code, label, first_line=model.shader_line)
    source.add("const bool IS_DELTA = false;", "<host>")
    source.add("vec3 DELTA_REFLECTANCE(vec3 L, vec3 N, vec3 X, vec3 Y) { return vec3(0.0); }",
               "<host>")
    view_path = glsl.VIEW_DIR / f"{view}.glsl"
    source.add(view_path.read_text(encoding="utf-8"), glsl.label_of(view_path))
    return source

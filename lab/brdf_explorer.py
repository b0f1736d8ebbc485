"""Read BRDF Explorer `.brdf` files (Disney's format) as lab models.

The format, as BRDF Explorer reads it and as we read it:

    analytic                      the type: the first line (words after it are ignored)
    ::begin parameters
    float NAME MIN MAX DEFAULT    a slider (MIN may exceed MAX; DEFAULT may lie outside)
    bool NAME 0|1                 a check box (any other integer means true)
    color NAME R G B              a colour
    ::end parameters
    ::begin shader
    ... GLSL defining vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) ...
    ::end shader

Blank lines and lines whose first non-blank character is `#` are skipped everywhere,
the shader included. Words after a parameter's values are ignored (`# text` after them
becomes the parameter's description). Text outside the sections and sections other than
`parameters` and `shader` (e.g. `isFunc`, an importance sampler) are ignored. With
several shader sections the last one counts. The shaders were written for `#version 410`
and lean on its implicit int-to-float conversions, so they are compiled with the highest
GLSL version the context offers (int arithmetic stays int: `1/4` is 0, as in BRDF
Explorer; the web page's GLSL ES conversion keeps that, static/explorer.js floatLiterals);
compile errors point at the .brdf file's lines.

Assembly keeps the file's GLSL and the lab's apart: names the file declares that our
helpers or the view also declare (`PI`, `sqr`, ...) are renamed on our side, built-in
functions the file redefines (`reflect`, `smoothstep`) are renamed on the file's side,
and the file's `BRDF` is wrapped to follow the lab's contract (0 outside the hemisphere;
NaN shown as 0, as BRDF Explorer's display does).
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path

from lab import glsl
from lab.constants import glsl_defines
from lab.models import SHADER_DIR, Model, ModelError, Param

# Names declared at the start of a line: constants, globals, uniforms, functions.
DECLARATION = re.compile(
    r"^\s*(?:(?:const|uniform|in|out|flat|highp|mediump|lowp)\s+)*"
    r"(?:void|float|double|int|uint|bool|[biud]?vec[234]|mat[234](?:x[234])?|\w*sampler\w*)"
    r"\s+([A-Za-z_]\w*)\s*[=;(\[]",
    re.MULTILINE,
)
# A function definition or prototype: TYPE NAME(
FUNCTION = re.compile(
    r"^\s*(?:(?:highp|mediump|lowp)\s+)?"
    r"(?:void|float|double|int|uint|bool|[biud]?vec[234]|mat[234](?:x[234])?)"
    r"\s+([A-Za-z_]\w*)\s*\(",
    re.MULTILINE,
)

# GLSL built-in functions a shader might redefine. In Mesa a redefinition hides the
# built-in for the rest of the program, our view templates included.
BUILTINS = frozenset(
    """radians degrees sin cos tan asin acos atan sinh cosh tanh asinh acosh atanh pow exp
    log exp2 log2 sqrt inversesqrt abs sign floor trunc round roundEven ceil fract mod modf
    min max clamp mix step smoothstep isnan isinf fma frexp ldexp length distance dot cross
    normalize faceforward reflect refract matrixCompMult outerProduct transpose determinant
    inverse lessThan lessThanEqual greaterThan greaterThanEqual equal notEqual any all not
    dFdx dFdy fwidth texture texelFetch textureSize""".split()
)

# Words GLSL 4.x reserves: a parameter (a uniform) cannot be called that.
KEYWORDS = frozenset(
    """attribute const uniform varying buffer shared coherent volatile restrict readonly
    writeonly atomic_uint layout centroid flat smooth noperspective patch sample break
    continue do for while switch case default if else subroutine in out inout float double
    int void bool true false invariant precise discard return lowp mediump highp precision
    struct common partition active asm class union enum typedef template this resource
    goto inline noinline public static extern external interface long short half fixed
    unsigned superp input output filter sizeof cast namespace using""".split()
)
TYPE_NAME = re.compile(r"(?:[biud]?vec[234]|d?mat[234](?:x[234])?|u?int|\w*sampler\w*|image\w*)$")
NUMBER = re.compile(r"[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?[fF]?$")
USAGE = "write 'float NAME MIN MAX DEFAULT', 'bool NAME 0|1' or 'color NAME R G B'"


@dataclass
class ExplorerModel(Model):
    """A model read from a .brdf file; `shader_line` is where its GLSL starts in the file."""

    shader_line: int = 1


def _number(token: str, path: Path, line: int, what: str) -> float:
    if not NUMBER.match(token):
        raise ModelError(f"{what}: the values must be numbers, not {token!r}", path, line)
    return float(token.rstrip("fF"))


def _parameter(text: str, path: Path, line: int) -> Param:
    tokens = text.split()
    kind = tokens[0]
    if kind not in ("float", "bool", "color") or len(tokens) < 2:
        raise ModelError(f"unknown parameter line {text!r}: {USAGE}", path, line)
    name = tokens[1]
    if not re.match(r"[A-Za-z_]\w*$", name):
        raise ModelError(f"parameter name {name!r} is not a GLSL identifier", path, line)
    if name in KEYWORDS or TYPE_NAME.match(name) or name.startswith("gl_") or "__" in name:
        raise ModelError(f"parameter name {name!r} is reserved by GLSL: rename it", path, line)
    count = {"float": 3, "bool": 1, "color": 3}[kind]
    args = tokens[2 : 2 + count]
    # BRDF Explorer reads only the values it needs; a trailing '# text' describes them.
    rest = " ".join(tokens[2 + count :])
    doc = rest.lstrip("#/ ").strip() if rest.startswith(("#", "//")) else ""
    if len(args) < count:
        form = {"float": "MIN MAX DEFAULT", "bool": "0|1", "color": "R G B"}[kind]
        raise ModelError(f"{kind} {name}: write '{kind} {name} {form}'", path, line)
    if kind == "bool":
        word = args[0].lower()
        if re.match(r"[+-]?\d+$", word):
            return Param(name, "bool", int(word) != 0, doc, line=line)
        if word in ("true", "false"):
            return Param(name, "bool", word == "true", doc, line=line)
        raise ModelError(f"bool {name}: write 'bool {name} 0' or 'bool {name} 1'", path, line)
    numbers = [_number(t, path, line, f"{kind} {name}") for t in args]
    if kind == "float":
        low, high, default = numbers
        # BRDF Explorer's slider spans MIN..MAX either way round and its text box takes
        # any value; our values are checked against the range, so it holds the default.
        low, high = min(low, high, default), max(low, high, default)
        if low == high:
            high = low + 1.0
        # Wide positive ranges (exponents) move evenly on a log slider.
        scale = "log" if low > 0 and high / low >= 100 else "linear"
        return Param(name, "float", default, doc, low, high, scale, line=line)
    rgb = tuple(numbers)
    return Param(name, "color", rgb, doc, min(0.0, *rgb), max(1.0, *rgb), line=line)


def _section_marker(stripped: str) -> tuple[str, str] | None:
    """('begin'|'end', NAME) for a section line; None for any other line."""
    words = stripped.split()
    if words[0] not in ("::begin", "::end"):
        return None
    return words[0][2:], words[1] if len(words) > 1 else ""


def parse_brdf(text: str, path: str | Path) -> ExplorerModel:
    """Parse the text of a .brdf file; raises ModelError naming the file and line."""
    path = Path(path)
    lines = text.removeprefix("\ufeff").splitlines()
    params: dict[str, Param] = {}
    shader: list[str] = []
    shader_line = 0
    section = ""
    seen_type = False
    for number, raw in enumerate(lines, start=1):
        stripped = raw.strip()
        if not stripped or stripped.startswith("#"):
            if section == "shader":
                shader.append("")  # keep the shader's line numbers aligned with the file
            continue
        if not seen_type:
            kind = stripped.split()[0]
            if kind == "bparam":
                raise ModelError(
                    "this is a BRDF Explorer parameter file (bparam): open the .brdf file it "
                    "names instead",
                    path,
                    number,
                )
            if kind != "analytic":
                raise ModelError(
                    f"expected 'analytic' as the first line, not {stripped!r} (only analytic "
                    "BRDF Explorer files can be opened)",
                    path,
                    number,
                )
            seen_type = True
            continue
        marker = _section_marker(stripped)
        if marker is not None:
            action, name = marker
            if not name:
                raise ModelError(
                    f"'{stripped}' needs a section name, e.g. '::{action} shader'", path, number
                )
            if action == "begin":
                if section:
                    raise ModelError(
                        f"::begin {name} inside ::begin {section} (close it with "
                        f"::end {section} first)",
                        path,
                        number,
                    )
                section = name
                if section == "shader":  # as in BRDF Explorer, a later shader section wins
                    shader, shader_line = [], number + 1
            else:
                if name != section:
                    raise ModelError(f"::end {name} without ::begin {name}", path, number)
                section = ""
            continue
        if section == "shader":
            shader.append(raw)
        elif section == "parameters":
            param = _parameter(stripped, path, number)
            if param.name in params:
                raise ModelError(f"parameter {param.name} is declared twice", path, number)
            params[param.name] = param
        # BRDF Explorer ignores text outside sections and sections it has no use for.
    if not seen_type:
        raise ModelError("empty file: a .brdf file starts with the line 'analytic'", path, 1)
    if section:
        message = f"::begin {section} is never closed with ::end {section}"
        raise ModelError(message, path, len(lines))
    if not shader_line:
        raise ModelError("no '::begin shader' section with the BRDF function", path, len(lines))
    code = "\n".join(shader)
    if not re.search(r"\bvec3\s+BRDF\s*\(", code):
        raise ModelError(
            "the shader section defines no 'vec3 BRDF(vec3 L, vec3 V, ...)'", path, shader_line
        )
    name = re.sub(r"\W", "_", path.stem)
    return ExplorerModel(
        name=name,
        path=path,
        code=code,
        title=f"BRDF Explorer model {path.name}",
        params=params,
        shader_line=shader_line,
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


# The lab's side of the program: the file's BRDF follows the lab's contract through it.
HOST_BRDF = """\
vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {
    if (dot(N, L) <= 0.0 || dot(N, V) <= 0.0) return vec3(0.0);
    vec3 f = explorer_BRDF(L, V, N, X, Y);
    return mix(f, vec3(0.0), isnan(f));
}
const bool IS_DELTA = false;
vec3 DELTA_REFLECTANCE(vec3 L, vec3 N, vec3 X, vec3 Y) { return vec3(0.0); }
vec3 AMBIENT_REFLECTANCE() { return vec3(1.0); }"""


def _defines(names, prefix: str) -> tuple[str, str]:
    """`#define NAME PREFIXNAME` lines for `names` and the `#undef` lines that end them."""
    names = sorted(names)
    return (
        "\n".join(f"#define {n} {prefix}{n}" for n in names),
        "\n".join(f"#undef {n}" for n in names),
    )


def assemble(
    model: ExplorerModel, view: str, version: int, preamble: str = "", enums: dict | None = None
) -> glsl.Source:
    """The fragment shader for a .brdf model in `view`, lines mapped back to the file."""
    label = str(model.path)
    common_path = SHADER_DIR / "terms" / "common.glsl"
    view_path = glsl.VIEW_DIR / f"{view}.glsl"
    common = common_path.read_text(encoding="utf-8")
    view_text = view_path.read_text(encoding="utf-8")
    preamble = preamble or glsl.DEFAULT_PREAMBLE.get(view, "")
    host_names = set(DECLARATION.findall("\n".join((preamble, common, HOST_BRDF, view_text))))
    file_names = set(DECLARATION.findall(model.code)) | set(model.params)
    # Our helpers and view step aside where the file (or a parameter) uses their names.
    ours = (host_names & file_names) - {"main", "BRDF"}
    host_on, host_off = _defines(ours, "lab_")
    # The file's redefinitions of built-ins stay its own, so the view keeps the real ones.
    theirs = (set(FUNCTION.findall(model.code)) & BUILTINS) | {"BRDF"}
    file_on, file_off = _defines(theirs, "explorer_")

    source = glsl.Source()
    source.add(f"#version {version} core", "<version>")
    source.add(glsl_defines(), "<constants>")
    source.add(host_on, "<host>")
    if preamble:
        source.add(preamble, "<preamble>")
    source.add(common, glsl.label_of(common_path))
    source.add(host_off, "<host>")
    source.add("\n".join(glsl.uniform_declarations(model, enums)), f"{label} (parameters)")
    source.add(file_on, "<host>")
    code, loops = glsl.guard_loops(model.code)
    source.add(glsl.loop_guard_prelude(len(loops), model.loop_limit), "<loop guard>")
    source.add(code, label, first_line=model.shader_line)
    source.add(file_off, "<host>")
    source.add(host_on, "<host>")
    source.add(HOST_BRDF, "<host>")
    glsl.add_view(source, view_text, glsl.label_of(view_path))
    source.add(host_off, "<host>")
    return source

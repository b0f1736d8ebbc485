"""Model files and their headers: the one place where parameters are declared.

The header format is documented in shaders/README.md.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field
from pathlib import Path

from lab.constants import LOOP_LIMIT
from lab.resources import data_dir, install_line

SHADER_DIR = data_dir("shaders").resolve()
MODEL_DIR = SHADER_DIR / "brdfs"

PARAM_TYPES = ("float", "color", "bool", "enum")
IDENTIFIER = re.compile(r"[A-Za-z_][A-Za-z0-9_]*$")

Value = float | bool | str | tuple[float, float, float]


# What a model's header may claim (@property); the physics tests hold each model to them.
PROPERTIES = ("reciprocal", "isotropic", "energy-conserving")


class ModelError(ValueError):
    """A problem in a model file or a parameter value, with where it happened."""

    def __init__(self, message: str, file: str | Path | None = None, line: int | None = None):
        self.file = str(file) if file is not None else None
        self.line = line
        self.message = message
        where = (
            f"{self.file}:{line}: "
            if self.file and line
            else (f"{self.file}: " if self.file else "")
        )
        super().__init__(where + message)


@dataclass(frozen=True)
class Param:
    """One parameter of a model, as its header declares it."""

    name: str
    kind: str  # float | color | bool | enum
    default: Value
    doc: str = ""
    minimum: float = 0.0
    maximum: float = 1.0
    scale: str = "linear"  # linear | log (slider spacing)
    choices: tuple[str, ...] = ()
    line: int = 0

    def parse(self, text: str) -> Value:
        """Value from command-line text (`0.5`, `0.2,0.3,0.4`, `true`, `beckmann`)."""
        text = text.strip()
        if self.kind == "enum":
            if text not in self.choices:
                raise ModelError(
                    f"{self.name} must be one of {', '.join(self.choices)}, not {text!r}"
                )
            return text
        if self.kind == "bool":
            lowered = text.lower()
            if lowered in ("1", "true", "yes", "on"):
                return True
            if lowered in ("0", "false", "no", "off"):
                return False
            raise ModelError(f"{self.name} is a bool: use true/false or 1/0, not {text!r}")
        parts = [p for p in text.split(",")]
        try:
            numbers = [float(p) for p in parts]
        except ValueError:
            raise ModelError(f"{self.name} needs a number, not {text!r}") from None
        if self.kind == "color":
            if len(numbers) == 1:
                numbers *= 3
            if len(numbers) != 3:
                raise ModelError(
                    f"{self.name} is a color: give r,g,b or one grey value, not {text!r}"
                )
            return self.check(tuple(numbers))
        if len(numbers) != 1:
            raise ModelError(f"{self.name} is a single number, not {text!r}")
        return self.check(numbers[0])

    def check(self, value: Value) -> Value:
        """The value, validated and normalized to its canonical Python type."""
        if self.kind == "enum":
            if isinstance(value, (int, float)) and not isinstance(value, bool):
                index = int(value)
                if 0 <= index < len(self.choices):
                    return self.choices[index]
            if value not in self.choices:
                raise ModelError(
                    f"{self.name} must be one of {', '.join(self.choices)}, not {value!r}"
                )
            return value
        if self.kind == "bool":
            return bool(value)
        if self.kind == "color":
            if isinstance(value, (int, float)):
                value = (value,) * 3
            rgb = tuple(float(c) for c in value)
            if len(rgb) != 3 or not all(math.isfinite(c) for c in rgb):
                raise ModelError(f"{self.name} is a color of three finite numbers, not {value!r}")
            if any(c < self.minimum or c > self.maximum for c in rgb):
                raise ModelError(
                    f"{self.name}={','.join(f'{c:g}' for c in rgb)} is outside its range "
                    f"[{self.minimum:g}, {self.maximum:g}] per channel"
                )
            return rgb
        number = float(value)
        if not math.isfinite(number) or number < self.minimum or number > self.maximum:
            raise ModelError(
                f"{self.name}={number:g} is outside its range [{self.minimum:g}, {self.maximum:g}]"
            )
        return number

    def header_line(self) -> str:
        """This parameter as a header line (used to write files and in listings)."""
        if self.kind == "float":
            spec = f"{self.minimum:g} {self.maximum:g} {self.default:g} {self.scale}"
        elif self.kind == "color":
            spec = " ".join(f"{c:g}" for c in self.default)
        elif self.kind == "bool":
            spec = "1" if self.default else "0"
        else:
            spec = " ".join(self.choices)
        return f"// @param {self.name} {self.kind} {spec} | {self.doc}"


@dataclass
class Model:
    """A reflection model: its parsed header and its GLSL code."""

    name: str
    path: Path
    code: str
    title: str = ""
    formula: list[str] = field(default_factory=list)
    source: list[str] = field(default_factory=list)
    includes: list[str] = field(default_factory=list)
    params: dict[str, Param] = field(default_factory=dict)
    delta: bool = False
    ambient: str = ""  # the colour parameter that reflects ambient light (@ambient)
    properties: list[str] = field(default_factory=list)  # @property: what tests hold it to
    # iterations a loop may run per invocation (lab.glsl's guard); 0 turns the guard off,
    # for grade-bench's baseline only
    loop_limit: int = LOOP_LIMIT

    def defaults(self) -> dict[str, Value]:
        return {p.name: p.default for p in self.params.values()}

    def header(self) -> dict:
        """The parsed header as JSON data, shaped as the web page's parser makes it
        (static/header.js): the manifest carries the library's so the page need not parse."""
        params = [
            {
                "name": p.name,
                "kind": p.kind,
                "default": list(p.default) if isinstance(p.default, tuple) else p.default,
                "doc": p.doc,
                "minimum": p.minimum,
                "maximum": p.maximum,
                "scale": p.scale,
                "choices": list(p.choices),
                "line": p.line,
            }
            for p in self.params.values()
        ]
        return {
            "name": self.name,
            "title": self.title,
            "formula": list(self.formula),
            "source": list(self.source),
            "includes": list(self.includes),
            "delta": self.delta,
            "ambient": self.ambient,
            "properties": list(self.properties),
            "params": params,
        }

    def resolve(self, values: dict[str, Value] | None = None) -> dict[str, Value]:
        """Defaults overridden by `values`, each checked against the header."""
        resolved = self.defaults()
        for name, value in (values or {}).items():
            if name not in self.params:
                known = ", ".join(self.params) or "none"
                raise ModelError(f"model {self.name} has no parameter {name!r} (it has: {known})")
            resolved[name] = self.params[name].check(value)
        return resolved

    def parse_settings(self, settings: list[str]) -> dict[str, Value]:
        """`NAME=VALUE` strings (the CLI's --set) to checked values."""
        values: dict[str, Value] = {}
        for item in settings:
            name, sep, text = item.partition("=")
            name = name.strip()
            if not sep or not name or not text.strip():
                raise ModelError(f"--set {item!r} is malformed: write NAME=VALUE, e.g. ke=50")
            if name not in self.params:
                known = ", ".join(self.params) or "none"
                raise ModelError(f"model {self.name} has no parameter {name!r} (it has: {known})")
            values[name] = self.params[name].parse(text)
        return self.resolve(values)


def _number(token: str, what: str, path: Path, line: int) -> float:
    try:
        value = float(token)
    except ValueError:
        raise ModelError(f"{what} must be a number, not {token!r}", path, line) from None
    if not math.isfinite(value):
        raise ModelError(f"{what} must be finite, not {token!r}", path, line)
    return value


def parse_param(text: str, path: Path, line: int) -> Param:
    """One `@param` line (without the `// @param` prefix)."""
    spec, _, doc = text.partition("|")
    tokens = spec.split()
    usage = "write '@param NAME TYPE ... | meaning' (see shaders/README.md)"
    if len(tokens) < 2:
        raise ModelError(f"incomplete @param line: {usage}", path, line)
    name, kind, args = tokens[0], tokens[1], tokens[2:]
    if not IDENTIFIER.match(name):
        raise ModelError(f"parameter name {name!r} is not a GLSL identifier", path, line)
    if kind not in PARAM_TYPES:
        raise ModelError(
            f"unknown parameter type {kind!r}: use one of {', '.join(PARAM_TYPES)}", path, line
        )
    doc = doc.strip()
    if kind == "float":
        if len(args) not in (3, 4):
            raise ModelError(
                f"float parameter {name}: write 'MIN MAX DEFAULT [linear|log]'", path, line
            )
        low, high, default = (_number(a, f"{name} range/default", path, line) for a in args[:3])
        scale = args[3] if len(args) == 4 else "linear"
        if scale not in ("linear", "log"):
            raise ModelError(
                f"{name}: slider scale must be linear or log, not {scale!r}", path, line
            )
        if not low < high:
            raise ModelError(f"{name}: MIN ({low:g}) must be below MAX ({high:g})", path, line)
        if not low <= default <= high:
            raise ModelError(
                f"{name}: default {default:g} is outside [{low:g}, {high:g}]", path, line
            )
        if scale == "log" and low <= 0:
            raise ModelError(f"{name}: a log slider needs MIN > 0", path, line)
        return Param(name, kind, default, doc, low, high, scale, line=line)
    if kind == "color":
        if len(args) != 3:
            raise ModelError(f"color parameter {name}: write 'R G B' (each 0..1)", path, line)
        rgb = tuple(_number(a, f"{name} channel", path, line) for a in args)
        if any(not 0.0 <= c <= 1.0 for c in rgb):
            raise ModelError(f"color parameter {name}: channels must be in 0..1", path, line)
        return Param(name, kind, rgb, doc, 0.0, 1.0, line=line)
    if kind == "bool":
        if len(args) != 1 or args[0] not in ("0", "1"):
            raise ModelError(f"bool parameter {name}: write 0 or 1 as the default", path, line)
        return Param(name, kind, args[0] == "1", doc, line=line)
    if not args:
        raise ModelError(
            f"enum parameter {name}: list its choices (the first is the default)", path, line
        )
    for choice in args:
        if not IDENTIFIER.match(choice):
            raise ModelError(f"enum choice {choice!r} of {name} is not an identifier", path, line)
    if len(set(args)) != len(args):
        raise ModelError(f"enum parameter {name} lists a choice twice", path, line)
    return Param(name, kind, args[0], doc, choices=tuple(args), line=line)


def parse_model(code: str, path: Path | str, expected_name: str | None = None) -> Model:
    """Parse a model file's header; `code` is kept whole for the compiler."""
    path = Path(path)
    model = Model(name=expected_name or path.stem, path=path, code=code)
    named = False
    ambient_line = 0
    for number, raw in enumerate(code.splitlines(), start=1):
        stripped = raw.strip()
        if not stripped:
            continue
        if not stripped.startswith("//"):
            break  # the header ends at the first line of code
        body = stripped[2:].strip()
        if not body.startswith("@"):
            continue
        keyword, _, rest = body[1:].partition(" ")
        rest = rest.strip()
        if keyword == "model":
            if not IDENTIFIER.match(rest):
                raise ModelError(f"@model name {rest!r} is not an identifier", path, number)
            model.name, named = rest, True
        elif keyword == "title":
            model.title = rest
        elif keyword == "formula":
            model.formula.append(rest)
        elif keyword == "source":
            model.source.append(rest)
        elif keyword == "include":
            model.includes.append(rest)
        elif keyword == "delta":
            model.delta = True
        elif keyword == "ambient":
            model.ambient, ambient_line = rest, number
        elif keyword == "property":
            for word in rest.split():
                if word not in PROPERTIES:
                    raise ModelError(
                        f"@property {word}: unknown property; use {', '.join(PROPERTIES)}",
                        path,
                        number,
                    )
                if word not in model.properties:
                    model.properties.append(word)
        elif keyword == "param":
            param = parse_param(rest, path, number)
            if param.name in model.params:
                raise ModelError(f"parameter {param.name} is declared twice", path, number)
            model.params[param.name] = param
        else:
            raise ModelError(
                f"unknown header keyword @{keyword}: use @model, @title, @formula, @source, "
                "@include, @delta, @ambient, @property or @param",
                path,
                number,
            )
    if ambient_line:
        param = model.params.get(model.ambient)
        if param is None or param.kind != "color":
            raise ModelError(
                f"@ambient {model.ambient}: name a color parameter of this model "
                "(declared with '@param NAME color R G B')",
                path,
                ambient_line,
            )
    if named and expected_name and model.name != expected_name:
        raise ModelError(f"@model {model.name} does not match the file name {path.name}", path, 1)
    return model


def model_names() -> list[str]:
    """Names of the models in the library, sorted."""
    if not MODEL_DIR.is_dir():
        raise ModelError(
            f"the shader library {MODEL_DIR} is missing from this install of brdf-lab: "
            f'reinstall it (pip install --force-reinstall "{install_line()}", or '
            "'pip install -e .' in a clone)"
        )
    return sorted(p.stem for p in MODEL_DIR.glob("*.glsl"))


def load_model(name_or_path: str | Path) -> Model:
    """A library model by name, or a .glsl model file by path.

    Front ends open models with `lab.sources.open_model`, which also reads BRDF
    Explorer's .brdf files and measured tables.
    """
    candidate = Path(name_or_path)
    if candidate.exists() and candidate.suffix != ".glsl":
        raise ModelError(
            f"not a model file: a model is GLSL in a .glsl file (or a BRDF Explorer .brdf, a "
            f"MERL .binary table); rename it to {candidate.stem}.glsl if it holds a model",
            candidate,
        )
    if candidate.suffix == ".glsl":
        path = candidate
    else:
        path = MODEL_DIR / f"{name_or_path}.glsl"
        if not path.exists():
            raise ModelError(
                f"unknown model {name_or_path!r}: choose one of {', '.join(model_names())} "
                "(or give a path to a .glsl file)"
            )
    try:
        raw = path.read_bytes()
    except OSError as err:
        raise ModelError(f"cannot read model file: {err.strerror}", path) from None
    try:
        code = raw.decode("utf-8")
    except UnicodeDecodeError as err:
        line = raw[: err.start].count(b"\n") + 1
        raise ModelError("file is not UTF-8 text; save it as UTF-8", path, line) from None
    model = parse_model(code, path, expected_name=path.stem if path.parent == MODEL_DIR else None)
    if not DEFINES_BRDF.search(_without_comments(code)):
        raise ModelError(
            "defines no function 'vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y)': every "
            "view calls it (see shaders/README.md; names are case-sensitive)",
            path,
        )
    return model


DEFINES_BRDF = re.compile(r"\bvec3\s+BRDF\s*\(")


def _without_comments(code: str) -> str:
    """GLSL with its // and /* */ comments removed (a BRDF in a comment defines nothing)."""
    return re.sub(r"//[^\n]*|/\*.*?\*/", " ", code, flags=re.S)

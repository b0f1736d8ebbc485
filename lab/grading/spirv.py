"""Submissions as optimised SPIR-V, for the similarity report (lab.grading.similarity).

A submission is compiled with the library code it may call (common.glsl and the exercise's
includes) and a `main` that calls the functions the exercise asks for, by glslang to SPIR-V,
then optimised by `spirv-opt -O` (Debian's spirv-tools): functions are inlined, dead code and
unused variables vanish, and names are only debug information. Each instruction of the
result becomes a feature: its opcode, type and constant, and the same for the instructions
that compute its operands, two levels down, so that ids, their numbering and the order of
independent statements do not count. A copy with dummy statements, renamed variables or a
library call inlined by hand gives the same features; a formula written another way does not.
"""

from __future__ import annotations

import hashlib
import re
import shutil
import subprocess
import tempfile
from collections import Counter
from functools import cache
from pathlib import Path

from lab.constants import glsl_defines
from lab.models import SHADER_DIR, load_model, parse_model

TOOLS = ("glslangValidator", "spirv-opt", "spirv-dis")
SECONDS = 20.0  # per file: the optimiser on a long loop takes well under a second
DEPTH = 2  # levels of operands in a feature
# Levels for the class's pairs (what two students share beyond the references): one level
# keeps a student's separate choices apart instead of multiplying them into rare-looking
# combinations; honest pairs then share less (tests/test_similarity_class.py).
PAIR_DEPTH = 1
# Instructions that carry names, debug information or the module's frame, not code.
SKIP = re.compile(
    r"Op(Name|MemberName|Decorate|MemberDecorate|Source\w*|Line|NoLine|String|ModuleProcessed"
    r"|Capability|Extension|ExtInstImport|MemoryModel|EntryPoint|ExecutionMode)$"
)
INSTRUCTION = re.compile(r"^\s*(?:(%\w+)\s*=\s*)?(Op\w+)(.*)$")
GLSL_TYPES = {"float": "float", "color": "vec3", "bool": "bool", "enum": "int"}


# The library's own code for an exercise's sampler: its model's lobe, from sampling.glsl.
LIBRARY_LOBES = {
    "blinn_phong": """
vec3 sample_lobe(vec2 u, vec3 V, vec3 N, vec3 X, vec3 Y) {
    return reflect_about(V, sample_power_cosine(u, N, ke));
}
float pdf_lobe(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {
    vec3 H = normalize(L + V);
    return half_to_light_pdf(pdf_power_cosine(H, N, ke), V, H);
}
"""
}


# An estimator exercise's (14) given functions: the model's BRDF and the map, made opaque
# as the library's are, and random numbers that change from call to call (as
# lab.ibl.integrator.ESTIMATOR_LINE's do), so the optimiser cannot fold the samples into one.
ESTIMATOR_GIVEN = """
vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) { return L; }
vec3 environment(vec3 d) { return d; }
"""
ESTIMATOR_RANDOM = """
uint lab_draws = 0u;
vec2 random2() { lab_draws += 1u; return vec2(float(lab_draws) * 0.37, float(lab_draws) * 0.61); }
"""


def library_text(exercise) -> str | None:
    """The library's code for what the exercise asks: its lobe sampler, the term file the
    student's file replaces, or its model's file (None if there is none)."""
    if exercise.sampler_for:  # (an estimator's model has no estimate of its own)
        return (
            None
            if getattr(exercise, "estimator", False)
            else LIBRARY_LOBES.get(exercise.sampler_for)
        )
    if exercise.replaces:
        path = SHADER_DIR / exercise.replaces
    else:
        path = SHADER_DIR / "brdfs" / f"{exercise.model_name}.glsl"
    return path.read_text(encoding="utf-8") if path.is_file() else None


def available() -> bool:
    """Whether glslang and spirv-tools are installed (else similarity uses tokens only)."""
    return all(shutil.which(tool) for tool in TOOLS)


def _parameters(exercise) -> str:
    """The model's parameters as one uniform block (opaque to the optimiser)."""
    if exercise.sampler_for or exercise.wrapper:
        params = load_model(exercise.sampler_for or exercise.wrapper).params
    else:
        params = parse_model(exercise.stub.read_text(encoding="utf-8"), exercise.stub).params
    members, constants = [], []
    for p in params.values():
        members.append(f"    {GLSL_TYPES[p.kind]} {p.name};")
        for index, choice in enumerate(p.choices or []):
            constants.append(f"const int {p.name.upper()}_{choice.upper()} = {index};")
    block = "layout(std140, binding = 0) uniform LabParams {\n" + "\n".join(members) + "\n};"
    return "\n".join(constants) + "\n" + block if members else "\n".join(constants)


def _main(functions: list[str]) -> str:
    """Inputs for every argument, and a main adding up what each function returns."""
    lines, calls, location = [], [], 0
    for signature in functions:
        name = re.match(r"\s*\w+\s+(\w+)", signature).group(1)
        result = signature.split()[0]
        args = []
        for part in re.search(r"\((.*)\)", signature).group(1).split(","):
            words = part.split()
            kind, arg = words[-2], words[-1]
            array = re.search(r"\[\d+\]", arg)
            lines.append(
                f"layout(location = {location}) flat in {kind} lab_in_{location}"
                f"{array.group() if array else ''};"
            )
            args.append(f"lab_in_{location}")
            location += int(array.group()[1:-1]) if array else 1
        call = f"{name}({', '.join(args)})"
        size = result[-1] if result[-1] in "234" else "1"  # ivec3 counts as vec3, int as float
        target = {"1": "lab_out.r", "2": "lab_out.rg", "3": "lab_out.rgb", "4": "lab_out"}[size]
        convert = "float" if size == "1" else f"vec{size}"
        calls.append(f"    {target} += {convert}({call});")
    lines.append("layout(location = 0) out vec4 lab_out;")
    return "\n".join([*lines, "void main() {", "    lab_out = vec4(0.0);", *calls, "}"])


_FRAMES: dict[Path, tuple[str, str]] = {}


def _frame(exercise) -> tuple[str, str]:
    """(what goes before the submission, what goes after it) for an exercise."""
    if exercise.folder not in _FRAMES:
        _FRAMES[exercise.folder] = _make_frame(exercise)
    return _FRAMES[exercise.folder]


def _make_frame(exercise) -> tuple[str, str]:
    includes = ["terms/common.glsl"]
    if exercise.sampler_for:
        includes += [*load_model(exercise.sampler_for).includes, "terms/sampling.glsl"]
    elif exercise.wrapper:
        wrapper = load_model(exercise.wrapper)
        includes += [i for i in wrapper.includes if i != exercise.replaces]
    else:
        includes += parse_model(exercise.stub.read_text("utf-8"), exercise.stub).includes
    library = [
        opaque((SHADER_DIR / i).read_text(encoding="utf-8"), exercise.api)
        for i in dict.fromkeys(includes)
    ]
    if getattr(exercise, "estimator", False):  # what its host gives an estimate, opaque
        library.append(opaque(ESTIMATOR_GIVEN, exercise.api) + ESTIMATOR_RANDOM)
    before = "\n".join(["#version 450", glsl_defines(), _parameters(exercise), *library])
    return before + "\n", "\n" + _main(exercise.functions) + "\n"


FUNCTION = re.compile(r"^(\w+)[ \t]+(\w+)[ \t]*\(([^()]*)\)\s*\{", re.M)
TO_FLOAT = {"float": "{}", "int": "float({})", "uint": "float({})", "bool": "float({})"}


def opaque(text: str, api: list[str]) -> str:
    """`text` with the body of each function that `api` names replaced by one the optimiser
    cannot see through: what the student calls counts once, with its arguments, instead of
    the library's code inlined (which would make every submission alike)."""
    out, position = [], 0
    for match in FUNCTION.finditer(text):
        result, name, params = match.groups()
        if name not in api or result == "void":
            continue
        depth, end = 0, match.end() - 1
        for end in range(match.end() - 1, len(text)):
            depth += {"{": 1, "}": -1}.get(text[end], 0)
            if depth == 0:
                break
        args = []
        for part in filter(str.strip, params.split(",")):
            kind, arg = part.split()[-2:]
            args.append(TO_FLOAT.get(kind, "dot({}, " + kind + "(1.0))").format(arg))
        tag = int(hashlib.blake2b(name.encode(), digest_size=2).hexdigest(), 16) + 1
        value = f"({' + '.join(args) or '1.0'}) * {tag}.0"
        out += [text[position : match.end()], f" return {result}({value}); }}"]
        position = end + 1
    return "".join(out) + text[position:]


SAMPLER = re.compile(r"^([ \t]*)(uniform\s+(?:(?:highp|mediump|lowp)\s+)?\w*sampler\w+\s)", re.M)


def _bound(code: str) -> str:
    """Vulkan GLSL wants a binding on each sampler the file declares (a table it reads)."""
    count = iter(range(1, 1000))
    return SAMPLER.sub(lambda m: f"{m.group(1)}layout(binding = {next(count)}) {m.group(2)}", code)


def disassemble(code: str, exercise) -> str | None:
    """The optimised SPIR-V of a submission as text, or None if it does not compile."""
    before, after = _frame(exercise)
    with tempfile.TemporaryDirectory(prefix="brdf-spirv-") as folder:
        source, binary = Path(folder) / "s.frag", Path(folder) / "s.spv"
        source.write_text(before + _bound(code) + after, encoding="utf-8")
        try:
            steps = [
                ["glslangValidator", "-V", "--aml", "-o", str(binary), str(source)],
                ["spirv-opt", "-O", str(binary), "-o", str(binary)],
                ["spirv-dis", "--raw-id", "--no-header", str(binary)],
            ]
            for step in steps:
                done = subprocess.run(step, capture_output=True, text=True, timeout=SECONDS)
                if done.returncode != 0:
                    return None
        except (OSError, subprocess.TimeoutExpired):
            return None
    return done.stdout


def features(text: str, depth: int = DEPTH) -> Counter:
    """Each instruction's shape (opcode, type, constants, and its operands' shapes to DEPTH
    levels) hashed, counted: ids and their order do not count."""
    defs: dict[str, tuple[str, list[str]]] = {}
    body: list[tuple[str, list[str]]] = []
    for line in text.splitlines():
        match = INSTRUCTION.match(line)
        if not match or SKIP.match(match.group(2)):
            continue
        result, opcode, rest = match.groups()
        operands = rest.split()
        if result:
            defs[result] = (opcode, operands)
        if not opcode.startswith(("OpType", "OpConstant", "OpVariable", "OpFunction", "OpLabel")):
            body.append((opcode, operands))

    @cache
    def shape(operand: str, depth: int) -> str:
        if not operand.startswith("%") or operand not in defs:
            return operand  # a literal: a constant's value, an enum, an extended instruction
        opcode, operands = defs[operand]
        if opcode in ("OpLabel", "OpFunction") or depth == 0:
            return opcode
        if opcode.startswith(("OpType", "OpConstant")):
            return opcode + "(" + " ".join(shape(o, depth) for o in operands) + ")"
        return opcode + "(" + " ".join(shape(o, depth - 1) for o in operands) + ")"

    counts: Counter = Counter()
    for opcode, operands in body:
        text = opcode + "(" + " ".join(shape(o, depth) for o in operands) + ")"
        counts[hashlib.blake2b(text.encode(), digest_size=8).hexdigest()] += 1
    return counts


def normalised(code: str, exercise) -> Counter | None:
    """The submission's features, or None when it does not compile (or tools are missing)."""
    text = disassemble(code, exercise) if available() else None
    return features(text) if text is not None else None


def both_depths(code: str, exercise) -> tuple[Counter, Counter] | None:
    """(features to DEPTH, features to PAIR_DEPTH) from one compile, or None."""
    text = disassemble(code, exercise) if available() else None
    return None if text is None else (features(text), features(text, PAIR_DEPTH))

"""What an exercise's checks may name: the student file, the function signatures, and the
parameters of the model's header (lab.grading.exercise calls these on loading).

`exercise` arguments are lab.grading.exercise.Exercise (not imported: it imports this).
"""

from __future__ import annotations

import re
from pathlib import Path

from lab.grading import kinds, schema
from lab.grading.spec import ExerciseError
from lab.models import ModelError, Param, load_model, parse_model

SIGNATURE = re.compile(r"\b(\w+)\s+(\w+)\s*\(([^()]*)\)\s*\{")  # a GLSL function head


def check_files(exercise, where: str, lines) -> None:
    """student_file is a .glsl name in the folder; each of `functions` a GLSL signature."""
    name = exercise.student_file
    if Path(name).name != name or not name.endswith(".glsl"):
        raise ExerciseError(
            f"{where}:{lines.line('', 0, 'student_file')}: student_file = {name!r} should be "
            'the name of a .glsl file in the exercise folder, e.g. "phong.glsl"'
        )
    for signature in exercise.functions:
        if not SIGNATURE.fullmatch(signature.strip() + " {"):
            raise ExerciseError(
                f"{where}:{lines.line('', 0, 'functions')}: functions: {signature!r} is not a "
                'GLSL signature; write e.g. "vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y)"'
            )


def header_params(exercise) -> dict[str, Param] | None:
    """The parameters a check may set: the wrapper's or sampled model's header, else the
    stub's (None when it cannot be read: the stub is missing or its header is broken)."""
    library = exercise.wrapper or exercise.sampler_for
    for name in (exercise.wrapper, exercise.replaces, exercise.sampler_for):
        if name is not None and not isinstance(name, str):
            return None
    try:
        if library:
            return load_model(library).params
        return parse_model(exercise.stub.read_text("utf-8"), exercise.stub).params
    except (OSError, ModelError, UnicodeDecodeError):
        return None


def check_params(exercise, spec: dict, where: str, lines) -> None:
    """Each parameter a check sets or draws is one of the model's, with a value of its type."""
    library = exercise.wrapper or exercise.sampler_for
    if library:
        try:
            load_model(library)
        except ModelError as err:
            key = "wrapper" if exercise.wrapper else "sampler_for"
            raise ExerciseError(
                f"{where}:{lines.line('', 0, key)}: {key} = {library!r}: {err}"
            ) from None
    if exercise.wrapper and exercise.replaces:
        includes = load_model(exercise.wrapper).includes
        if exercise.replaces not in includes:
            raise ExerciseError(
                f"{where}:{lines.line('', 0, 'replaces')}: replaces = {exercise.replaces!r} is "
                f"not a file the wrapper {exercise.wrapper} includes ({', '.join(includes)})"
            )
    header = header_params(exercise)
    if header is None:
        return
    for index, check in enumerate(exercise.checks):
        raw = spec["checks"][index]
        groups = sum(check.same, ())
        own = kinds.kind_of(check).params_model(check, None)  # a kind's own model (11's target)
        header = own.params if own is not None else header_params(exercise)
        for key, names in (("params", check.params), ("ranges", check.ranges), ("same", groups)):
            line = lines.line(*(("checks", index) if key in raw else ("defaults", 0)), key)
            schema.check_param_names(names, header, where, line, f"check {check.name}: {key}")
        line = lines.line(*(("checks", index) if "ranges" in raw else ("defaults", 0)), "ranges")
        for name, (low, high) in check.ranges.items():
            param = header[name]
            if param.kind == "float" and (low < param.minimum or high > param.maximum):
                raise ExerciseError(
                    f"{where}:{line}: check {check.name}: ranges.{name} = [{low:g}, {high:g}] "
                    f"leaves the header's range [{param.minimum:g}, {param.maximum:g}]; narrow it"
                )
        line = lines.line(*(("checks", index) if "params" in raw else ("defaults", 0)), "params")
        for name, value in check.params.items():
            problem = schema.param_value_problem(header[name], value)
            if problem:
                raise ExerciseError(f"{where}:{line}: check {check.name}: params.{name} {problem}")

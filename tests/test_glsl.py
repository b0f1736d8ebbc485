"""Assembly of model programs: both GLSL targets compile, errors point into the model file."""

from __future__ import annotations

import shutil
import subprocess

import pytest

from lab import glsl
from lab.models import ModelError, load_model, model_names, parse_model

VIEWS = ["sphere", "probe", "slice", "albedo"]


def enum_variants(model):
    """The default settings plus each choice of each enum (every program a user can get)."""
    variants = [{}]
    for p in model.params.values():
        if p.kind == "enum":
            variants += [{p.name: c} for c in p.choices[1:]]
    return variants


@pytest.mark.parametrize("name", model_names())
def test_compiles_on_desktop_gl(renderer, name, gl_clean):
    model = load_model(name)
    for view in VIEWS:
        for enums in enum_variants(model):
            renderer.program(model, view, enums)


@pytest.mark.parametrize("name", model_names())
def test_compiles_as_glsl_es_300(tmp_path, name):
    """The WebGL2 target, checked by Khronos' reference compiler."""
    validator = shutil.which("glslangValidator")
    assert validator, "glslangValidator is missing: apt-get install glslang-tools"
    model = load_model(name)
    for view in ("sphere", "probe"):
        for enums in enum_variants(model):
            source = glsl.assemble_fragment(
                model, view, "300es", "const int LIGHT_COUNT = 2;", enums
            )
            path = tmp_path / f"{name}_{view}.frag"
            path.write_text(source.text)
            result = subprocess.run([validator, str(path)], capture_output=True, text=True)
            assert result.returncode == 0, (name, view, enums, result.stdout)


EMPTY_BRDF = "vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) { return vec3(0.0); }\n"

BROKEN = """// @model broken
// @title a model with a typo on line 7
// @param kd color 0.5 0.5 0.5 | diffuse

vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {
    float NoL = dot(N, L);
    return kd * NoL   // missing semicolon
}
"""


def test_compile_error_names_model_file_and_line(renderer, tmp_path):
    path = tmp_path / "broken.glsl"
    path.write_text(BROKEN)
    model = load_model(path)
    with pytest.raises(glsl.ShaderCompileError) as info:
        renderer.program(model, "sphere")
    first = info.value.errors[0]
    assert first.file == str(path)
    assert first.line in (7, 8)  # drivers flag the statement or the token after it
    assert str(path) in str(info.value)


def test_error_log_formats_of_other_drivers_are_mapped():
    model = parse_model(BROKEN, "broken.glsl")
    source = glsl.assemble_fragment(model, "sphere")
    line = next(i for i, (f, n) in enumerate(source.origins, 1) if f == "broken.glsl" and n == 7)
    logs = {
        "mesa": f"0:{line}(5): error: syntax error, unexpected '}}'",
        "nvidia": f'0({line}) : error C1008: undefined variable "x"',
        "angle": f"ERROR: 0:{line}: '}}' : syntax error",
    }
    for driver, log in logs.items():
        errors = glsl.translate_log(log, source)
        assert [(e.file, e.line) for e in errors] == [("broken.glsl", 7)], driver


@pytest.mark.parametrize(
    "directive", ["#version 330 core", "#extension GL_OES_foo : enable", '#include "x.glsl"']
)
def test_host_owned_directives_are_rejected_with_line(directive):
    code = (
        "// @model m\n\n"
        + directive
        + "\nvec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) { return vec3(0.0); }\n"
    )
    model = parse_model(code, "m.glsl")
    with pytest.raises(ModelError) as info:
        glsl.assemble_fragment(model, "probe")
    assert info.value.line == 3 and "m.glsl:3:" in str(info.value)


def test_missing_include_is_reported():
    code = "// @model m\n// @include terms/nope.glsl\n" + EMPTY_BRDF
    with pytest.raises(ModelError, match="m.glsl:2: @include terms/nope.glsl"):
        glsl.assemble_fragment(parse_model(code, "m.glsl"), "probe")


def test_enum_choice_is_compiled_in_as_constant():
    model = load_model("cook_torrance")
    text = glsl.assemble_fragment(model, "probe", enums={"fresnel": "none"}).text
    assert "const int fresnel = FRESNEL_NONE;" in text
    assert "const int FRESNEL_DIELECTRIC = 1;" in text
    assert "uniform float m;" in text and "uniform vec3 f0;" in text


def test_view_includes_come_before_the_view_with_their_own_lines():
    """The object view's `// @include views/object_shape.glsl` puts that file in once, before
    the template, its lines labelled with its own name (a compile error in it points there)."""
    source = glsl.assemble_fragment(load_model("phong"), "object")
    shape = (glsl.VIEW_DIR / "object_shape.glsl").read_text().splitlines()
    at = next(
        i for i, line in enumerate(source.lines) if line.startswith("bool lab_object_surface(")
    )
    assert source.origins[at] == (
        "shaders/views/object_shape.glsl",
        shape.index(source.lines[at]) + 1,
    )
    view_start = next(
        i for i, (f, _) in enumerate(source.origins) if f == "shaders/views/object.glsl"
    )
    assert at < view_start
    assert sum(line.startswith("uniform int u_shape;") for line in source.lines) == 1


def test_a_view_include_of_a_missing_file_says_which():
    source = glsl.Source()
    with pytest.raises(FileNotFoundError, match=r"views/x\.glsl: @include views/nowhere\.glsl"):
        glsl.add_view(source, "// @include views/nowhere.glsl\nvoid f() {}\n", "views/x.glsl")

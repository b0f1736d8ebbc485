"""BRDF Explorer .brdf files: parsed, compiled with the context's GLSL, errors on their lines."""

from __future__ import annotations

import numpy as np
import pytest

from lab.brdf_explorer import parse_brdf
from lab.glsl import ShaderCompileError
from lab.models import ModelError

# Written in BRDF Explorer's style: '#' comments, int literals where floats are meant.
BLINN = """\
# Normalised Blinn-Phong, as a BRDF Explorer file
analytic

# variables: float NAME MIN MAX DEFAULT, bool NAME 0|1, color NAME R G B
::begin parameters
float n 1 1000 40
bool normalized 1
color tint 1 0.5 0.25
::end parameters

::begin shader
const float PI = 3.14159265358979323846;
# a comment inside the shader
vec3 BRDF( vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y )
{
    vec3 H = normalize(L+V);
    float val = pow(max(0, dot(N,H)), n);
    if (normalized)
        val *= (n + 2) / (2*PI);
    return tint * val;
}
::end shader
"""


@pytest.fixture(scope="module")
def app_renderer(ctx):
    from lab.app.renderer import AppRenderer

    return AppRenderer(ctx)


def test_parameters_and_shader_section_are_read():
    model = parse_brdf(BLINN, "blinn.brdf")
    n, normalized, tint = model.params.values()
    assert (n.kind, n.minimum, n.maximum, n.default, n.scale) == ("float", 1, 1000, 40, "log")
    assert (normalized.kind, normalized.default) == ("bool", True)
    assert (tint.kind, tint.default) == ("color", (1.0, 0.5, 0.25))
    assert model.shader_line == 12
    assert "a comment inside" not in model.code
    # The shader keeps the file's line numbering: line 15 of the file is its 4th line.
    assert model.code.splitlines()[15 - model.shader_line] == "{"


def test_values_match_the_formula(app_renderer, gl_clean):
    model = parse_brdf(BLINN, "blinn.brdf")
    theta_o = np.array([0.0, 10.0, 30.0, 50.0])
    angles = np.stack([np.full(4, 30.0), np.zeros(4), theta_o, np.full(4, 180.0)], axis=1)
    f = app_renderer.eval_angles(model, {"n": 40.0}, angles)
    from lab.render import direction

    L = direction(30.0, 0.0)
    V = direction(theta_o, 180.0)
    H = (L + V) / np.linalg.norm(L + V, axis=1, keepdims=True)
    expected = H[:, 2] ** 40 * 42 / (2 * np.pi)
    np.testing.assert_allclose(f, expected[:, None] * [1.0, 0.5, 0.25], rtol=2e-4, atol=1e-6)


def test_compile_error_names_the_brdf_file_line(app_renderer):
    bad = BLINN.replace("return tint * val;", "return tint * val")  # line 20 of the file
    model = parse_brdf(bad, "blinn.brdf")
    with pytest.raises(ShaderCompileError) as info:
        app_renderer.sphere(model, {}, size=16)
    assert any(e.file.endswith("blinn.brdf") and e.line in (20, 21) for e in info.value.errors)


@pytest.mark.parametrize(
    ("text", "line", "words"),
    [
        ("nonsense\n", 1, "analytic"),
        ("analytic\n::begin parameters\nfloat n 1 x 3\n::end parameters\n", 3, "numbers"),
        ("analytic\n::begin parameters\nint n 1 2 3\n::end parameters\n", 3, "float NAME"),
        ("analytic\n::begin shader\nvec3 BRDF(vec3 L) { return L; }\n", 3, "never closed"),
        ("analytic\n::begin parameters\n::end parameters\n", 3, "::begin shader"),
    ],
)
def test_bad_files_give_one_line_errors(text, line, words):
    with pytest.raises(ModelError) as info:
        parse_brdf(text, "bad.brdf")
    assert info.value.line == line
    assert words in str(info.value)
    assert "\n" not in str(info.value)

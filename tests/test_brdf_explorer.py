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


# Integer arithmetic as BRDF Explorer's GLSL 4.10 does it: 1/4 is 0, 7/2 is 3, -7/2 is -3,
# 7 % 3 is 1; the int result is converted to float only where it meets a float.
INT_DIVISION = """\
analytic
::begin parameters
float scale 0 2 1
::end parameters
::begin shader
vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y)
{
    int n = 7;
    float quarter = 1/4;                   // 0
    float three = float(7/2) + 1/4 * 3.0;  // 3 + 0 * 3.0
    float mixed = n/2 + (1 + 1/2) * 0.5;   // 3 + 1 * 0.5
    float rest = -7/2 + 7 % 3;             // -3 + 1
    float exact = 1.0 / 4 + scale * 3/4;   // 0.25 + (scale * 3) / 4
    return vec3(quarter + 0.1 * three, 0.1 * mixed + 0.05 * rest, exact) * (1 + 1/2);
}
::end shader
"""
INT_DIVISION_VALUE = (0.3, 0.25, 1.0)  # with scale = 1


def test_int_division_is_glsl_int_division(app_renderer, gl_clean):
    model = parse_brdf(INT_DIVISION, "ints.brdf")
    angles = np.array([[30.0, 0.0, 20.0, 180.0], [10.0, 40.0, 60.0, 100.0]])
    f = app_renderer.eval_angles(model, {}, angles)
    np.testing.assert_allclose(f, [INT_DIVISION_VALUE] * 2, rtol=1e-6)


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


# -- what real BRDF Explorer files do (wdas/brdf's src/brdfs), in files of our own ----------


def _probe(renderer, model, values, theta_i, phi_i, theta_o, phi_o):
    from lab.render import direction

    def directions(theta, phi):
        return direction(np.atleast_1d(np.asarray(theta, float)), np.atleast_1d(phi))

    return renderer.probe(model, values, directions(theta_i, phi_i), directions(theta_o, phi_o))


# Many files declare PI and sqr themselves (globally, or PI inside BRDF); our helpers
# and the views (albedo, slice, object) use the same names.
OWN_HELPERS = """\
analytic
::begin parameters
float rho 0 1 0.6
::end parameters
::begin shader
float sqr(float v) { return v*v; }
float PI = 3.14159265358979;
vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) { return vec3(rho / PI) * sqr(1); }
::end shader
"""

LOCAL_PI = """\
analytic
::begin parameters
float rho 0 1 0.6
::end parameters
::begin shader
vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y)
{
    float PI = 3.14159265358979;
    return vec3(rho / PI);
}
::end shader
"""


@pytest.mark.parametrize("text", [OWN_HELPERS, LOCAL_PI], ids=["global", "local"])
def test_files_declaring_pi_and_sqr_work_in_every_view(renderer, app_renderer, text):
    from lab.render import Light

    model = parse_brdf(text, "own_pi.brdf")
    # A constant BRDF rho/pi reflects rho of the light at every incidence.
    albedo = renderer.albedo(model, {"rho": 0.6}, [0.0, 40.0, 70.0])
    np.testing.assert_allclose(albedo[:, 0], 0.6, atol=0.01)
    assert np.allclose(renderer.slice(model, None, size=16), 0.6 / np.pi, rtol=1e-4)
    image = renderer.sphere(model, None, (0.0, 0.0), size=32)
    assert abs(image[16, 16, 0] - 0.6 / np.pi) < 2e-3  # centre: N = L = V
    obj = app_renderer.object(model, None, [Light(30.0, 0.0)], size=32)
    assert np.isfinite(obj).all() and obj[..., 0].max() > 0.05


# Files redefine built-ins; their reflect points the other way round from GLSL's.
OWN_REFLECT = """\
analytic
::begin parameters
float n 1 1000 200
::end parameters
::begin shader
vec3 reflect(vec3 I, vec3 N) { return 2*dot(I,N)*N - I; }
float smoothstep(float a, float b, float x) { return 0.0; }
vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y)
{
    return vec3(pow(max(0, dot(reflect(L,N), V)), n) + smoothstep(0, 1, 0.5));
}
::end shader
"""


def test_redefined_builtins_serve_the_file_and_not_the_views(renderer, app_renderer):
    from lab.render import Light

    model = parse_brdf(OWN_REFLECT, "own_reflect.brdf")
    # The file's own reflect: the lobe peaks in the mirror direction.
    f = _probe(renderer, model, None, [30, 30], [0, 0], [30, 40], [180, 180])[:, 0]
    assert f[0] == pytest.approx(1.0, abs=1e-4)
    assert f[1] == pytest.approx(np.cos(np.radians(10)) ** 200, rel=1e-3)
    # The object view calls the real smoothstep: the same picture as without the override.
    plain_text = OWN_REFLECT.replace("+ smoothstep(0, 1, 0.5)", "+ 0.0").replace(
        "float smoothstep(float a, float b, float x) { return 0.0; }", ""
    )
    plain = parse_brdf(plain_text, "plain.brdf")
    lights = [Light(35.0, 20.0)]
    ours = app_renderer.object(model, None, lights, mode=3, size=48)
    np.testing.assert_allclose(ours, app_renderer.object(plain, None, lights, mode=3, size=48))


# Names our views and helpers declare, used by a file: a function with a view's signature,
# a parameter named like one of our constants.
VIEW_NAMES = """\
analytic
::begin parameters
float INV_PI 0 1 0.5
::end parameters
::begin shader
vec3 environment(vec3 d) { return vec3(0.25); }
vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) { return environment(N) + INV_PI; }
::end shader
"""


def test_names_shared_with_the_views_and_helpers(renderer):
    model = parse_brdf(VIEW_NAMES, "view_names.brdf")
    f = _probe(renderer, model, {"INV_PI": 0.25}, 20, 0, 20, 180)
    np.testing.assert_allclose(f, [[0.5, 0.5, 0.5]], atol=1e-6)
    image = renderer.sphere(model, None, (0.0, 0.0), size=32)
    assert image[16, 16, 0] == pytest.approx(0.75, abs=2e-3)
    albedo = renderer.albedo(model, None, [0.0])
    assert albedo[0, 0] == pytest.approx(0.75 * np.pi, rel=0.01)


# CRLF, a byte-order mark, tabs, trailing blanks, comments everywhere, text outside the
# sections, sections we do not use, trailing words on parameter lines, and a second shader
# section (BRDF Explorer keeps the last).
ODD_LAYOUT = (
    "\ufeffanalytic   generated by hand\r\n"
    "this line is outside any section and ignored\r\n"
    "::begin parameters\t \r\n"
    "  # a comment between parameters\r\n"
    "float gain 2 0 .5   # how bright   \r\n"
    "\tbool  doubled 1 extra words\r\n"
    "color tint 1 .5 .25 // warm\r\n"
    "float spread 1e0 1.5e3 20.f\r\n"
    "::end parameters\r\n"
    "::begin isFunc\r\n"
    "vec3 sampleBRDF(float u, float v) { return vec3(0.0); }\r\n"
    "::end isFunc\r\n"
    "::begin shader\r\n"
    "vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) { return vec3(99); }\r\n"
    "::end shader\r\n"
    "::begin shader  (the one that counts)\r\n"
    "   # an indented comment inside the shader  \r\n"
    "vec3 BRDF( vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y )   \r\n"
    "{\r\n"
    "    float k = doubled ? 2 : 1;\r\n"
    "#   a comment in column one\r\n"
    "    return k * gain * tint;\r\n"
    "}\r\n"
    "::end shader\r\n"
    "# trailing comment\r\n"
)


def test_odd_layout_is_read_like_brdf_explorer(renderer):
    model = parse_brdf(ODD_LAYOUT, "odd.brdf")
    gain, doubled, tint, spread = model.params.values()
    # MIN above MAX is a reversed slider: the range holds both ends and the default.
    assert (gain.minimum, gain.maximum, gain.default, gain.doc) == (0.0, 2.0, 0.5, "how bright")
    assert (doubled.kind, doubled.default) == ("bool", True)
    assert (tint.default, tint.doc) == ((1.0, 0.5, 0.25), "warm")
    assert (spread.minimum, spread.maximum, spread.default) == (1.0, 1500.0, 20.0)
    assert model.shader_line == 17
    assert "99" not in model.code and "comment" not in model.code
    f = _probe(renderer, model, None, 10, 0, 10, 180)
    np.testing.assert_allclose(f, [[1.0, 0.5, 0.25]], rtol=1e-6)
    f = _probe(
        renderer, model, {"doubled": False, "gain": 1.5, "tint": (0.2, 0.4, 0.6)}, 10, 0, 10, 180
    )
    np.testing.assert_allclose(f, [[0.3, 0.6, 0.9]], rtol=1e-6)


def test_compile_errors_keep_the_file_lines_with_crlf(renderer):
    model = parse_brdf(
        ODD_LAYOUT.replace("return k * gain * tint;", "return k * gain * tnt;"), "odd.brdf"
    )
    with pytest.raises(ShaderCompileError) as info:
        renderer.sphere(model, None, size=8)
    assert any(e.file.endswith("odd.brdf") and e.line == 22 for e in info.value.errors)


@pytest.mark.parametrize(
    ("line", "default"),
    [
        ("bool b 0", False),
        ("bool b 1", True),
        ("bool b 2", True),
        ("bool b true", True),
        ("bool b false", False),
    ],
)
def test_bool_values(line, default):
    text = f"analytic\n::begin parameters\n{line}\n::end parameters\n" + BLINN.split("\n", 10)[10]
    assert parse_brdf(text, "b.brdf").params["b"].default is default


# Files compute sqrt and pow of negative numbers: below the surface (where the lab's
# contract is 0) and, for some parameters, above it (BRDF Explorer shows NaN as black).
NEGATIVE_ROOTS = """\
analytic
::begin parameters
float edge 0 1 0.5
::end parameters
::begin shader
vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y)
{
    return vec3(sqrt(dot(N,L) * dot(N,V)), pow(dot(N,V) - edge, 0.5), 1);
}
::end shader
"""


def test_below_the_surface_is_zero_and_nan_reads_as_zero(renderer):
    model = parse_brdf(NEGATIVE_ROOTS, "roots.brdf")
    f = _probe(renderer, model, None, [0, 100, 0], [0, 0, 0], [0, 0, 80], [0, 0, 0])
    cos80 = np.cos(np.radians(80))
    expected = [[1, np.sqrt(0.5), 1], [0, 0, 0], [np.sqrt(cos80), 0, 1]]
    np.testing.assert_allclose(f, expected, atol=1e-5)
    image = renderer.sphere(model, None, (60.0, 0.0), size=32)
    assert np.isfinite(image).all()
    assert image[16, 2, 2] == 0.0 and image[16, 29, 2] > 0.1  # dark side, lit side


@pytest.mark.parametrize(
    ("text", "line", "words"),
    [
        (
            "bparam phong.brdf\n::begin parameters\nfloat n 1 2 1\n::end parameters\n",
            1,
            "parameter file",
        ),
        ("analytic\n::begin\n", 2, "section name"),
        ("analytic\n::begin parameters\nfloat sample 0 1 0.5\n::end parameters\n", 3, "reserved"),
        ("analytic\n::begin parameters\ncolor c 1 1\n::end parameters\n", 3, "R G B"),
        ("analytic\n::begin parameters\nbool b maybe\n::end parameters\n", 3, "bool b 1"),
        ("analytic\n::begin parameters\n::begin shader\n", 3, "inside"),
        ("analytic\n::end shader\n", 2, "without"),
        (
            "analytic\n::begin parameters\nfloat a 0 1 0\nfloat a 0 1 0\n::end parameters\n",
            4,
            "twice",
        ),
        ("analytic\n::begin shader\nfloat BRDF() { return 1.0; }\n::end shader\n", 3, "defines no"),
    ],
)
def test_more_bad_files_give_one_line_errors(text, line, words):
    with pytest.raises(ModelError) as info:
        parse_brdf(text, "bad.brdf")
    assert info.value.line == line
    assert words in str(info.value)
    assert "\n" not in str(info.value)

"""The model header: parsing, validation and the errors users see."""

from __future__ import annotations

import pytest

from lab.models import ModelError, load_model, model_names, parse_model

EXPECTED_PARAMS = {
    "lambert": {"albedo"},
    "mirror": {"rho_s"},
    "phong": {"kd", "ks", "ke"},
    "blinn_phong": {"kd", "ks", "ke"},
    "ward": {"kd", "ks", "alpha_x", "alpha_y"},
    "cook_torrance": {"kd", "ks", "m", "f0", "ior", "distribution", "fresnel"},
    "ggx": {"kd", "ks", "alpha", "f0"},
    "oren_nayar": {"albedo", "sigma"},
    "lommel_seeliger": {"albedo"},
}


def test_library_has_every_model_with_its_parameters():
    names = set(model_names())
    assert set(EXPECTED_PARAMS) <= names
    for name, params in EXPECTED_PARAMS.items():
        model = load_model(name)
        assert set(model.params) == params, name
        assert model.title and model.formula and model.source, name


def test_header_details():
    ct = load_model("cook_torrance")
    assert ct.params["distribution"].choices == ("beckmann", "blinn", "gaussian")
    assert ct.params["fresnel"].choices == ("schlick", "dielectric", "none")
    assert ct.params["m"].scale == "log"
    assert ct.params["kd"].kind == "color"
    assert load_model("phong").params["ke"].scale == "log"
    assert load_model("mirror").delta and not load_model("phong").delta
    assert "terms/distributions.glsl" in ct.includes


@pytest.mark.parametrize(
    "line, fragment",
    [
        ("// @param ke float 1 10", "MIN MAX DEFAULT"),
        ("// @param ke float 10 1 5", "must be below MAX"),
        ("// @param ke float 1 10 50", "outside"),
        ("// @param ke float 0 10 5 log", "log slider needs MIN > 0"),
        ("// @param ke float 1 10 5 cubic", "linear or log"),
        ("// @param kd color 0.5 0.5", "R G B"),
        ("// @param kd color 2 0 0", "0..1"),
        ("// @param on bool 2", "0 or 1"),
        ("// @param d enum", "list its choices"),
        ("// @param 2x float 0 1 0", "not a GLSL identifier"),
        ("// @param x vec4 0 1 0", "unknown parameter type"),
        ("// @parm x float 0 1 0", "unknown header keyword"),
        ("// @param x float a 1 0", "must be a number"),
    ],
)
def test_bad_header_lines_name_file_and_line(line, fragment):
    code = (
        "// @model broken\n// @title t\n"
        + line
        + "\nvec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) { return vec3(0.0); }\n"
    )
    with pytest.raises(ModelError) as info:
        parse_model(code, "broken.glsl")
    assert info.value.line == 3
    assert "broken.glsl:3:" in str(info.value)
    assert fragment in str(info.value)


def test_header_ends_at_first_code_line():
    code = (
        "// @param a float 0 1 0.5 | first\nfloat x = 1.0;\n// @param b float 0 1 0.5 | ignored\n"
    )
    assert list(parse_model(code, "m.glsl").params) == ["a"]


def test_settings_parse_and_validate():
    phong = load_model("phong")
    values = phong.parse_settings(["ke=120", "kd=0.2,0.3,0.4", "ks=0.5"])
    assert values["ke"] == 120.0
    assert values["kd"] == (0.2, 0.3, 0.4)
    assert values["ks"] == (0.5, 0.5, 0.5)
    for bad, fragment in [
        (["ke=5000"], "outside its range"),
        (["shininess=3"], "has no parameter 'shininess'"),
        (["ke"], "malformed"),
        (["ke=abc"], "needs a number"),
        (["kd=0.1,0.2"], "r,g,b"),
    ]:
        with pytest.raises(ModelError, match=fragment):
            phong.parse_settings(bad)
    ct = load_model("cook_torrance")
    assert ct.parse_settings(["distribution=gaussian"])["distribution"] == "gaussian"
    with pytest.raises(ModelError, match="one of beckmann, blinn, gaussian"):
        ct.parse_settings(["distribution=ggx"])


def test_unknown_model_lists_the_known_ones():
    with pytest.raises(ModelError, match="unknown model 'phongg'.*phong"):
        load_model("phongg")

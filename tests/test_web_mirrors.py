"""The web lab's JavaScript mirrors of Python code agree with it on a table of cases.

The page's directions and plane of incidence (static/geometry.js, lab/geometry.py), its
value parsing and sliders (static/values.js: Param.parse, parse_rgb, the app's sliders), its
polar scale (static/plotscale.js, lab/plotscale.py) and the library headers the manifest
carries (parsed in Python, used by the page without parsing) are each run in node and
compared with the Python on the same inputs. The header parser and the GLSL assembly have
their own fixtures (test_web_fixtures.py).
"""

from __future__ import annotations

import json
import math
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

from lab.constants import GRAZING_DEG, PLOT_DECADES
from lab.errors import UsageError, parse_rgb
from lab.geometry import direction, plane_of_incidence
from lab.models import MODEL_DIR, ModelError, Param, model_names
from lab.plotscale import Scale, peak_value
from lab.web.site import manifest

ROOT = Path(__file__).resolve().parent.parent
CHECKER = ROOT / "lab" / "web" / "check_mirrors.mjs"

PARAMS = [
    Param("roughness", "float", 0.5, minimum=0.0, maximum=1.0),
    Param("ke", "float", 10.0, minimum=1.0, maximum=1000.0, scale="log"),
    Param("shift", "float", 0.0, minimum=-2.5, maximum=2.5),
    Param("kd", "color", (0.5, 0.5, 0.5)),
    Param("metal", "bool", False),
    Param("distribution", "enum", "beckmann", choices=("beckmann", "ggx")),
]
TEXTS = [
    "0.5",
    " 0.5 ",
    "+0.5",
    "1",
    "0",
    "-0",
    "-0.1",
    "2",
    "2.5",
    "-2.5",
    "1000",
    "1000.01",
    "1e-3",
    "1E2",
    ".5",
    "5.",
    "1_0",
    "1__0",
    "_1",
    "0x10",
    "0b1",
    "1e400",
    "0.5e",
    "e5",
    "",
    " ",
    "nan",
    "inf",
    "-inf",
    "Infinity",
    "abc",
    "0.5,0.5",
    "0.1, 0.2, 0.3",
    "0.1,,0.3",
    "0.1,0.2,0.3,0.4",
    "1,1,1",
    "0.2 0.3",
    "true",
    "True",
    "yes",
    "ON",
    "off",
    "1.0",
    "beckmann",
    " ggx ",
    "GGX",
    "beckmann,ggx",
]
RGB_TEXTS = [
    "1,1,1",
    "0.5",
    "0,0",
    "-1,0,0",
    "a",
    "",
    "inf",
    "1,2,3,4",
    " 0.2 , 0.3 , 0.4",
    "1_0",
    "0,0,nan",
    "3,0.5,7",
]
LIGHTS = [
    (t, p) for t in (0.0, 0.5, 30.0, 45.0, 89.9, 90.0) for p in (0.0, 90.0, -45.0, 270.0, 725.5)
]
PLANES = [(p, s) for p in (0.0, 30.0, 180.0, 359.0, -120.0) for s in (1.0, 0.5, 2.5, 7.0)]
THETA_O = list(range(-90, 91))
# Lobes as the page samples them: peaks inside the cut-off, a divergence at the horizon
# (Ward), a lobe wholly beyond the cut-off, all zero, negative values.
LOBES = [
    [math.exp(-(((t - 40) / 12) ** 2)) for t in THETA_O],
    [0.3 / math.sqrt(max(math.cos(math.radians(t)), 1e-9)) for t in THETA_O],
    [5.0 if abs(t) > GRAZING_DEG else 0.0 for t in THETA_O],
    [0.0 for _ in THETA_O],
    [-1.0 + 0.01 * t for t in THETA_O],
]
RADII = [
    (f, top, log)
    for f in (0.0, -1.0, 1e-9, 1e-4, 0.05, 0.5, 1.0, 2.0, 123.0)
    for top in (1.0, 0.25, 1e3)
    for log in (False, True)
]


def jsonable(param: Param) -> dict:
    return {
        "name": param.name,
        "kind": param.kind,
        "default": list(param.default) if isinstance(param.default, tuple) else param.default,
        "minimum": param.minimum,
        "maximum": param.maximum,
        "scale": param.scale,
        "choices": list(param.choices),
    }


def python_value(param: Param, text: str):
    try:
        value = param.parse(text)
    except ModelError:
        return "error"
    return list(value) if isinstance(value, tuple) else value


def library_files() -> dict:
    """Each library model's file as the page fetches it (its newlines untouched)."""
    out = {}
    for name in model_names():
        with open(MODEL_DIR / f"{name}.glsl", encoding="utf-8", newline="") as handle:
            out[name] = {"path": f"shaders/brdfs/{name}.glsl", "code": handle.read()}
    return out


@pytest.fixture(scope="module")
def javascript():
    if shutil.which("node") is None:
        pytest.skip("node is not installed (apt nodejs; python3 -m lab test installs it)")
    from lab.app.params import slider_position, slider_value

    float_params = [p for p in PARAMS if p.kind == "float"] + [
        Param("gloss", "float", 0.1, minimum=0.001, maximum=1.0, scale="log")
    ]
    positions = [0, 1, 250, 500, 999, 1000]
    rng = np.random.default_rng(12)
    samples = []
    for p in float_params:
        span = p.maximum - p.minimum
        outside = (p.minimum / 2, p.maximum * 2) if p.scale == "log" else (-span, 2 * span)
        samples += [(p, v) for v in (p.minimum, p.maximum, *outside)]
        samples += [(p, float(v)) for v in rng.uniform(p.minimum, p.maximum, 20)]
    cases = {
        "direction": LIGHTS,
        "plane": PLANES,
        "values": [(jsonable(p), t) for p in PARAMS for t in TEXTS],
        "rgb": RGB_TEXTS,
        "slider_value": [(jsonable(p), k) for p in float_params for k in positions],
        "slider_position": [(jsonable(p), v) for p, v in samples],
        "slider_steps": manifest()["constants"]["SLIDER_STEPS"],  # as the page gets it
        "library": library_files(),
        "peak": [(THETA_O, lobe, GRAZING_DEG) for lobe in LOBES],
        "radius": [(f, top, log, PLOT_DECADES) for f, top, log in RADII],
        "g": [(x, d) for x in G_NUMBERS for d in (2, 3, 6)],
        "fill": fill_cases(),
    }
    python = {
        "values": [python_value(p, t) for p in PARAMS for t in TEXTS],
        "slider_value": [slider_value(p, k) for p in float_params for k in positions],
        "slider_position": [slider_position(p, v) for p, v in samples],
    }
    with_cases = Path(__file__).resolve().parent / "output" / "mirror_cases.json"
    with_cases.parent.mkdir(exist_ok=True)
    with_cases.write_text(json.dumps(cases), encoding="utf-8")
    run = subprocess.run(
        ["node", str(CHECKER), str(with_cases)], capture_output=True, text=True, timeout=60
    )
    assert run.returncode == 0, run.stderr
    return cases, python, json.loads(run.stdout)


def test_direction_matches_python(javascript):
    cases, _, js = javascript
    for (theta, phi), got in zip(cases["direction"], js["direction"], strict=True):
        want = direction(theta, phi)
        assert np.allclose(got, want, rtol=0, atol=1e-15), (theta, phi, got, want)
        assert (np.asarray(got) == 0).tolist() == (want == 0).tolist(), (theta, phi)


def test_plane_of_incidence_matches_python(javascript):
    cases, _, js = javascript
    for (phi, step), got in zip(cases["plane"], js["plane"], strict=True):
        theta_o, V = plane_of_incidence(30.0, phi, step)
        assert got["thetaO"] == theta_o.tolist(), (phi, step)
        assert np.allclose(got["V"], V, rtol=0, atol=1e-15), (phi, step)
        # The mirror of the light lies at theta_o = theta_i on the positive side.
        mirror = np.asarray(got["V"])[np.argmin(np.abs(theta_o - 30.0))]
        light = direction(30.0, phi)
        reflected = 2 * light[2] * np.array([0.0, 0.0, 1.0]) - light
        if step == 1.0:
            assert np.allclose(mirror, reflected, atol=1e-12), (phi, mirror, reflected)


def test_value_parsing_matches_python(javascript):
    cases, python, js = javascript
    wrong = []
    for (param, text), want, got in zip(
        cases["values"], python["values"], js["values"], strict=True
    ):
        outcome = "error" if "error" in got else got["value"]
        if outcome != want:
            wrong.append(
                f"{param['name']} ({param['kind']}) {text!r}: Python {want!r}, page {outcome!r}"
            )
    assert not wrong, "\n".join(wrong)
    accepted = [w for w in python["values"] if w != "error"]
    assert len(accepted) > 40 and len(accepted) < len(python["values"]) - 100  # both kinds tried


def test_rgb_parsing_matches_python(javascript):
    cases, _, js = javascript
    for text, got in zip(cases["rgb"], js["rgb"], strict=True):
        try:
            want = list(parse_rgb(text, "--ambient"))
        except UsageError:
            want = None
        assert got == want, (text, got, want)


def test_sliders_match_the_apps(javascript):
    _, python, js = javascript
    assert np.allclose(js["slider_value"], python["slider_value"], rtol=1e-12, atol=0)
    assert js["slider_position"] == python["slider_position"]


def test_manifest_headers_are_what_the_page_would_parse(javascript):
    """The page uses the manifest's headers instead of parsing the library files: they must
    be what its own parser (header.js) makes of each file."""
    cases, _, js = javascript
    library = manifest()["library"]
    assert set(library) == set(cases["library"]) == set(js["headers"])
    for name, header in library.items():
        assert "error" not in header, header
        assert json.loads(json.dumps(header)) == js["headers"][name], name
        assert header["params"] and header["title"], name


# Numbers the page writes with Python's %g: the edges of the fixed and exponent forms,
# rounding up to a new digit, negative zero.
G_NUMBERS = [
    0.0,
    -0.0,
    1.0,
    -2.5,
    0.1,
    1e-4,
    9.99995e-5,
    1e-5,
    123456.0,
    999999.5,
    1e6,
    1234567.0,
    0.30000000000000004,
    2 / 3,
    -1e-300,
    6.02214076e23,
    99.95,
    0.00012345,
]


def test_number_formatting_is_pythons_g(javascript):
    """header.js formatDigits (the page's one %g: formatG, the diagnosis' and sampling's
    sentences) writes what Python's format(x, ".Ng") writes."""
    _, _, js = javascript
    cases = [(x, d) for x in G_NUMBERS for d in (2, 3, 6)]
    for (x, digits), got in zip(cases, js["g"], strict=True):
        assert got == format(x, f".{digits}g"), (x, digits)


# Numbers the sentences' templates are filled with: exact ties (Python rounds them to the
# even digit), near-ties, negatives, negative zero, tiny and huge, not finite.
FILL_NUMBERS = [0.5, 1.5, 2.5, -2.5, 0.125, 0.375, 1.005, -0.04, -0.0, 99.95, 1e-7, 7.0, 3e22]
FILL_NUMBERS += [123.456, 0.0049999, math.inf, -math.inf, math.nan, 2 / 3, 1e5 + 0.5]


def fill_cases() -> list:
    """Every sentence of lab/grading/words.py with numbers in its number fields and words
    in the others, and a template of each spec the page knows over FILL_NUMBERS."""
    from string import Formatter

    from lab.grading import words

    cases = []
    templates = [*words.DIAGNOSIS.values(), *words.SAMPLING.values(), *words.SH.values()]
    for k, template in enumerate(templates):
        fields = [(name, spec) for _, name, spec, _ in Formatter().parse(template) if name]
        numbers = FILL_NUMBERS[k % 7 :] + FILL_NUMBERS
        values = {
            name: numbers[i] if spec else ("θ 10°" if i % 2 else 17)
            for i, (name, spec) in enumerate(fields)
        }
        cases.append((template, values))
    specs = "{x:.0f}|{x:.1f}|{x:.2f}|{x:+.1f}|{x:.4f}|{x:g}|{x:.3g}|{x:.2g}|{x:.2%}|{x:.1%}"
    cases += [(specs, {"x": x}) for x in FILL_NUMBERS if x not in (0.125, 0.375)]
    cases += [("{x:.0f}|{x:.1f}|{x:.2f}", {"x": x}) for x in (0.125, 0.375)]
    # JSON has no NaN or infinity: those travel as {"float": "nan"} (check_mirrors.mjs).
    return [(t, {k: jsonable_number(v) for k, v in values.items()}) for t, values in cases]


def jsonable_number(value):
    if isinstance(value, float) and not math.isfinite(value):
        return {"float": str(value)}
    return value


def python_number(value):
    return float(value["float"]) if isinstance(value, dict) else value


def test_sentences_are_filled_as_python_formats_them(javascript):
    """header.js fill() (the diagnosis', sampling and sh checks' sentences in practice mode)
    writes what Python's str.format writes for every template of lab/grading/words.py."""
    cases, _, js = javascript
    assert len(cases["fill"]) > 60
    for (template, values), got in zip(cases["fill"], js["fill"], strict=True):
        values = {k: python_number(v) for k, v in values.items()}
        assert got == template.format(**values), (template, values)


def test_plot_scale_matches_python(javascript):
    """The page's peak (grazing values left out) and radii, linear and log, are plotscale's."""
    _, _, js = javascript
    for lobe, got in zip(LOBES, js["peak"], strict=True):
        assert got == pytest.approx(peak_value(np.array(THETA_O), np.array(lobe)), rel=1e-12)
    for (f, top, log), got in zip(RADII, js["radius"], strict=True):
        want = float(Scale(top, log, PLOT_DECADES).radius(np.array([f]))[0])
        assert got == pytest.approx(want, rel=1e-12, abs=1e-15), (f, top, log)

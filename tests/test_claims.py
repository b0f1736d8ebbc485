"""Every number the deck or a preset claims, computed again by the renderer (the GLSL).

Each claim names the text it checks (which must appear in its file, so editing the text
without the claim fails) and how the renderer computes it. A scan makes sure no "≈ N" or
"N×" in the presets' notes or the deck goes unchecked.
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pytest

from lab.constants import LUMA
from lab.presets import read_preset, shipped_presets
from lab.resources import data_dir

DECK = data_dir("slides") / "lecture.md"
PRESETS = {p.stem[:2]: p for p in shipped_presets()}


def preset_models(number: str) -> list[tuple[str, dict]]:
    data = read_preset(PRESETS[number])
    return [
        (
            m["model"],
            {k: tuple(v) if isinstance(v, list) else v for k, v in m.get("values", {}).items()},
        )
        for m in data["model"]
    ]


def lum(values: np.ndarray) -> np.ndarray:
    return values.astype(np.float64) @ np.array(LUMA)


def peak_angle(renderer, name: str, values: dict, theta_i: float) -> float:
    """θo (deg) where f_r cos θo peaks in the plane of incidence (1-degree steps)."""
    polar = renderer.polar(name, values, theta_i, cos_weighted=True)
    return float(polar.theta_o[np.argmax(lum(polar.values))])


def peak_value(renderer, name: str, values: dict, theta_i: float) -> float:
    return float(lum(renderer.polar(name, values, theta_i, cos_weighted=True).values).max())


def f_at(renderer, name: str, values: dict, theta_i: float, theta_o: float) -> float:
    """Luminance of f_r for light at theta_i and view at theta_o on the mirror side."""
    from lab.render import direction

    L, V = direction(theta_i, 0.0)[None], direction(theta_o, 180.0)[None]
    return float(lum(renderer.probe(name, values, L, V))[0])


def sphere_ratio(renderer, name: str, values: dict, r: float) -> float:
    """Radiance at radius r of the disc over the centre's, lit and seen from the eye."""
    image = renderer.sphere(name, values, (0.0, 0.0), size=201)
    row = lum(image[100, :, :3])
    return float(row[100 + int(round(r * 100))] / row[100])


@dataclass
class Claim:
    where: str  # "deck" or a preset number
    text: str  # the words that make the claim, as they stand in the file
    value: Callable[[object], float]  # computed by the renderer
    expected: float
    tolerance: float  # absolute


CT = {"kd": (0.0, 0.0, 0.0), "m": 0.35}
CT_ = ("cook_torrance", CT)
PHONG = {"kd": (0.0, 0.0, 0.0), "ks": (0.2, 0.2, 0.2), "ke": 20.0}


def _preset(number: str, index: int) -> tuple[str, dict]:
    return preset_models(number)[index]


def _ratio_at_mirror(r) -> float:
    schlick, constant = _preset("05", 0), _preset("05", 1)
    return f_at(r, *schlick, 80.0, 80.0) / f_at(r, *constant, 80.0, 80.0)


def _same_centre(r) -> float:
    """Lommel-Seeliger (albedo 0.8) over Lambert (albedo 0.1) at the disc's centre."""
    lambert = {"albedo": (0.1, 0.1, 0.1)}
    return f_at(r, "lommel_seeliger", {}, 0.0, 0.0) / f_at(r, "lambert", lambert, 0.0, 0.0)


def _ct(fresnel: str = "schlick") -> dict:
    return {**CT, "fresnel": fresnel}


CLAIMS = [
    # Preset 04: the off-specular peak at θi = 75°.
    Claim(
        "04",
        "Cook-Torrance peaks past the mirror direction (≈ 85°)",
        lambda r: peak_angle(r, *_preset("04", 1), 75.0),
        85.0,
        1.0,
    ),
    Claim("04", "Phong before it (≈ 68°)", lambda r: peak_angle(r, *_preset("04", 0), 75.0), 68, 1),
    # Preset 05: Schlick's F against constant F = f0 at the mirror direction, θi = 80°.
    Claim("05", "Schlick's F is 10× the constant F = f0", _ratio_at_mirror, 10.0, 0.5),
    # Preset 07 and the deck: the Lommel-Seeliger disc is flat, and as bright as Lambert's.
    Claim(
        "07",
        "the Lommel-Seeliger disc is flat",
        lambda r: sphere_ratio(r, "lommel_seeliger", {}, 0.8),
        1.0,
        0.01,
    ),
    Claim("deck", "Same centre: $0.1/\\pi = 0.8/(8\\pi)$", _same_centre, 1.0, 0.002),
    # The deck's off-specular slide (θi = 75°, Cook-Torrance m = 0.35, f0 = 0.04, kd = 0).
    Claim("deck", "peaks **past** it, at 85°", lambda r: peak_angle(r, *CT_, 75.0), 85, 1),
    Claim(
        "deck",
        "peaks **at** the mirror direction, 75°",
        lambda r: peak_angle(r, "cook_torrance", _ct("none"), 75.0),
        75,
        0.5,
    ),
    Claim("deck", "short of it, at 68°", lambda r: peak_angle(r, "phong", PHONG, 75.0), 68, 1),
    Claim("deck", "2.5 sr⁻¹ at the mirror direction", lambda r: f_at(r, *CT_, 75, 75), 2.5, 0.05),
    Claim("deck", "16 sr⁻¹ at 89°", lambda r: f_at(r, *CT_, 75.0, 89.0), 16.0, 0.5),
    # The live demo at θi = 60° (the demo's own peak marks: tests/test_slides.py).
    Claim("deck", "Schlick's $F$ (left) peaks at 80°", lambda r: peak_angle(r, *CT_, 60), 80, 1),
    Claim(
        "deck",
        "with $F = 1$ (right) at the\nmirror direction, 60°",
        lambda r: peak_angle(r, "cook_torrance", _ct("none"), 60.0),
        60,
        0.5,
    ),
    Claim("deck", "Their peaks: 0.17", lambda r: peak_value(r, *CT_, 60.0), 0.17, 0.005),
    Claim(
        "deck",
        "0.17 and 1.3 sr⁻¹",
        lambda r: peak_value(r, "cook_torrance", _ct("none"), 60),
        1.3,
        0.05,
    ),
]


def source(where: str) -> str:
    if where == "deck":
        return DECK.read_text(encoding="utf-8")
    return str(read_preset(PRESETS[where]).get("notes", ""))


@pytest.mark.parametrize("claim", CLAIMS, ids=[f"{c.where}:{c.text[:30]}" for c in CLAIMS])
def test_claim_holds(renderer, claim):
    assert claim.text in source(claim.where), f"the {claim.where} no longer says {claim.text!r}"
    value = claim.value(renderer)
    assert math.isfinite(value)
    assert abs(value - claim.expected) <= claim.tolerance, (
        f"{claim.where} claims {claim.text!r}: the renderer gives {value:.4g}"
    )


NUMBER_CLAIM = re.compile(r"≈\s*[\d.]+|[\d.]+\s*×")


@pytest.mark.parametrize("where", ["deck", *PRESETS])
def test_no_unchecked_approximate_numbers(where):
    """Every '≈ N' and 'N×' in the notes and the deck lies inside a checked claim's text."""
    text = source(where)
    checked = [c.text for c in CLAIMS if c.where == where]
    for match in NUMBER_CLAIM.finditer(text):
        around = text[max(match.start() - 80, 0) : match.end() + 80]
        assert any(c in around and match.group(0) in c for c in checked), (
            f"{where}: {match.group(0)!r} is claimed but no test checks it: {around!r}"
        )


def test_deck_file_exists():
    assert Path(DECK).is_file()

"""The shape of an error, named from probe values alone (lab.grading.diagnosis.shape) and
one hint for generated edits that behave alike (lab.grading.mistakes.either)."""

from __future__ import annotations

import numpy as np
import pytest

from lab.grading import diagnosis, mistakes
from lab.grading.exercise import Check


def probe_rows(n: int = 200, seed: int = 3) -> np.ndarray:
    rng = np.random.default_rng(seed)
    return np.stack(
        [rng.uniform(0, hi, n) for hi in (80, 360, 80, 360)],
        axis=1,
    )


@pytest.mark.parametrize(
    "factor,words",
    [
        (np.pi, "π times too large"),
        (1 / np.pi, "π times too small"),
        (4.0, "4 times too large"),
        (0.5, "2 times too small"),
        (1.37, "1.37 times too large"),
    ],
)
def test_constant_ratio_is_named(factor, words):
    check = Check("probe.x", "probe", 1.0)
    angles = probe_rows()
    expected = np.random.default_rng(1).uniform(0.1, 2.0, (len(angles), 3))
    assert words in diagnosis.shape(check, angles, expected, expected * factor)


def test_cosine_factor_grazing_and_channel_are_named():
    check = Check("probe.x", "probe", 1.0)
    angles = probe_rows()
    expected = np.random.default_rng(1).uniform(0.1, 2.0, (len(angles), 3))
    cos_i = np.cos(np.radians(angles[:, 0]))[:, None]
    assert "cos θi" in diagnosis.shape(check, angles, expected, expected * cos_i)
    assert "√(cos θi cos θo)" in diagnosis.shape(
        check,
        angles,
        expected,
        expected * np.sqrt(cos_i * np.cos(np.radians(angles[:, 2]))[:, None]),
    )
    grazing = expected.copy()
    grazing[np.maximum(angles[:, 0], angles[:, 2]) > 70] *= 1.5
    assert "near grazing" in diagnosis.shape(check, angles, expected, grazing)
    red = expected.copy()
    red[:50, 0] *= 0.5
    assert "red channel" in diagnosis.shape(check, angles, expected, red)
    grey = np.repeat(expected[:, :1], 3, axis=1)
    assert "grey" in diagnosis.shape(check, angles, expected, grey)
    assert diagnosis.shape(check, angles, expected, expected * (1 + 1e-5)) == ""


def test_zeros_blame_the_horizon_only_below_it():
    """Wrong only where the solution is 0: below the surface, the horizon test is missing;
    above it, a dot product the solution clamps is not (abs(R·V) in 02)."""
    check = Check("probe.x", "probe", 1.0)
    angles = probe_rows()
    angles[:20, 0] = 95.0  # the light below the surface
    expected = np.random.default_rng(1).uniform(0.1, 2.0, (len(angles), 3))
    expected[:40] = 0.0
    below = expected.copy()
    below[:20] = 0.3
    assert "below the surface" in diagnosis.shape(check, angles, expected, below)
    above = expected.copy()
    above[20:40] = 0.3
    assert "clamps" in diagnosis.shape(check, angles, expected, above)


def test_alike_edits_share_one_hint():
    advice = "check which dot product each factor uses"
    first, second = f"V·H where N·H belongs: {advice}", f"N·H where V·H belongs: {advice}"
    both = f"V·H where N·H belongs, or N·H where V·H belongs: {advice}"
    assert mistakes.either(first, second) == both
    assert mistakes.either(first, first) == first
    assert mistakes.either("x is off", "y") == "x is off; or else y"

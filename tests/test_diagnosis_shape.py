"""The shape of an error, named from probe values alone (lab.grading.diagnosis.shape) and
one hint for generated edits that behave alike (lab.grading.mistakes.either)."""

from __future__ import annotations

import json
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

from lab.grading import diagnosis, mistakes
from lab.grading.exercise import Check
from lab.web.exercises import diagnosis_rules


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
    assert "Fresnel" in diagnosis.shape(check, angles, expected, grazing)
    # A check that reads a table has no Fresnel or G term: its lookup of large angles is
    # what differs there (exercise 12's θd in degrees was sent to Fresnel and G).
    tabulated = Check("probe.x", "probe", 1.0, table=("a table",))
    said = diagnosis.shape(tabulated, angles, expected, grazing)
    assert "near grazing" in said and "θd" in said and "Fresnel" not in said
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


def coloured_case() -> tuple[Check, np.ndarray, np.ndarray]:
    """A probe check, its rows and a coloured solution's values at them."""
    angles = probe_rows()
    expected = np.random.default_rng(1).uniform(0.1, 2.0, (len(angles), 3)) * [1.0, 0.5, 0.2]
    return Check("probe.x", "probe", 1.0), angles, expected


def seam_case() -> tuple[Check, np.ndarray, np.ndarray, np.ndarray]:
    """A check reading a (small) table, rows of which some lie across φd's seam, values."""
    from lab.grading.tables import TableSpec

    check = Check("bins.x", "bin_edges", 1.0, table=(TableSpec("ggx", dims=(8, 8, 16)),))
    angles = probe_rows(400)
    seam = diagnosis.seam_rows(check, angles)
    expected = np.random.default_rng(1).uniform(0.1, 2.0, (len(angles), 3))
    return check, angles, expected, seam


def test_a_lookup_wrong_only_across_the_periodic_seam_is_named():
    """Values off only within half a bin of φd's ends (a clamp where it should wrap, at
    either end, however written) are named; off elsewhere too, or without a table, not."""
    check, angles, expected, seam = seam_case()
    assert 8 <= seam.sum() < len(seam) - 8  # both kinds of row are there
    for end in (seam, seam & (np.arange(len(seam)) % 2 == 0)):  # all of them, or some
        got = expected.copy()
        got[end] *= 1.3
        assert "φd is periodic" in diagnosis.shape(check, angles, expected, got)
    got = expected.copy()
    got[seam] *= 1.3
    got[np.flatnonzero(~seam)[:3]] *= 0.7  # wrong elsewhere as well: no seam
    assert "periodic" not in diagnosis.shape(check, angles, expected, got)
    plain = Check("probe.x", "probe", 1.0)
    got = expected.copy()
    got[seam] *= 1.3
    assert "periodic" not in diagnosis.shape(plain, angles, expected, got)
    assert diagnosis.seam_rows(Check("p", "probe", 1.0, table=("a table",)), angles) is None


def test_a_term_that_is_zero_is_called_missing_not_grey():
    """0 is grey in every channel, but a specular term that is 0 everywhere (never added)
    is no float used for a colour: it is named as a part that is missing."""
    check, angles, expected = coloured_case()
    said = diagnosis.shape(check, angles, expected, np.zeros_like(expected))
    assert said.startswith("it is 0 everywhere") and "missing" in said
    assert "grey" not in said
    # Zero only where it is wrong (elsewhere right): 'wherever it is wrong'.
    got = expected.copy()
    got[::2] = 0.0
    assert diagnosis.shape(check, angles, expected, got).startswith("it is 0 wherever")
    # Grey but not zero stays what it was.
    grey = np.repeat(expected.mean(axis=1, keepdims=True), 3, axis=1)
    assert "grey" in diagnosis.shape(check, angles, expected, grey)


@pytest.mark.skipif(shutil.which("node") is None, reason="node is not installed (apt nodejs)")
def test_the_pages_shape_says_what_the_graders_says(tmp_path):
    """static/diagnosis.js's shape() (practice mode) against this one, case by case: the
    zero term (all or part), grey, one channel, a factor, a cosine, negative values."""
    check, angles, expected = coloured_case()
    half_zero = expected.copy()
    half_zero[::2] = 0.0
    red = expected.copy()
    red[:, 0] *= 1.5
    cases = {
        "zero": np.zeros_like(expected),
        "half zero": half_zero,
        "grey": np.repeat(expected.mean(axis=1, keepdims=True), 3, axis=1),
        "red": red,
        "factor": expected * 4.0,
        "cosine": expected * np.cos(np.radians(angles[:, 0]))[:, None],
        "negative": expected - 3.0,
        "not finite": np.where(np.arange(len(expected))[:, None] % 5 == 0, np.nan, expected),
        "1/π": expected / np.pi,
        "odd factor": expected * 1.37,
        "scaled cosine": expected * 1.5 * np.cos(np.radians(angles[:, 0]))[:, None],
    }
    python = {k: diagnosis.shape(check, angles, expected, v) for k, v in cases.items()}
    # Across a table's periodic seam: the page reads the seam's rows as exercises.json sends.
    table, rows, table_expected, seam = seam_case()
    across = table_expected.copy()
    across[seam] *= 1.3
    python["seam"] = diagnosis.shape(table, rows, table_expected, across)
    # The terms' sentence, with one, two and three names (', ' and ' and ' as the grader's).
    terms = [(["D"], [], ""), (["D", "G"], ["diffuse"], "x"), (["D", "G", "F"], ["a", "b"], "")]
    python["terms"] = [diagnosis.terms_sentence(*t) for t in terms]
    data = {
        "check": {"atol": check.atol, "rtol": check.rtol},
        "angles": angles.tolist(),
        "expected": expected.tolist(),
        "cases": {k: np.nan_to_num(v, nan=-7e300).tolist() for k, v in cases.items()},
        "terms": terms,
        "rules": diagnosis_rules(),  # the words and thresholds, as exercises.json sends them
        "seam": {
            "check": {
                "atol": table.atol,
                "rtol": table.rtol,
                "table": [{"model": "ggx"}],
                "diagnosis": {"seam": np.flatnonzero(seam).tolist()},
            },
            "angles": rows.tolist(),
            "expected": table_expected.tolist(),
            "got": across.tolist(),
        },
    }
    (tmp_path / "data.json").write_text(json.dumps(data))
    module = (Path(__file__).resolve().parent.parent / "lab/web/static/diagnosis.js").as_uri()
    script = tmp_path / "shape.mjs"
    script.write_text(
        f'import {{ shape, termsSentence, useRules }} from "{module}";\n'
        'import { readFileSync } from "node:fs";\n'
        f'const d = JSON.parse(readFileSync("{tmp_path / "data.json"}", "utf8"));\n'
        "useRules(d.rules);\n"
        "const out = {};\n"
        "for (const [k, got] of Object.entries(d.cases)) "
        "out[k] = shape(d.check, d.angles, d.expected, "
        "got.map((r) => r.map((x) => (x === -7e300 ? NaN : x))));\n"
        "out.terms = d.terms.map((t) => termsSentence(...t));\n"
        "out.seam = shape(d.seam.check, d.seam.angles, d.seam.expected, d.seam.got);\n"
        "console.log(JSON.stringify(out));\n"
    )
    run = subprocess.run(["node", str(script)], capture_output=True, text=True, check=True)
    assert json.loads(run.stdout) == python
    assert python["zero"].startswith("it is 0 everywhere")
    assert "φd is periodic" in python["seam"]

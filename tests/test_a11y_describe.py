"""Plot descriptions (lab/describe.py and its mirror lab/web/static/describe.js): the words
and the table equal `brdf-lab eval` at the same settings, and the page says the same words."""

from __future__ import annotations

import csv
import json
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

from lab import describe
from lab.constants import GRAZING_DEG, LUMA

ROOT = Path(__file__).resolve().parent.parent
CASES = [  # (models with parameters, theta_i, cos weighted)
    ([("phong", {})], 45.0, False),
    ([("phong", {"ke": 4.0})], 30.0, False),
    ([("lambert", {})], 45.0, False),
    ([("mirror", {})], 30.0, False),
    ([("ggx", {"alpha": 0.3})], 60.0, True),
    ([("phong", {}), ("blinn_phong", {}), ("cook_torrance", {}), ("ggx", {})], 45.0, False),
    ([("ward", {})], 0.0, False),
]


def lobes(case):
    models, theta_i, cos = case
    return [describe.reference_lobe(m, p, theta_i, cos) for m, p in models]


def eval_lobe(tmp_path: Path, model: str, params: dict, theta_i: float) -> np.ndarray:
    """f_r luminance at theta_o = -90..90 (1 deg) from `brdf-lab eval` (the GLSL model)."""
    from lab.cli import main

    rows = tmp_path / "angles.csv"
    theta_o = np.arange(-90, 91)
    with rows.open("w") as f:
        f.write("theta_i,phi_i,theta_o,phi_o\n")
        for t in theta_o:
            f.write(f"{theta_i},0,{abs(t)},{180 if t >= 0 else 0}\n")
    out = tmp_path / "eval.csv"
    args = ["eval", model, "--in", str(rows), "--out", str(out)]
    for name, value in params.items():
        args += ["--set", f"{name}={value}"]
    assert main(args) == 0
    with out.open() as f:
        table = list(csv.DictReader(f))
    rgb = np.array([[float(r[c]) for c in ("r", "g", "b")] for r in table])
    return rgb @ np.asarray(LUMA)


@pytest.mark.parametrize(
    "model,params,theta_i", [("phong", {"ke": 20.0}, 45.0), ("ggx", {"alpha": 0.2}, 30.0)]
)
def test_description_and_table_equal_brdf_lab_eval(tmp_path, model, params, theta_i):
    ours = describe.reference_lobe(model, params, theta_i)
    values = eval_lobe(tmp_path, model, params, theta_i)
    np.testing.assert_allclose(ours.values, values, rtol=2e-4, atol=1e-6)
    from_eval = describe.Lobe(model, np.arange(-90.0, 91.0), values)
    assert describe.describe([ours], theta_i) == describe.describe([from_eval], theta_i)
    assert describe.table([ours], theta_i) == describe.table([from_eval], theta_i)
    # The words say what the numbers are: the peak at the largest value, in the mirror direction.
    s = describe.summarise(from_eval)
    assert s.peak == pytest.approx(values[np.abs(np.arange(-90, 91)) <= GRAZING_DEG].max())
    text = describe.describe([from_eval], theta_i)
    assert abs(s.peak_theta - theta_i) <= describe.NEAR_DEG
    assert (
        f"θo {describe.deg(s.peak_theta)}, the mirror direction, {describe.fmt(s.peak)} sr⁻¹"
        in text
    )


def test_half_width_and_floor_of_phong_in_closed_form():
    """Phong's specular ks (cos α)^ke (ke+2)/2π falls to half at cos α = 2^(-1/ke)."""
    ke = 20.0
    lobe = describe.reference_lobe("phong", {"ke": ke, "kd": [0, 0, 0]}, 40.0)
    s = describe.summarise(lobe)
    assert s.peak_theta == 40
    assert s.half_width == pytest.approx(np.degrees(np.arccos(2 ** (-1 / ke))), abs=0.3)
    lambert = describe.reference_lobe("lambert", {"albedo": [0.5, 0.5, 0.5]}, 40.0)
    assert describe.summarise(lambert).floor == pytest.approx(0.5 / np.pi)
    assert "no lobe" in describe.describe([lambert], 40.0)


def test_cursor_says_the_share_of_the_peak():
    lobe = describe.reference_lobe("phong", {"ke": 20.0, "kd": [0, 0, 0]}, 40.0)
    s = describe.summarise(lobe)
    value = lobe.values[lobe.theta_o == 30][0]
    said = describe.cursor(lobe, 30)
    assert said == f"θo 30°, f_r {describe.fmt(value)}, {round(100 * value / s.peak)} % of the peak"


def test_table_marks_peak_and_mirror_and_csv_reads_back():
    ls = lobes(CASES[5])
    rows = describe.table(ls, 45.0)
    assert rows[0][0] == "θo (deg)" and len(rows) == 1 + 37
    marked = {r[0]: r[-1] for r in rows[1:] if r[-1]}
    assert "mirror" in marked["45"] and "peak phong" in marked["45"]
    back = list(csv.reader(describe.csv_text(rows).splitlines()))
    assert [float(x) for x in back[1 + 27][1:-1]] == pytest.approx(
        [float(x) for x in rows[1 + 27][1:-1]]
    )


@pytest.mark.skipif(shutil.which("node") is None, reason="needs node")
def test_page_says_the_same_words(tmp_path):
    """describe.js on the same lobes: the same text, table and cursor, to the character."""
    cases = []
    for case in CASES:
        ls = lobes(case)
        theta_i, cos = case[1], case[2]
        what = "f_r cos θo" if cos else "f_r"
        cases.append(
            {
                "lobes": [
                    {
                        "name": lo.name,
                        "thetaO": lo.theta_o.tolist(),
                        "values": [float(v) for v in lo.values],
                        "spike": lo.spike,
                    }
                    for lo in ls
                ],
                "thetaI": theta_i,
                "what": what,
                "python": {
                    "text": describe.describe(ls, theta_i, what),
                    "table": describe.table(ls, theta_i),
                    "csv": describe.csv_text(describe.table(ls, theta_i)),
                    "cursor": [describe.cursor(ls[0], t, what) for t in (-40, 0, 12, 45)],
                },
            }
        )
    data = tmp_path / "cases.json"
    data.write_text(json.dumps(cases))
    script = tmp_path / "check.mjs"
    module = (ROOT / "lab/web/static/describe.js").as_uri()
    script.write_text(
        f"""import * as d from "{module}";
import {{ readFileSync }} from "node:fs";
const cases = JSON.parse(readFileSync(process.argv[2], "utf8"));
const out = cases.map((c) => {{
  const table = d.table(c.lobes, c.thetaI, {GRAZING_DEG});
  const text = d.describe(c.lobes, c.thetaI, c.what, {GRAZING_DEG});
  return {{ text, table, csv: d.csvText(table),
    cursor: [-40, 0, 12, 45].map((t) => d.cursor(c.lobes[0], t, c.what, {GRAZING_DEG})) }};
}});
console.log(JSON.stringify(out));
"""
    )
    result = subprocess.run(
        ["node", str(script), str(data)], capture_output=True, text=True, check=True
    )
    for case, js in zip(cases, json.loads(result.stdout), strict=True):
        assert js == case["python"]

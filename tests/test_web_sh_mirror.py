"""The page's spherical harmonics (static/sh.js, run in node) agree with lab/measured/sh.py:
the quadrature grid, the harmonics and, for several lobes, the coefficients and the error of
every order. The page gets its errors from Parseval's identity (the coefficients' energy),
the desktop sums the squared residual over the nodes: the two agree to rounding."""

from __future__ import annotations

import json
import math
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

from lab.measured import sh
from lab.views import sh as sh_view

ROOT = Path(__file__).resolve().parent.parent
CHECKER = ROOT / "lab" / "web" / "check_sh.mjs"
GRID = sh_view.GRID  # the app's and, as the view's page data, the page's
ORDER = sh_view.MAX_ORDER


def lobes(grid: sh.Grid) -> dict[str, np.ndarray]:
    """Lobes g = f_r cos θo on the grid: smooth, exact at order 1, sharp, noisy, clipped."""
    V = grid.directions
    z = V[:, 2]
    mirror = np.array([-math.sin(0.6), 0.0, math.cos(0.6)])
    along = np.clip(V @ mirror, 0.0, None)
    rng = np.random.default_rng(3)
    return {
        "lambert": 0.3 * z,
        "phong": (0.2 + 3.0 * along**40) * z,
        "sharp": 50.0 * along**1000 * z,
        "noise": rng.uniform(0.0, 1.0, len(z)),
        "half": np.where(V[:, 0] > 0, 1.0, 0.0) * z,
        "zero": np.zeros(len(z)),
    }


@pytest.fixture(scope="module")
def mirrored(tmp_path_factory):
    if shutil.which("node") is None:
        pytest.skip("node is not installed (apt nodejs; python3 -m lab test installs it)")
    grid = sh.hemisphere_grid(*GRID)
    rng = np.random.default_rng(5)
    directions = [(0.0, 0.0), (math.pi / 2, 1.0), (math.pi, -2.0)]
    directions += [
        (float(t), float(p)) for t, p in rng.uniform([0, -math.pi], [math.pi, math.pi], (20, 2))
    ]
    table = lobes(grid)
    cases = {
        "directions": directions,
        "lobes": [v.tolist() for v in table.values()],
        "shape": json.loads(json.dumps(sh_view.VIEW.page_data)),  # as the manifest sends it
    }
    path = tmp_path_factory.mktemp("sh") / "cases.json"
    path.write_text(json.dumps(cases), encoding="utf-8")
    run = subprocess.run(
        ["node", str(CHECKER), str(path)], capture_output=True, text=True, timeout=60
    )
    assert run.returncode == 0, run.stderr
    return grid, directions, table, json.loads(run.stdout)


def test_grid_matches(mirrored):
    grid, _, _, js = mirrored
    x, w = np.polynomial.legendre.leggauss(2 * GRID[0])
    np.testing.assert_allclose(js["legendre"]["x"], x, rtol=0, atol=1e-14)
    np.testing.assert_allclose(js["legendre"]["w"], w, rtol=1e-10)
    V = np.array(js["grid"]["V"]).reshape(-1, 4)
    np.testing.assert_allclose(V[:, :3], grid.directions, atol=1e-7)  # float32 texture
    np.testing.assert_allclose(js["grid"]["weight"], grid.weight, rtol=1e-10)


def test_harmonics_match(mirrored):
    _, directions, _, js = mirrored
    for (theta, phi), got in zip(directions, js["real_sh"], strict=True):
        want = sh.real_sh(ORDER, np.array([theta]), np.array([phi]))[0]
        np.testing.assert_allclose(got, want, rtol=0, atol=1e-12)


def test_coefficients_and_errors_match(mirrored):
    """Parseval's errors (page) equal the residual summed over the nodes (desktop)."""
    grid, _, table, js = mirrored
    projector = sh.Projector(ORDER, grid)
    for (name, lobe), got in zip(table.items(), js["analyse"], strict=True):
        coefficients = projector.project(lobe[:, None])
        top = max(np.abs(coefficients).max(), 1e-300)
        np.testing.assert_allclose(
            got["coefficients"], coefficients[:, 0], rtol=0, atol=1e-12 * top
        )
        errors = projector.errors(lobe[:, None], coefficients)
        # Rounding: |g|² - Σ a²/2 cancels to ~1e-15 of |g|², i.e. ~1e-7 of the error's scale.
        np.testing.assert_allclose(got["errors"], errors, rtol=1e-6, atol=1e-6, err_msg=name)
        if name == "lambert":
            assert got["errors"][0] > 0.1 and max(got["errors"][1:]) < 1e-6
        if name in ("phong", "sharp"):
            assert all(a >= b for a, b in zip(got["errors"], got["errors"][1:], strict=False)), name
        if name == "zero":
            assert got["errors"] == [0.0] * (ORDER + 1)

"""Fitting analytic models to tables: recovery of known parameters, model comparison, CLI."""

from __future__ import annotations

import numpy as np
import pytest

from lab.cli import main
from lab.measured import fit as fitting
from lab.measured.merl import write_merl
from lab.measured.tabulate import tabulate
from lab.models import load_model
from lab.presets import read_preset, write_preset

TRUTH = {"kd": (0.25, 0.12, 0.05), "ks": (0.8, 0.7, 0.6), "alpha": 0.2, "f0": (0.05,) * 3}
DIMS = (45, 45, 90)  # a quarter-resolution table: the fit uses a subsample anyway


@pytest.fixture(scope="module")
def noisy_ggx(renderer):
    """GGX data with 3 % relative noise."""
    return tabulate("ggx", TRUTH, dims=DIMS, noise=0.03, seed=7, renderer=renderer)


@pytest.fixture(scope="module")
def samples(noisy_ggx):
    return fitting.select_samples(noisy_ggx, 6000)


def test_fit_recovers_parameters_from_noisy_data(samples):
    result = fitting.fit(samples, "ggx")
    values = result.lobes[0]
    # Stated tolerances (3 % noise): roughness 3 %, diffuse 5 %, specular at normal
    # incidence ks * f0 10 %.
    assert values["alpha"] == pytest.approx(TRUTH["alpha"], rel=0.03)
    assert np.allclose(values["kd"], TRUTH["kd"], rtol=0.05)
    spec = np.array(values["ks"]) * np.array(values["f0"])
    assert np.allclose(spec, np.array(TRUTH["ks"]) * 0.05, rtol=0.10)
    assert result.error < 0.01


def test_wrong_model_fits_worse(samples):
    own = fitting.fit(samples, "ggx").error
    for other in ("ward", "blinn_phong", "cook_torrance"):
        assert fitting.fit(samples, other).error > 2 * own, other


def test_selection_excludes_grazing_angles_and_unmeasured(noisy_ggx):
    table = noisy_ggx
    table.raw[:, 10, 20, :] = -1.0  # a band that was "not measured"
    chosen = fitting.select_samples(table, 100000)
    assert np.all(chosen.L[:, 2] >= np.cos(np.radians(80.0)) - 1e-12)
    assert np.all(chosen.V[:, 2] >= np.cos(np.radians(80.0)) - 1e-12)
    assert np.all(chosen.f >= 0) and chosen.weight.sum() == pytest.approx(1.0)
    table.raw[:, 10, 20, :] = np.abs(table.raw[:, 10, 21, :])


def test_two_lobes_and_preset_format(samples, tmp_path):
    result = fitting.fit(samples, "cook_torrance", lobes=2)
    one = fitting.fit(samples, "cook_torrance", lobes=1)
    assert result.error <= one.error * 1.001
    table = tmp_path / "data" / "ct.binary"
    path = write_preset(result.preset(table, tmp_path), tmp_path / "fit.toml")
    preset = read_preset(path)  # the lab's TOML preset layout, read back
    entries = preset["model"]
    assert [m["model"] for m in entries] == ["measured", "cook_torrance", "cook_torrance"]
    assert entries[0]["table"] == "data/ct.binary"
    assert "SUM" in preset["notes"] and "lobe 2 of 2" in entries[2]["label"]
    model = load_model("cook_torrance")
    for entry in entries[1:]:
        model.resolve(
            {k: tuple(v) if isinstance(v, list) else v for k, v in entry["values"].items()}
        )  # inside the header's ranges
    assert entries[2]["values"]["kd"] == [0.0, 0.0, 0.0]
    assert set(preset["views"]) >= {"sphere", "polar", "sh"}


def test_fit_command_writes_preset_and_figure(renderer, tmp_path, capsys):
    table = tabulate("cook_torrance", {"m": 0.2}, dims=(30, 30, 60), renderer=renderer)
    path = write_merl(table, tmp_path / "ct.binary")
    assert (
        main(
            [
                "fit",
                str(path),
                "--model",
                "cook_torrance",
                "--model",
                "ward",
                "--samples",
                "3000",
                "--outdir",
                str(tmp_path),
            ]
        )
        == 0
    )
    out = capsys.readouterr().out
    assert "m=0.2" in out and "error" in out and out.count("wrote preset") == 2
    preset = read_preset(tmp_path / "ct-cook_torrance-fit.toml")
    assert preset["model"][0] == {
        "model": "measured",
        "table": "ct.binary",
        "label": "measured",
        "color": fitting.MEASURED_COLOR,
        "visible": True,
        "values": {"interpolation": "linear", "gain": 1.0},
    }
    assert preset["model"][1]["values"]["m"] == pytest.approx(0.2, rel=0.01)
    assert (tmp_path / "ct-ward-fit.png").stat().st_size > 10000
    # The comparison table ranks the true model first.
    assert out.split("rel.")[1].split()[0] == "cook_torrance"

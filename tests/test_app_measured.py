"""Measured BRDFs in the desktop lab (real window, real OpenGL; run under xvfb-run)."""

from __future__ import annotations

import os
import sys

import numpy as np
import pytest

pytest.importorskip("pytestqt")
if sys.platform.startswith("linux") and not os.environ.get("DISPLAY"):
    pytest.skip("needs a display: run under xvfb-run -a", allow_module_level=True)

from PyQt6.QtCore import QTimer  # noqa: E402
from PyQt6.QtWidgets import QApplication  # noqa: E402
from qtapp import floating_view, settle  # noqa: E402

from lab.app.window import MainWindow  # noqa: E402
from lab.cli import main  # noqa: E402
from lab.measured.merl import MerlTable, write_merl  # noqa: E402
from lab.measured.model import measured_model  # noqa: E402
from lab.measured.tabulate import tabulate  # noqa: E402
from lab.models import load_model  # noqa: E402
from lab.presets import read_preset  # noqa: E402

GGX = {"kd": (0.2, 0.1, 0.05), "ks": (0.8, 0.8, 0.8), "alpha": 0.25, "f0": (0.5, 0.5, 0.5)}
DIMS = (45, 45, 90)  # a quarter-size table: quick to make, still a real MERL layout


@pytest.fixture(scope="module")
def table_file(renderer, tmp_path_factory):
    """GGX tabulated in the MERL layout (no noise), written once for the module."""
    path = tmp_path_factory.mktemp("measured") / "ggx.binary"
    return write_merl(tabulate("ggx", GGX, dims=DIMS, renderer=renderer), path)


@pytest.fixture(scope="module")
def fit_preset(table_file, tmp_path_factory):
    """`brdf-lab fit` of GGX to the table: the preset it writes (in another folder)."""
    outdir = tmp_path_factory.mktemp("fit")
    assert (
        main(
            [
                "fit",
                str(table_file),
                "--model",
                "ggx",
                "--samples",
                "3000",
                "--outdir",
                str(outdir),
                "--no-figure",
            ]
        )
        == 0
    )
    return outdir / "ggx-ggx-fit.toml"


def spheres(win: MainWindow) -> dict[str, np.ndarray]:
    return {state.label: image for state, image in win.view("sphere").floats}


def test_fit_preset_opens_with_measured_and_fitted_overlaid(
    qtbot, window, fit_preset, table_file, output_dir
):
    data = read_preset(fit_preset)
    measured, fitted = data["model"]
    assert measured["model"] == "measured" and measured["table"] == "../measured0/ggx.binary"
    assert fitted["model"] == "ggx" and fitted["values"]["alpha"] == pytest.approx(0.25, rel=0.01)
    window.load_preset(fit_preset)
    settle(qtbot, window)
    names = [(m.model.name, m.label) for m in window.lab.models]
    assert names == [("measured", "measured"), ("ggx", "ggx fit")]
    assert window.lab.models[0].model.table.path.resolve() == table_file.resolve()
    # Every view draws both.
    images = spheres(window)
    assert set(images) == {"measured", "ggx fit"}
    for name in ("polar", "lobe3d", "slice", "albedo"):
        assert len(window.view(name).data) == 2, name
    # A fit of a tabulated GGX is GGX: the spheres agree up to the table's binning.
    a, b = images["measured"][..., :3], images["ggx fit"][..., :3]
    on = images["measured"][..., 3] > 0
    assert a.max() > 0.3
    diff = np.abs(a - b)[on]
    assert np.median(diff) < 0.002 and np.percentile(diff, 99) < 0.03 * b.max()
    # So do the polar lobes (luminance, away from grazing angles).
    (_, pm), (_, pf) = window.view("polar").data
    near = np.abs(pm.theta_o) <= 80
    assert np.allclose(pm.values[near], pf.values[near], rtol=0.05, atol=1e-3)
    window.grab().save(str(output_dir / "app_measured_vs_fit.png"))


def test_open_binary_matches_the_renderer(qtbot, window, table_file, renderer, output_dir):
    texts = [a.text() for a in window.menuBar().actions()[0].menu().actions()]
    assert "Open measured BRDF (.binary)…" in texts
    state = window.open_file(table_file)  # what File > Open does for a .binary
    assert state is not None and state.model.name == "measured" and state.label == "ggx"
    assert set(window.params.controls) == {"interpolation", "gain"}
    window.params.controls["interpolation"].combo.setCurrentText("nearest")
    assert state.values["interpolation"] == "nearest"
    window.lab.settings.set("theta_i", 40.0)
    settle(qtbot, window)
    image = spheres(window)["ggx"]
    s = window.lab.settings
    expected = renderer.sphere(
        measured_model(table_file),
        {"interpolation": "nearest"},
        (40.0, s["phi_i"]),
        size=image.shape[0],
        multiply_cos=s["multiply_cos"],
    )
    assert np.allclose(image, expected, atol=1e-6)
    for name in ("polar", "lobe3d", "slice", "albedo", "sh"):
        assert window.view(name).data, name
    assert window.view("object").image[..., :3].max() > 0.05
    # The gain slider scales the table.
    control = window.params.controls["gain"]
    control.text.setText("2")
    control.text.editingFinished.emit()
    settle(qtbot, window)
    assert np.allclose(spheres(window)["ggx"][..., :3], 2 * expected[..., :3], rtol=1e-5, atol=1e-6)
    # A preset saved with the table refers to it and restores the same pixels.
    preset = window.save_preset(table_file.parent / "with_table.toml")
    text = preset.read_text()
    assert 'model = "measured"' in text and 'table = "ggx.binary"' in text
    window.lab.clear()
    window.load_preset(preset)
    settle(qtbot, window)
    assert np.allclose(spheres(window)["ggx"][..., :3], 2 * expected[..., :3], rtol=1e-5, atol=1e-6)


def test_bad_binary_shows_an_error_and_the_app_runs_on(qtbot, window, table_file, tmp_path):
    window.lab.add(load_model("phong"))
    settle(qtbot, window)
    bad = tmp_path / "broken.binary"
    bad.write_bytes(table_file.read_bytes()[:5000])
    assert window.open_measured(bad) is None
    text = window.error_text()
    assert "broken.binary" in text and "truncated" in text and not window.error_dock.isHidden()
    assert [m.model.name for m in window.lab.models] == ["phong"]
    # A valid file too large for the GPU's 3D textures is refused the same way.
    huge = write_merl(MerlTable(np.zeros((3, 4000, 1, 1))), tmp_path / "huge.binary")
    assert window.open_measured(huge) is None
    assert "huge.binary" in window.error_text() and "3D texture" in window.error_text()
    # A preset naming a missing table fails as a whole, with the file in the message.
    preset = tmp_path / "missing.toml"
    preset.write_text('[[model]]\nmodel = "measured"\ntable = "gone.binary"\n')
    with pytest.raises(Exception, match="gone.binary"):
        window.load_preset(preset)
    preset.write_text('[[model]]\nmodel = "measured"\n')
    with pytest.raises(Exception, match="table"):
        window.load_preset(preset)
    window.lab.settings.set("theta_i", 20.0)
    settle(qtbot, window)
    assert spheres(window)["phong"][..., :3].max() > 0.3


def test_sh_view_error_falls_with_order(qtbot, window, table_file, output_dir):
    window.lab.add(load_model("lambert"))
    state = window.open_file(table_file)
    window.lab.select(state)
    window.lab.settings.set("theta_i", 30.0)
    view = window.view("sh")
    view.order_box.setValue(2)
    settle(qtbot, window)
    assert view.state is state
    errors = view.order_errors
    assert len(errors) == 17
    assert errors[16] < errors[8] < errors[4] < errors[1] < errors[0]
    assert errors[16] < 0.1
    plane = view.data.plane

    def plane_error(order: int) -> float:
        return float(np.abs(view.data.reconstruction(order) - plane).mean())

    # The curves are drawn relative to the lobe's peak (a fixed y range while sliding).
    low = view.series_curve.getData()[1] / view.scale
    assert np.allclose(low, view.data.reconstruction(2))
    assert np.allclose(view.lobe_curve.getData()[1] / view.scale, plane)
    view.order_box.setValue(12)
    settle(qtbot, window)
    assert window.lab.settings["sh_order"] == 12
    assert not np.allclose(view.series_curve.getData()[1] / view.scale, low)
    assert plane_error(12) < 0.5 * plane_error(2)
    assert "169 coefficients" in view.info.text()
    view.export_png(output_dir / "app_view_sh.png")
    # A Lambertian lobe (f_r cos = const * z) is exact at order 1.
    window.lab.select(window.lab.models[0])
    settle(qtbot, window)
    assert view.state.model.name == "lambert"
    assert view.order_errors[1] < 1e-3 and view.order_errors[0] > 0.3
    # An ideal mirror has no finite lobe: the view says so and draws nothing.
    window.lab.add(load_model("mirror"))
    settle(qtbot, window)
    assert len(view.order_errors) == 0 and "mirror" in view.info.text()


def test_app_command_opens_a_binary(qtbot, table_file):
    found = {}

    def inspect() -> None:
        try:
            win = next(
                w
                for w in QApplication.topLevelWidgets()
                if isinstance(w, MainWindow) and w.isVisible()
            )
            found["models"] = [(m.model.name, m.label) for m in win.lab.models]
            win.close()
        finally:
            QApplication.instance().quit()  # never leave the test waiting in exec()

    QTimer.singleShot(500, inspect)
    assert main(["app", str(table_file)]) == 0
    assert found["models"] == [("measured", "ggx")]


def test_app_command_opens_a_fit_preset(qtbot, fit_preset, capsys):
    found = {}

    def inspect() -> None:
        try:
            win = next(
                w
                for w in QApplication.topLevelWidgets()
                if isinstance(w, MainWindow) and w.isVisible()
            )
            found["models"] = [m.label for m in win.lab.models]
            found["title"] = win.windowTitle()
            win.close()
        finally:
            QApplication.instance().quit()

    QTimer.singleShot(500, inspect)
    assert main(["app", str(fit_preset)]) == 0
    assert found["models"] == ["measured", "ggx fit"] and "ggx fit" in found["title"]
    # A damaged table stops the command with one line, before any window opens.
    broken = fit_preset.parent / "broken.binary"
    broken.write_bytes(b"\0" * 20)
    assert main(["app", str(broken)]) == 2
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0 and "broken.binary" in err


def test_render_measured_command(table_file, tmp_path, capsys):
    from PIL import Image

    out = tmp_path / "m.png"
    assert (
        main(
            [
                "render",
                "measured",
                "--table",
                str(table_file),
                "--set",
                "interpolation=nearest",
                "--size",
                "128",
                "-o",
                str(out),
            ]
        )
        == 0
    )
    pixels = np.asarray(Image.open(out).convert("RGB"), dtype=np.float64)
    assert pixels.shape == (128, 128, 3) and pixels.max() > 200 and pixels.std() > 20
    # The same picture as the renderer gives (up to 8-bit rounding).
    assert (
        main(
            [
                "render-measured",
                str(table_file),
                "--interpolation",
                "nearest",
                "--size",
                "128",
                "-o",
                str(tmp_path / "old.png"),
            ]
        )
        == 0
    )
    old = np.asarray(Image.open(tmp_path / "old.png").convert("RGB"), dtype=np.float64)
    assert np.abs(old - pixels).max() <= 1
    capsys.readouterr()
    for argv, words in (
        (["render", "measured", "-o", str(out)], "--table"),
        (["render", "ggx", "--table", str(table_file), "-o", str(out)], "measured"),
        (
            ["render", "measured", "--table", str(tmp_path / "no.binary"), "-o", str(out)],
            "no such file",
        ),
        (
            [
                "render",
                "measured",
                "--table",
                str(table_file),
                "--set",
                "interpolation=cubic",
                "-o",
                str(out),
            ],
            "cubic",
        ),
    ):
        assert main(argv) == 2
        err = capsys.readouterr().err.strip()
        assert err.count("\n") == 0 and words in err, err


def test_terms_view_tells_a_table_to_fit_a_model(qtbot, window, table_file):
    """The D, G, F view names the table and says to fit a microfacet model to it, not to
    define MICROFACET_TERMS (which a table cannot)."""
    window.open_file(table_file)
    view = floating_view(qtbot, window, "terms")
    settle(qtbot, window)
    text = view.info.text()
    assert "ggx" in text and "fit a microfacet model" in text and "MICROFACET_TERMS" not in text

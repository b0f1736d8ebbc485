"""Failures the user would not see otherwise: NaN/Inf pixels, files deleted and written
again, files that are no models, rejected parameter values and bad preset settings."""

from __future__ import annotations

import os
import sys

import numpy as np
import pytest

from lab import presets
from lab.models import MODEL_DIR, ModelError, load_model
from lab.nonfinite import sphere_report
from lab.render import direction

DIVIDES_BY_ZERO = """// @model divzero
// @param kd color 0.5 0.5 0.5 | albedo
vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {
    // Infinite where N.L <= 0.8 (a division by zero), finite inside that.
    return kd / max(dot(N, L) - 0.8, 0.0);
}
"""


def test_sphere_report_gives_share_and_place(renderer, tmp_path):
    path = tmp_path / "divzero.glsl"
    path.write_text(DIVIDES_BY_ZERO)
    image = renderer.sphere(load_model(path), {}, (0.0, 0.0), size=128)
    report = sphere_report(image, direction(0.0, 0.0))
    on = image[..., 3] > 0
    bad = on & ~np.isfinite(image[..., :3]).all(axis=-1)
    share = bad.sum() / on.sum()
    # N.L <= 0.8 with the light at the eye: outside the disc of radius 0.6, 64% of the sphere.
    assert share == pytest.approx(0.64, abs=0.02)
    assert f"{share:.1%}" in report and "in a ring around the centre" in report
    assert "Inf" in report and "N·L 0.03–0.80" in report  # pixel centres stop short of the rim
    assert sphere_report(renderer.sphere("lambert", {}, (30.0, 0.0), size=64)) == ""


def test_cli_render_warns_about_nonfinite_pixels(tmp_path, capsys):
    from lab.cli import main

    path = tmp_path / "divzero.glsl"
    path.write_text(DIVIDES_BY_ZERO)
    assert main(["render", str(path), "--light", "0,0", "-o", str(tmp_path / "x.png")]) == 0
    err = capsys.readouterr().err
    assert "warning: divzero:" in err and "Inf" in err and "division by zero" in err


def test_a_text_file_and_a_glsl_without_brdf_name_the_users_file(tmp_path):
    text = tmp_path / "lambert.txt"
    text.write_text((MODEL_DIR / "lambert.glsl").read_text())
    with pytest.raises(ModelError) as err:
        load_model(text)
    assert str(text) in str(err.value) and ".glsl" in str(err.value)
    no_brdf = tmp_path / "mine.glsl"
    no_brdf.write_text("// BRDF in a comment is no definition\nvec3 brdf(vec3 L) { return L; }\n")
    with pytest.raises(ModelError) as err:
        load_model(no_brdf)
    message = str(err.value)
    assert str(no_brdf) in message and "vec3 BRDF(" in message and "sphere.glsl" not in message


def test_preset_settings_are_checked_clamped_and_named():
    with pytest.raises(ModelError) as err:
        presets.check_settings({"theta_i": "abc"}, "p.toml")
    assert "theta_i" in str(err.value) and "p.toml" in str(err.value)
    raw = {"theta_i": 75, "exposure": 1e30, "gamma": 0}
    settings = presets.check_settings(raw, "p.toml")
    assert settings["theta_i"] == 75.0 and settings["exposure"] == 8.0 and settings["gamma"] == 1.0
    notes = presets.clamped_notes(raw, settings, "p.toml")
    assert len(notes) == 2 and all(n.startswith("p.toml: setting ") for n in notes)
    assert "exposure = 1e+30" in notes[0] and "using 8.0" in notes[0]


qt = pytest.mark.skipif(
    sys.platform.startswith("linux") and not os.environ.get("DISPLAY"),
    reason="needs a display: run under xvfb-run -a",
)


@qt
def test_app_banner_for_nonfinite_pixels(qtbot, window, tmp_path):
    from qtapp import settle

    path = tmp_path / "divzero.glsl"
    path.write_text(DIVIDES_BY_ZERO)
    window.open_file(path)
    window.lab.settings.set("theta_i", 0.0)
    settle(qtbot, window)
    banner = window.view("sphere").banner
    assert banner.isVisible() and "divzero" in banner.text() and "Inf" in banner.text()
    window.lab.clear()
    window.lab.add(load_model("lambert"))
    settle(qtbot, window)
    assert not banner.isVisible()


@qt
def test_hot_reload_recovers_after_delete_and_rewrite(qtbot, window, tmp_path):
    from qtapp import settle

    good = (MODEL_DIR / "lambert.glsl").read_text().replace("@model lambert", "@model mine")
    path = tmp_path / "mine.glsl"
    path.write_text(good)
    state = window.open_file(path)
    settle(qtbot, window)
    with qtbot.waitSignal(window.file_reloaded, timeout=10000):
        path.unlink()  # an editor deletes the file ...
    assert state.error
    qtbot.wait(300)
    brighter = good.replace("albedo * INV_PI", "2.0 * albedo * INV_PI")
    assert brighter != good
    with qtbot.waitSignal(window.file_reloaded, timeout=10000):
        path.write_text(brighter)  # ... and writes it again later
    assert state.error == "" and "2.0 * albedo" in state.model.code
    with qtbot.waitSignal(window.file_reloaded, timeout=10000):
        path.write_text(good)  # and the file is watched again
    assert "2.0 * albedo" not in state.model.code


@qt
def test_rejected_parameter_values_are_said_in_the_status_bar(qtbot, window):
    from qtapp import settle

    state = window.lab.add(load_model("phong"))
    settle(qtbot, window)
    control = window.params.controls["ke"]
    before = state.values["ke"]
    for typed, reason in (
        ("1e30", "outside"),
        ("-5", "outside"),
        ("nan", "outside"),
        ("abc", "number"),
    ):
        control.text.setText(typed)
        control.text.editingFinished.emit()
        message = window.statusBar().currentMessage()
        assert "rejected" in message and reason in message and "ke" in message, typed
        assert state.values["ke"] == before
    control.text.setText("20")
    control.text.editingFinished.emit()
    assert state.values["ke"] == 20.0 and control.text.toolTip() == ""


@qt
def test_bad_preset_values_are_clamped_and_shown(qtbot, window, tmp_path):
    from qtapp import settle

    path = tmp_path / "bad.toml"
    path.write_text(
        'title = "bad"\n[settings]\nexposure = 1e30\ngamma = 0\n[[model]]\nmodel = "lambert"\n'
    )
    window.load_preset(path)
    settle(qtbot, window)
    s = window.lab.settings
    assert s["exposure"] == 8.0 and s["gamma"] == 1.0
    assert "exposure" in window.statusBar().currentMessage()
    assert "exposure" in window.error_text() and "gamma" in window.error_text()
    assert window.view("sphere").floats[0][1][..., :3].max() > 0.05  # not black

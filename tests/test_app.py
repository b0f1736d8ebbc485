"""The desktop lab through its real window and real OpenGL (run under xvfb-run)."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("pytestqt")
if sys.platform.startswith("linux") and not os.environ.get("DISPLAY"):
    pytest.skip("needs a display: run under xvfb-run -a", allow_module_level=True)

from qtapp import settle  # noqa: E402

from lab import constants, views  # noqa: E402
from lab.app.state import shipped_presets  # noqa: E402
from lab.app.window import MainWindow  # noqa: E402
from lab.models import MODEL_DIR, load_model  # noqa: E402

LUMA = np.array(constants.LUMA)


def sphere_image(win: MainWindow, index: int = 0) -> np.ndarray:
    return win.view("sphere").floats[index][1]


def width_at_half(theta: np.ndarray, values: np.ndarray) -> float:
    """Width (degrees) of the part of the lobe above half its height over the diffuse floor."""
    floor = values.min()
    above = theta[values - floor >= 0.5 * (values.max() - floor)]
    return float(above.max() - above.min())


def test_start_add_two_models_and_open_every_view(qtbot, window, output_dir):
    window.lab.add(load_model("phong"))
    window.lab.add(load_model("cook_torrance"))
    settle(qtbot, window)
    assert [s.label for s, _ in window.view("sphere").floats] == ["phong", "cook_torrance"]
    for view in window.views:
        tab_of = views.view(view.name).tab_of  # a heavy view waits, closed, behind another
        assert view.is_shown() != bool(tab_of), view.name
    assert len(window.view("polar").data) == 2
    assert len(window.view("lobe3d").data) == 2
    assert len(window.view("slice").data) == 2
    assert len(window.view("albedo").data) == 2
    assert window.view("object").image is not None
    # Something is lit: the sphere has bright pixels, the object too.
    assert sphere_image(window)[..., :3].max() > 0.3
    assert window.view("object").image[..., 3].sum() > 1000
    window.grab().save(str(output_dir / "app_main_window.png"))
    for view in window.views:
        view.export_png(output_dir / f"app_view_{view.name}.png")
        assert (output_dir / f"app_view_{view.name}.png").stat().st_size > 1000
    # Each object mode renders (geometry, single BRDF, diffuse texture, textured parameters).
    for mode in range(4):
        window.lab.settings.set("mode", mode)
        settle(qtbot, window)
        assert window.view("object").image[..., :3].max() > 0.05
        window.view("object").export_png(output_dir / f"app_view_object_mode{mode}.png")


def test_raising_phong_exponent_narrows_the_lobe(qtbot, window):
    window.lab.add(load_model("phong"))
    window.lab.add(load_model("lambert"))
    phong = window.lab.models[0]
    window.lab.select(phong)
    window.lab.settings.set("theta_i", 30.0)
    settle(qtbot, window)
    polar = window.view("polar")
    theta, before = polar.curve(phong)
    sphere_before = sphere_image(window).copy()
    control = window.params.controls["ke"]
    control.slider.setValue(control.slider.value() + 200)  # a real slider move
    settle(qtbot, window)
    ke = phong.values["ke"]
    assert ke > 100
    theta, after = polar.curve(phong)
    assert width_at_half(theta, after) < width_at_half(theta, before)
    # The plotted data is the formula: kd/pi + ks cos^ke(angle from the mirror direction).
    kd, ks = np.array(phong.values["kd"]) @ LUMA, np.array(phong.values["ks"]) @ LUMA
    for offset in (0.0, 5.0, 10.0):
        index = int(np.argmin(np.abs(theta - (30.0 + offset))))
        expected = kd / np.pi + ks * np.cos(np.radians(offset)) ** ke
        assert after[index] == pytest.approx(expected, rel=1e-3)
    # The sphere's highlight shrinks: fewer pixels above half the peak.
    sphere_after = sphere_image(window)

    def bright(img):
        lum = img[..., :3] @ LUMA
        return int((lum > 0.5 * lum.max()).sum())

    assert bright(sphere_after) < bright(sphere_before)
    assert not np.array_equal(sphere_after, sphere_before)
    # The other model did not change.
    assert len(window.view("sphere").floats) == 2


def test_syntax_error_names_the_line_and_last_good_version_runs(qtbot, window, tmp_path):
    good = (MODEL_DIR / "phong.glsl").read_text().replace("@model phong", "@model my_phong")
    path = tmp_path / "my_phong.glsl"
    path.write_text(good)
    state = window.open_file(path)
    assert state is not None
    settle(qtbot, window)
    pixels = sphere_image(window).copy()
    lines = good.splitlines()
    broken_line = next(i for i, text in enumerate(lines, 1) if "vec3 R =" in text)
    lines[broken_line - 1] = lines[broken_line - 1].replace(";", "")  # missing semicolon
    with qtbot.waitSignal(window.file_reloaded, timeout=10000):
        path.write_text("\n".join(lines) + "\n")
    text = window.error_text()
    assert f"my_phong.glsl:{broken_line}:" in text or f"my_phong.glsl:{broken_line + 1}:" in text
    assert state.error
    settle(qtbot, window)
    assert np.array_equal(sphere_image(window), pixels)  # the last good version keeps running
    # Fixing the file clears the error and the new code runs (a brighter highlight).
    fixed = good.replace("ks * pow(RoV, ke)", "2.0 * ks * pow(RoV, ke)")
    with qtbot.waitSignal(window.file_reloaded, timeout=10000):
        path.write_text(fixed)
    settle(qtbot, window)
    assert window.error_text() == "" and state.error == ""
    assert sphere_image(window)[..., :3].max() > pixels[..., :3].max() * 1.2


def test_preset_round_trip_restores_the_same_pixels(qtbot, window, tmp_path):
    window.lab.add(load_model("ward"), {"alpha_x": 0.05, "alpha_y": 0.3})
    window.lab.add(load_model("cook_torrance"), {"distribution": "blinn", "m": 0.17})
    window.lab.models[1].set_color("#00ff00")
    window.lab.settings.set("theta_i", 42.5)
    window.lab.settings.set("phi_i", 20.0)
    window.lab.settings.set("exposure", 1.0)
    settle(qtbot, window)
    spheres = [img.copy() for _, img in window.view("sphere").floats]
    polar = [p.values.copy() for _, p in window.view("polar").data]
    path = window.save_preset(tmp_path / "state.toml")
    assert "alpha_x = 0.05" in path.read_text()
    window.lab.clear()
    window.lab.add(load_model("lambert"))
    window.lab.settings.set("theta_i", 10.0)
    settle(qtbot, window)
    window.load_preset(path)
    settle(qtbot, window)
    assert [m.model.name for m in window.lab.models] == ["ward", "cook_torrance"]
    assert window.lab.models[1].color == "#00ff00"
    restored = [img for _, img in window.view("sphere").floats]
    assert len(restored) == 2
    for a, b in zip(spheres, restored, strict=True):
        assert np.array_equal(a, b)
    for a, (_, p) in zip(polar, window.view("polar").data, strict=True):
        assert np.array_equal(a, p.values)


def test_shipped_presets_load_and_step(qtbot, window):
    presets = shipped_presets()
    assert len(presets) >= 7
    for _ in presets:
        window.step_preset(1)
        settle(qtbot, window)
        assert window.lab.models, window.windowTitle()
        assert window.view("sphere").floats or window.docks["sphere"].isHidden()


def test_open_brdf_explorer_file(qtbot, window, tmp_path):
    from test_brdf_explorer import BLINN

    path = tmp_path / "blinn.brdf"
    path.write_text(BLINN)
    state = window.open_file(path)
    assert state is not None and set(state.model.params) == {"n", "normalized", "tint"}
    assert set(window.params.controls) == {"n", "normalized", "tint"}
    settle(qtbot, window)
    image = sphere_image(window)
    # The tint (1, 0.5, 0.25) shows in the highlight's colour.
    r, g, b = image[..., :3].reshape(-1, 3)[np.argmax(image[..., 0])]
    assert g == pytest.approx(r / 2, rel=1e-3) and b == pytest.approx(r / 4, rel=1e-3)
    # A broken .brdf never crashes: the error names the file's own line.
    with qtbot.waitSignal(window.file_reloaded, timeout=10000):
        path.write_text(BLINN.replace("float val =", "float val = = "))
    assert "blinn.brdf:17:" in window.error_text()


def test_exports(qtbot, window, tmp_path):
    window.lab.add(load_model("phong"))
    settle(qtbot, window)
    window.view("polar").export_csv(tmp_path / "polar.csv")
    rows = (tmp_path / "polar.csv").read_text().splitlines()
    assert rows[0].startswith("theta_o_deg,phong:fr_r")
    assert len(rows) == 1 + 181


def test_no_display_renders_the_gallery(tmp_path):
    env = {k: v for k, v in os.environ.items() if k not in ("DISPLAY", "WAYLAND_DISPLAY")}
    env.pop("QT_QPA_PLATFORM", None)
    out = tmp_path / "gallery"
    result = subprocess.run(
        [sys.executable, "-m", "lab.cli", "app", "--gallery-dir", str(out)],
        env=env,
        capture_output=True,
        text=True,
        timeout=120,
        cwd=Path(__file__).parent.parent,
    )
    assert result.returncode == 0, result.stderr
    assert "no display" in result.stdout
    assert str(out) in result.stdout
    assert (out / "index.html").exists()
    assert "Traceback" not in result.stderr


def test_slice_axes_are_square_and_span_0_to_90(qtbot, window, output_dir):
    for name in ("phong", "cook_torrance", "ward"):
        window.lab.add(load_model(name))
    settle(qtbot, window)
    view = window.view("slice")
    axes = view.axes()
    assert len(axes) == 3
    sides = set()
    for theta_h, theta_d, rect in axes:
        assert theta_h == (0.0, 90.0) and theta_d == (0.0, 90.0)
        assert rect.width() == rect.height() >= 48  # equal aspect, readable
        assert view.canvas.rect().contains(rect)
        sides.add(rect.width())
    assert len(sides) == 1  # every model's slice at the same scale
    # The images are drawn at the plots' size (no stretching) once refined.
    for (_, image), (_, _, rect) in zip(view.data, axes, strict=True):
        assert image.shape[:2] == (rect.height(), rect.width())
    view.export_png(output_dir / "app_view_slice_three.png")


def test_views_recompute_only_what_changed(qtbot, window, app_renderer, monkeypatch):
    window.lab.add(load_model("phong"))
    window.lab.add(load_model("lambert"))
    settle(qtbot, window)
    calls: list[tuple[str, str]] = []
    for method in ("sphere", "polar", "lobe_peak", "slice", "albedo", "object", "probe"):
        original = getattr(app_renderer, method)

        def counted(model, *args, _method=method, _original=original, **kwargs):
            calls.append((_method, model.name))
            return _original(model, *args, **kwargs)

        monkeypatch.setattr(app_renderer, method, counted)
    draws = {view.name: view.draws for view in window.views}
    # The light: the slice and the albedo do not depend on theta_i; nothing redraws them.
    window.theta_slider.slider.setValue(window.theta_slider.slider.value() + 10)
    settle(qtbot, window)
    made = {method for method, _ in calls}
    assert "slice" not in made and "albedo" not in made
    assert {"sphere", "polar", "lobe_peak", "object"} <= made
    assert window.view("slice").draws == draws["slice"]
    assert window.view("albedo").draws == draws["albedo"]
    assert window.view("sphere").draws > draws["sphere"]
    # One model's parameter: only that model is computed again, in every view.
    calls.clear()
    phong = window.lab.models[0]
    window.lab.select(phong)
    control = window.params.controls["ke"]
    control.slider.setValue(control.slider.value() + 100)
    settle(qtbot, window)
    assert calls and {name for _, name in calls} == {"phong"}
    assert {"sphere", "polar", "lobe_peak", "slice", "albedo"} <= {m for m, _ in calls}
    # Selecting another model redraws the views that show the selected one.
    calls.clear()
    with qtbot.waitSignal(window.frame_done, timeout=5000):
        window.lab.select(window.lab.models[1])
    assert ("object", "lambert") in calls
    settle(qtbot, window)
    # Nothing changed: a frame costs no rendering at all.
    calls.clear()
    draws = {view.name: view.draws for view in window.views}
    settle(qtbot, window)
    assert calls == [] and draws == {view.name: view.draws for view in window.views}


def test_parameters_in_view_without_scrolling(qtbot, window):
    window.lab.add(load_model("phong"))
    window.lab.add(load_model("cook_torrance"))
    settle(qtbot, window)
    assert window.lab.selected.model.name == "cook_torrance"
    controls = window.params.controls
    assert len(controls) >= 7
    for name, control in controls.items():
        shown = control.visibleRegion().boundingRect()
        assert shown.height() == control.height() and shown.width() == control.width(), name
    # The formula folds out on demand and is the title's tooltip.
    assert window.params.formula.isHidden() and "f_r" in window.params.title.toolTip()
    window.params.formula_button.setChecked(True)
    assert not window.params.formula.isHidden() and "f_r" in window.params.formula.text()


def test_presenter_mode_enlarges_text_and_gives_the_desk_back(qtbot, window, output_dir):
    window.lab.add(load_model("phong"))
    window.lab.add(load_model("cook_torrance"))
    settle(qtbot, window)
    size = window.params.title.font().pointSizeF()
    tick = window.view("albedo").plot.getAxis("bottom").style["tickFont"]
    window.toggle_presenter()
    try:
        qtbot.wait(200)
        settle(qtbot, window)
        assert window.params.title.font().pointSizeF() > 1.4 * size
        bigger = window.view("albedo").plot.getAxis("bottom").style["tickFont"]
        assert bigger is not None and (tick is None or bigger.pointSizeF() > tick.pointSizeF())
        # The focus layout's views, large; the others closed until the desk comes back.
        assert window.layout_name == "sphere_polar"
        shown = {view.name for view in window.views if view.is_shown()}
        assert shown == {"sphere", "polar"}
        window.grab().save(str(output_dir / "app_presenter.png"))
    finally:
        window.toggle_presenter()
    qtbot.wait(100)
    settle(qtbot, window)
    assert window.params.title.font().pointSizeF() == pytest.approx(size)
    for view in window.views:  # the desk again: shown, or a tab behind a shown view
        tabs = window.tabifiedDockWidgets(window.docks[view.name])
        closed = bool(views.view(view.name).tab_of)  # opened from the View menu
        assert view.is_shown() or any(t.widget().is_shown() for t in tabs) or closed, view.name
    for _, _, rect in window.view("slice").axes():
        assert rect.width() == rect.height() >= 40


def test_tonemap_matches_the_formula():
    from lab.app.views.base import BACKGROUND, tonemap

    rng = np.random.default_rng(1)
    image = rng.uniform(0.0, 2.0, (5, 7, 4)).astype(np.float32)
    image[..., 3] = rng.choice([0.0, 0.5, 1.0], (5, 7))
    image[0, 0, :3] = (np.nan, np.inf, -np.inf)
    qimage = tonemap(image, -0.5, 2.2)
    bits = qimage.constBits().asstring(qimage.sizeInBytes())
    got = np.frombuffer(bits, np.uint8).reshape(5, -1, 4)[:, :7, 2::-1]  # BGRA -> RGB
    rgb = np.clip(np.nan_to_num(image[..., :3].astype(np.float64), nan=0.0) * 2**-0.5, 0, 1)
    rgb = rgb ** (1 / 2.2)
    alpha = image[..., 3:4]
    expected = (rgb * alpha + np.array(BACKGROUND) / 255 * (1 - alpha)) * 255
    assert np.abs(got - expected).max() <= 1.0  # NaN, +inf and -inf pixels included


def test_presets_reset_the_settings_they_do_not_name(qtbot, window):
    beckmann, off_specular = (shipped_presets()[i] for i in (2, 3))
    assert "polar_cos" not in beckmann.read_text()
    assert "polar_cos = true" in off_specular.read_text()

    def snapshot():
        settle(qtbot, window)
        spheres = [img.copy() for _, img in window.view("sphere").floats]
        polar = [p.values.copy() for _, p in window.view("polar").data]
        return dict(window.lab.settings.values), spheres, polar

    window.load_preset(beckmann)
    first = snapshot()
    window.load_preset(off_specular)
    assert window.lab.settings["polar_cos"]
    window.load_preset(beckmann)
    again = snapshot()
    assert again[0] == first[0] and not again[0]["polar_cos"]
    for a, b in zip(first[1] + first[2], again[1] + again[2], strict=True):
        assert np.array_equal(a, b)


def test_export_of_a_hidden_polar_view_is_up_to_date(qtbot, window, app_renderer, tmp_path):
    state = window.lab.add(load_model("phong"), {"ke": 10.0})
    settle(qtbot, window)
    window.docks["polar"].hide()
    state.set_value("ke", 200.0)
    window.lab.settings.set("theta_i", 50.0)
    settle(qtbot, window)
    window.view("polar").export_csv(tmp_path / "polar.csv")
    table = np.loadtxt(tmp_path / "polar.csv", delimiter=",", skiprows=1)
    expected = app_renderer.polar(state.model, state.values, 50.0, 0.0)
    assert np.allclose(table[:, 1:4], expected.values, rtol=1e-5, atol=1e-6)


def test_error_for_a_file_that_never_compiled(qtbot, window, tmp_path):
    path = tmp_path / "broken.glsl"
    path.write_text((MODEL_DIR / "phong.glsl").read_text().replace("vec3 R =", "vec3 R = = "))
    assert window.open_file(path) is None
    text = window.error_text()
    assert "broken.glsl" in text and "was not added" in text
    assert "last good version" not in text
    window.step_preset(to=0)
    assert window.error_dock.isHidden()


def test_polar_view_scale_legend_and_light_side(qtbot, window, output_dir):
    """The shared scale (grazing values left out, clipped ones marked and named), ring labels,
    a legend naming the unit and each model, and the light on the right as on the spheres."""
    window.lab.add(load_model("ward"))
    window.lab.settings.set("theta_i", 75.0)
    settle(qtbot, window)
    view = window.view("polar")
    scale = view.scale
    assert scale is not None and scale.clipped and len(view.clip_marks.xData) > 0
    legend = view.legend.text()
    assert "sr⁻¹" in legend and "ward" in legend and "clipped" in legend
    labels = [text.toPlainText() for _, text in view.rings if text.toPlainText()]
    assert labels == [scale.label(t) for t in scale.ticks]
    (_, incident), (_, mirror) = view.marks[1], view.marks[2]
    assert incident.pos().x() > 0 > mirror.pos().x()
    # The lobe lies on the mirror side (left), its clipped tail at the rim there.
    state, polar = view.data[0]
    x = view.curves[0][0].xData
    assert x[np.argmax(np.hypot(x, view.curves[0][0].yData))] < 0
    assert np.all(np.asarray(view.clip_marks.xData) < 0)
    view.export_png(output_dir / "app_polar_ward_75.png")

"""The desktop lab's IBL view: progressive, two strategies side by side, the furnace's
energy-gain flag, the convergence plot; screenshots in tests/output."""

from __future__ import annotations

import numpy as np
import pytest
from qtapp import floating_view

from lab.ibl import environments
from lab.models import load_model


def ibl_view(qtbot, window):
    return floating_view(qtbot, window, "ibl", (900, 420))


def wait_samples(qtbot, view, count):
    qtbot.waitUntil(lambda: bool(view.runs) and view.runs[0].samples >= count, timeout=60000)


def test_ibl_view_converges_side_by_side(qtbot, window, output_dir):
    window.lab.add(load_model("ggx"), {"alpha": 0.2})
    s = window.lab.settings
    s.set("ibl_samples", 32)
    s.set("ibl_strategy", 0)  # uniform
    s.set("ibl_compare", 6)  # vs mis_power
    view = ibl_view(qtbot, window)
    window.settle()
    wait_samples(qtbot, view, 32)
    assert [r.strategy for r in view.runs] == ["uniform", "mis_power"]
    assert view.runs[0].samples == view.runs[1].samples  # equal samples
    assert "32 samples per pixel each" in view.status.text()
    assert "stopped at the cap of 32 samples/pixel" in view.status.text()
    # The estimated error falls, and MIS is far below uniform at equal samples.
    uniform, mis = (np.array(r.history) for r in view.runs)
    assert uniform[-1, 1] < uniform[0, 1]
    assert mis[-1, 1] < 0.5 * uniform[-1, 1]
    view.grab().save(str(output_dir / "app_view_ibl_side_by_side.png"))


def test_ibl_view_flags_energy_gain_in_the_furnace(qtbot, window, output_dir):
    window.lab.add(load_model("phong"), {"kd": (0.5,) * 3, "ks": (1.0,) * 3, "ke": 1.0})
    s = window.lab.settings
    s.set("ibl_env", 1)  # furnace
    s.set("ibl_samples", 8)
    view = ibl_view(qtbot, window)
    window.settle()
    wait_samples(qtbot, view, 8)
    assert "ENERGY GAIN" in view.status.text()
    view.grab().save(str(output_dir / "app_view_ibl_furnace_phong.png"))
    window.lab.add(load_model("lambert"))
    window.settle()
    qtbot.waitUntil(lambda: "furnace: at most 0.8" in view.status.text(), timeout=60000)


def test_ibl_view_names_the_fallback_and_opens_files(qtbot, window, tmp_path):
    window.lab.add(load_model("oren_nayar"))
    s = window.lab.settings
    s.set("ibl_strategy", 3)  # brdf
    s.set("ibl_samples", 4)
    view = ibl_view(qtbot, window)
    window.settle()
    wait_samples(qtbot, view, 4)
    assert "oren_nayar has no BRDF sampler" in view.status.text()
    path = tmp_path / "room.hdr"
    environments.write_hdr(path, environments.procedural("grey_room", (64, 32)))
    view.load_file(path)
    window.settle()
    qtbot.waitUntil(lambda: view.runs and view.runs[0].halves[0].environment.name == str(path))
    bad = tmp_path / "bad.hdr"
    bad.write_bytes(b"nope")
    view.load_file(bad)
    assert "cannot use that file" in view.status.text()


def test_ibl_view_lights_the_object(qtbot, window, output_dir):
    """'lit: torus' puts the object view's shape (with its yaw and pitch) under the map."""
    window.lab.add(load_model("ggx"), {"alpha": 0.2})
    s = window.lab.settings
    s.set("ibl_samples", 8)
    s.set("ibl_target", 1)  # torus
    s.set("yaw", 0.9)
    view = ibl_view(qtbot, window)
    window.settle()
    wait_samples(qtbot, view, 8)
    half = view.runs[0].halves[0]
    assert (half.shape, half.view, half.yaw) == ("torus", "ibl_object", 0.9)
    image = view.runs[0].image()
    covered = (image[..., 3] > 0.5).mean()
    assert 0.1 < covered < 0.6  # a torus, not the sphere (0.785)
    view.grab().save(str(output_dir / "app_view_ibl_torus.png"))


def test_ibl_view_sample_target_and_error_ticks(qtbot, window):
    """The target menu sets how many samples per pixel the view runs to; the error plot's
    ticks are percentages and its samples axis whole counts (no '6·10²' for a ratio)."""
    from layout_checks import tick_texts

    window.lab.add(load_model("ggx"), {"alpha": 0.3})
    view = ibl_view(qtbot, window)
    view.samples.setCurrentIndex(view.samples.findData(16))
    assert window.lab.settings["ibl_samples"] == 16
    window.settle()
    qtbot.waitUntil(lambda: view.runs and view.runs[0].samples >= 16, timeout=60000)
    qtbot.wait(200)
    assert view.runs[0].samples == 16  # it stops at the target
    window.lab.settings.set("ibl_samples", 48)  # a preset's own value joins the menu
    assert view.samples.currentData() == 48
    left, bottom = tick_texts(view, "left"), tick_texts(view, "bottom")
    assert left and all(t.endswith("%") for t in left), left
    assert bottom and all(t.isdigit() for t in bottom), bottom


def test_ibl_view_refines_past_256_until_the_error_target(qtbot, window):
    """With no sample cap, the view refines until its estimated error reaches the chosen
    target (2%) and says so; a time budget stops a run that cannot get there."""
    window.lab.add(load_model("ggx"), {"alpha": 0.5})
    s = window.lab.settings
    s.set("ibl_env", 1)  # furnace
    s.set("ibl_stop_error", 0)  # 2%
    view = ibl_view(qtbot, window)
    window.settle()
    qtbot.waitUntil(lambda: view.stopped is not None, timeout=120000)
    assert view.stopped.startswith("done: error") and "≤ target 2.00%" in view.status.text()
    assert view.runs[0].error <= 0.02
    s.set("ibl_strategy", 0)  # uniform: far from 0.25% in a tenth of a second
    s.set("ibl_stop_error", 3)
    s.set("ibl_stop_time", 0)  # 10 s
    window.settle()
    view.elapsed = 9.95  # most of the budget already spent
    qtbot.waitUntil(lambda: view.stopped is not None, timeout=60000)
    assert view.stopped.startswith("time budget of 10 s spent")
    assert "> target 0.25%" in view.status.text()


@pytest.mark.parametrize("room", [True, False])
def test_the_ibl_view_waits_as_a_tab_behind_the_spheres(qtbot, app_renderer, monkeypatch, room):
    """Where the screen has room for a tab bar, the IBL view starts open as a tab behind the
    lit spheres: its tab names it, it runs no pass while behind, and brought to the front it
    refines and its row grows to its share; on a screen without room it starts closed."""
    from PyQt6.QtWidgets import QTabBar

    from lab.app import layouts
    from lab.app.window import MainWindow

    monkeypatch.setattr(layouts, "ROOM_FOR_TABS", 0 if room else 100_000)
    window = MainWindow(app_renderer)
    qtbot.addWidget(window)
    window.resize(1800, 1000)  # room for the IBL view's share of the height
    window.show()
    qtbot.waitExposed(window)
    window.settle()
    dock, view = window.docks["ibl"], window.view("ibl")
    assert dock.isHidden() != room
    assert dock.toggleViewAction().isChecked() == room
    if not room:
        return
    assert window.docks["sphere"] in window.tabifiedDockWidgets(dock)
    assert window.view("sphere").is_shown() and not view.is_shown()
    bars = [bar for bar in window.findChildren(QTabBar) if bar.isVisible()]
    titles = [bar.tabText(i) for bar in bars for i in range(bar.count())]
    assert "Image-based lighting" in titles or "IBL" in titles, titles
    window.lab.add(load_model("ggx"), {"alpha": 0.2})
    window.settle()
    qtbot.wait(300)
    assert not view.runs or view.runs[0].samples == 0  # no pass while behind
    row = window.docks["sphere"].height()
    dock.raise_()
    qtbot.waitUntil(view.is_shown)
    wait_samples(qtbot, view, 4)
    qtbot.waitUntil(lambda: dock.height() > row + 20)  # the IBL view's share of the height

"""Layouts on a projector's screen (issue 26): at 1024x768, 1280x720 and 1280x800 every
preset fits the screen on the desk (the controls keeping one width) and in presenter mode,
whose focus layouts show their plots at least MIN_PLOT large, with no text cut short or
lying on another and every text inside a plot at least PLOT_TEXT_PX tall.

Each screen is its own X server: `test_projector_screen` runs `test_layouts_fit_this_screen`
in a child pytest under `xvfb-run -s "-screen 0 WxHx24"` (a window manager is not needed:
the lab sizes a presenting window to its screen itself). The screenshots stay in
tests/output/layouts/WxH/.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

pytest.importorskip("pytestqt")
pytest.importorskip("pyqtgraph")
if sys.platform.startswith("linux") and not os.environ.get("DISPLAY"):
    pytest.skip("needs a display: run under xvfb-run -a", allow_module_level=True)

from layout_checks import (  # noqa: E402
    axis_overlaps,
    cut_texts,
    off_screen,
    plot_sizes,
    small_texts,
    tick_texts,
)
from qtapp import settle  # noqa: E402

from lab.app.state import shipped_presets  # noqa: E402
from lab.app.views.base import PLOT_TEXT_PX  # noqa: E402
from lab.models import load_model  # noqa: E402
from lab.presets import LAYOUTS, read_preset  # noqa: E402

SCREENS = [(1024, 768), (1280, 720), (1280, 800)]
# Pixels each plot gets at least in a focus layout on the smallest screen (1024x768).
MIN_PLOT = {
    "polar": 250,  # the disc's diameter
    "sphere": 140,
    "lobe3d": 250,
    "object": 250,
    "slice": 200,
    "ibl": 250,
    "ibl plot": 150,
}


def problems(window) -> list[str]:
    """What is wrong with a presenting window as it stands."""
    found = [off_screen(window)] if off_screen(window) else []
    found += cut_texts(window)
    found += small_texts(window, PLOT_TEXT_PX)
    found += axis_overlaps(window)
    sizes = plot_sizes(window)
    found += [f"{k} is {v} px < {MIN_PLOT[k]}" for k, v in sizes.items() if v < MIN_PLOT[k]]
    layout = LAYOUTS[window.layout_name]
    missing = [n for n in layout.views if n not in sizes and not (n == "sphere" and "ibl" in sizes)]
    found += [f"{n} is not shown" for n in missing]
    return found


def test_layouts_fit_this_screen(qtbot, window, output_dir):
    room = window.screen().availableGeometry()
    out = output_dir / "layouts" / f"{room.width()}x{room.height()}"
    out.mkdir(parents=True, exist_ok=True)
    window.lab.add(load_model("phong"))
    window.lab.add(load_model("cook_torrance"))
    qtbot.wait(100)
    settle(qtbot, window)
    failures = {}
    # Presenter mode before any preset: the default focus layout, spheres and polar plot.
    window.toggle_presenter()
    qtbot.wait(150)
    settle(qtbot, window)
    assert window.layout_name == "sphere_polar"
    window.grab().save(str(out / "presenter_default.png"))
    failures["default"] = problems(window)
    window.toggle_presenter()
    qtbot.wait(100)
    widths = {}
    for preset in shipped_presets():  # the desk
        window.load_preset(preset)
        qtbot.wait(80)
        settle(qtbot, window)
        window.grab().save(str(out / f"desk_{preset.stem[:2]}.png"))
        assert off_screen(window) == "", preset.stem
        widths[preset.stem] = window.controls_dock.width()
    assert len(set(widths.values())) == 1, f"the controls change width: {widths}"
    assert widths[preset.stem] <= 0.34 * window.width()
    for name in ("ibl", "terms", "object"):  # views opened and closed from the View menu
        window.docks[name].toggleViewAction().trigger()
        qtbot.wait(80)
        assert off_screen(window) == "", f"{name} opened on the desk"
        window.docks[name].toggleViewAction().trigger()
        qtbot.wait(30)
    window.toggle_presenter()
    try:
        for case in [*shipped_presets(), "ibl"]:
            if isinstance(case, Path):
                window.load_preset(case)
            if case == "ibl":  # opened from the View menu while presenting
                window.docks["lobe3d"].toggleViewAction().trigger()  # a tab: fits too
                qtbot.wait(80)
                assert off_screen(window) == "" and window.layout_name == "sphere_object"
                window.docks["ibl"].toggleViewAction().trigger()
            qtbot.wait(150)
            settle(qtbot, window)
            name = case.stem[:2] if isinstance(case, Path) else case
            if case == "ibl":
                view = window.view("ibl")
                qtbot.waitUntil(
                    lambda v=view: bool(v.runs) and len(v.runs[0].history) >= 8, timeout=60000
                )
                qtbot.wait(50)
                ticks = tick_texts(view, "left")
                assert ticks and all(t.endswith("%") for t in ticks), ticks
                assert view.samples.isVisible() and view.samples.isEnabled()
            if isinstance(case, Path):
                assert window.layout_name == read_preset(case).get("layout", "sphere_polar")
            window.grab().save(str(out / f"presenter_{name}.png"))
            failures[name] = problems(window)
    finally:
        window.toggle_presenter()
    assert {k: v for k, v in failures.items() if v} == {}
    qtbot.wait(100)
    assert window.layout_name == "desk" and not window.presenting
    assert off_screen(window) == ""


@pytest.mark.parametrize("size", SCREENS, ids=[f"{w}x{h}" for w, h in SCREENS])
def test_projector_screen(size):
    runner = shutil.which("xvfb-run")
    if runner is None:
        pytest.skip("xvfb-run is not installed (apt package xvfb)")
    width, height = size
    command = [
        runner,
        "-a",
        "-s",
        f"-screen 0 {width}x{height}x24",
        sys.executable,
        "-m",
        "pytest",
        f"{__file__}::test_layouts_fit_this_screen",
        "-x",
        "-q",
        "-p",
        "no:cacheprovider",
    ]
    root = Path(__file__).resolve().parent.parent
    env = {**os.environ, "PYTHONPATH": str(root)}
    done = subprocess.run(
        command, cwd=root, env=env, capture_output=True, text=True, timeout=900, check=False
    )
    assert done.returncode == 0, (done.stdout + done.stderr)[-6000:]


def test_a_preset_names_a_known_layout(tmp_path):
    from lab.models import ModelError

    path = tmp_path / "bad.toml"
    path.write_text('layout = "sideways"\n[[model]]\nmodel = "phong"\n', encoding="utf-8")
    with pytest.raises(ModelError, match="unknown layout 'sideways'; write one of 'desk'"):
        read_preset(path)
    assert all(read_preset(p).get("layout") in LAYOUTS for p in shipped_presets())

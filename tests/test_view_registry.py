"""The registry of views: every front end reads it, and a new view is its module alone.

`extra_views` (in tests/) adds a view the lab's own code has never heard of; once its
package is registered it shows up in the CLI, the app's docks, presets and the page.
"""

from __future__ import annotations

import os

import numpy as np
import pytest
from PIL import Image

from lab import views
from lab.cli import build_parser, main
from lab.models import ModelError
from lab.presets import check_settings
from lab.web.site import manifest


@pytest.fixture
def extra_view():
    views.add_package("extra_views")
    yield views.view("retro")
    views._PACKAGES.remove("extra_views")
    views._cache = None


def test_the_lab_views_are_registered():
    names = [v.name for v in views.all_views()]
    assert names == ["sphere", "polar", "lobe3d", "sh", "terms", "slice", "albedo", "object", "ibl"]
    assert views.plot_views() == ["sphere", "polar", "lobe3d", "terms", "slice", "albedo", "ibl"]
    choices = next(
        a.choices
        for a in build_parser()._subparsers._group_actions[0].choices["render"]._actions
        if a.dest == "view"
    )
    assert list(choices) == views.plot_views()


def test_settings_are_checked_against_their_ranges():
    assert check_settings({"gamma": 0.0, "theta_i": 120}, "p.toml") == {
        "gamma": 1.0,
        "theta_i": 90.0,
    }
    for bad, words in [
        ({"theta_i": "abc"}, "setting theta_i = 'abc': expected a number"),
        ({"exposure": float("inf")}, "finite"),
        ({"multiply_cos": 1}, "true or false"),
        ({"shape": 7}, "choose one of 0 (torus)"),
        ({"lights": 2.5}, "whole number"),
        ({"nonsense": 1}, "unknown setting(s) nonsense"),
    ]:
        with pytest.raises(ModelError, match=words.replace("(", r"\(").replace(")", r"\)")):
            check_settings(bad, "p.toml")


def test_a_new_view_appears_in_cli_presets_and_page(extra_view, tmp_path):
    assert "retro" in views.plot_views()
    assert check_settings({"retro_gain": 10.0}, "p.toml") == {"retro_gain": 4.0}
    assert any(v["name"] == "retro" for v in manifest()["views"])
    lambert, phong = tmp_path / "lambert.png", tmp_path / "phong.png"
    assert main(["render", "lambert", "--view", "retro", "-o", str(lambert)]) == 0
    assert main(["render", "phong", "--view", "retro", "--set", "kd=0", "-o", str(phong)]) == 0
    with Image.open(lambert) as flat, Image.open(phong) as peaked:
        flat_tops = (np.asarray(flat) > 0).sum(axis=0)
        peaked_tops = (np.asarray(peaked) > 0).sum(axis=0)
    assert (flat_tops == 100).all()  # Lambert: the same f_r at every angle
    assert peaked_tops[0] == 100 and peaked_tops[60] < 10  # Phong: R = V only at normal incidence


@pytest.mark.skipif(not os.environ.get("DISPLAY"), reason="needs a display (xvfb-run)")
def test_a_new_view_gets_a_dock(extra_view, qtbot, app_renderer):
    from lab.app.window import MainWindow
    from lab.models import load_model

    win = MainWindow(app_renderer)
    qtbot.addWidget(win)
    win.lab.add(load_model("lambert"))
    assert "retro" in win.docks
    retro = win.docks["retro"].widget()
    retro.redraw()
    assert retro.label.text() == f"peak {0.8 / np.pi:.4g} 1/sr"
    # Laid out from its spec like the others: a row of its own under the bottom row, and an
    # entry in the File menu's PNG export.
    win.resize(1280, 800)
    win.show()
    qtbot.waitExposed(win)
    win.fit_docks()
    qtbot.wait(50)
    dock, above = win.docks["retro"], win.docks["slice"]
    assert dock.isVisible() and dock.height() > 60 and dock.width() > 600
    assert dock.geometry().top() >= above.geometry().bottom()
    file_menu = win.menuBar().actions()[0].menu()
    export = next(a.menu() for a in file_menu.actions() if a.text() == "Export view as PNG")
    assert "Retroreflection" in [a.text() for a in export.actions()]


def test_each_view_redraws_on_the_settings_it_names(window):
    """A widget's settings_used are settings of the lab, and each of them moves its inputs():
    a change of one redraws the view (and a misspelt name fails here, not silently)."""
    settings = window.lab.settings.values  # set directly: no signal, no redraw
    named = 0
    for view in window.views:
        for key in view.settings_used:
            assert key in settings, f"{view.name} names an unknown setting {key}"
            before, old = view.inputs(), settings[key]
            settings[key] = (not old) if isinstance(old, bool) else old + 1
            try:
                assert view.inputs() != before, f"{view.name} does not redraw when {key} changes"
            finally:
                settings[key] = old
            named += 1
    assert named >= 20  # every view with settings named them

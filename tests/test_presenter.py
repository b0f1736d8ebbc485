"""Presenter mode's polar plot in large fonts. (Every preset on projector screens of
1024x768, 1280x720 and 1280x800 is measured in test_focus_layouts.py.)"""

from __future__ import annotations

import os
import sys

import pytest

pytest.importorskip("pytestqt")
pg = pytest.importorskip("pyqtgraph")
if sys.platform.startswith("linux") and not os.environ.get("DISPLAY"):
    pytest.skip("needs a display: run under xvfb-run -a", allow_module_level=True)

from layout_checks import cut_plot_texts  # noqa: E402
from qtapp import settle  # noqa: E402

from lab.models import load_model  # noqa: E402


def test_polar_direction_labels_become_letters_where_words_collide(qtbot, window):
    """In a small polar plot with the presenter's large text, 'normal', 'incident' and
    'mirror' would run into each other: N, L and R show instead, the legend says what they
    are; in a large plot the words show."""
    from qtapp import floating_view

    window.lab.add(load_model("phong"))
    window.toggle_presenter()
    try:
        for size, letters in (((300, 260), True), ((1000, 700), False)):
            view = floating_view(qtbot, window, "polar", size)
            qtbot.wait(60)
            settle(qtbot, window)
            words = [text.toPlainText() for _, text in view.marks]
            assert words == (["N", "L", "R"] if letters else ["normal", "incident", "mirror"])
            assert ("N normal" in view.legend.text()) == letters
            assert cut_plot_texts(window) == [], size
    finally:
        window.toggle_presenter()

"""Helpers for tests that drive the desktop lab's window (its fixtures are in conftest.py)."""

from __future__ import annotations


def settle(qtbot, win) -> None:
    """Wait for the pending frame, then run the refinements too."""
    qtbot.wait(1)
    win.request()
    with qtbot.waitSignal(win.frame_done, timeout=5000):
        pass
    win.settle()
    qtbot.wait(1)


def floating_view(qtbot, win, name: str, size: tuple[int, int] = (900, 320)):
    """The widget of view `name`, its dock floated at `size` and shown (a view behind a tab
    does not draw)."""
    dock = win.docks[name]
    dock.setFloating(True)
    dock.resize(*size)
    dock.show()
    qtbot.waitExposed(dock)
    return dock.widget()

"""Shared fixtures: one offscreen GL context for the whole session, checked for GL errors."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

OUTPUT = Path(__file__).parent / "output"

# `python3 -m lab test` (and so CI) sets this: there every tool is installed, and a test
# skipped for a missing display, browser or node would hide a broken set-up.
STRICT = os.environ.get("BRDF_LAB_STRICT") == "1"


def _no_skips(report) -> None:
    if STRICT and report.skipped and not hasattr(report, "wasxfail"):
        report.outcome = "failed"
        report.longrepr = (
            f"skipped, but BRDF_LAB_STRICT=1 requires every test to run: {report.longrepr}"
        )


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_makereport(item, call):
    outcome = yield
    _no_skips(outcome.get_result())


@pytest.hookimpl(hookwrapper=True)
def pytest_make_collect_report(collector):
    outcome = yield
    _no_skips(outcome.get_result())


@pytest.fixture(scope="session")
def ctx():
    from lab.gl import get_context

    return get_context()


@pytest.fixture(scope="session")
def renderer(ctx):
    from lab.render import Renderer

    return Renderer(ctx)


@pytest.fixture(scope="session")
def app_renderer(ctx):
    """The desktop lab's renderer (the core one plus the app's own views)."""
    from lab.app.renderer import AppRenderer

    return AppRenderer(ctx)


@pytest.fixture
def window(qtbot, app_renderer):
    """The lab's main window at a laptop size, shown and exposed."""
    from lab.app.window import MainWindow

    win = MainWindow(app_renderer)
    qtbot.addWidget(win)
    win.resize(1280, 800)
    win.show()
    qtbot.waitExposed(win)
    return win


@pytest.fixture
def gl_clean(ctx):
    """The shared context, for tests that use it directly (every test is checked anyway)."""
    return ctx


@pytest.fixture(autouse=True)
def no_gl_errors_left_behind():
    """Fail any test that leaves an OpenGL error in the process's offscreen context."""
    from lab import gl

    def error() -> str:
        return gl._offscreen.error if gl._offscreen is not None else "GL_NO_ERROR"

    assert error() == "GL_NO_ERROR", "an OpenGL error was pending before this test"
    yield
    assert error() == "GL_NO_ERROR", "this test left an OpenGL error behind"


@pytest.fixture(scope="session")
def output_dir() -> Path:
    OUTPUT.mkdir(exist_ok=True)
    return OUTPUT


@pytest.fixture(autouse=True)
def qt_event_loop_stays_usable(request):
    """After a Qt test, run one short event loop.

    A test that runs `brdf-lab app` closes its last window, which posts a quit for the
    *next* event loop; left pending, it would end every later wait at once. One exec()
    that quits by itself consumes it (and any deferred deletions).
    """
    yield
    if "qtbot" in request.fixturenames:
        from PyQt6.QtCore import QTimer
        from PyQt6.QtWidgets import QApplication

        app = QApplication.instance()
        if app is not None:
            QTimer.singleShot(0, app.quit)
            app.exec()

"""The app's first frame does not wait for modules it does not need yet."""

from __future__ import annotations

import os
import subprocess
import sys

import pytest

from lab.app.bench import HEAVY_MODULES

# A real window with three models and every default view; after its first frame the
# script prints the heavy modules that were imported on the way.
SCRIPT = """
import sys
from PyQt6.QtWidgets import QApplication
from lab.app.bench import HEAVY_MODULES
from lab.app.state import load_any
from lab.app.window import MainWindow, close_for_exit

app = QApplication([])
window = MainWindow()
for name in ("phong", "cook_torrance", "ward"):
    window.lab.add(load_any(name))
window.resize(1280, 800)
window.show()
before = window.frames
window.request()
while window.frames == before:
    app.processEvents()
print(",".join(m for m in HEAVY_MODULES if m in sys.modules) or "none")
close_for_exit(app, window)
"""


@pytest.mark.skipif(not os.environ.get("DISPLAY"), reason="needs a display (xvfb-run)")
def test_first_frame_imports_no_heavy_module():
    run = subprocess.run(
        [sys.executable, "-c", SCRIPT], capture_output=True, text=True, timeout=120
    )
    assert run.returncode == 0, run.stderr[-2000:]
    assert run.stdout.strip().splitlines()[-1] == "none", (
        f"loaded before the first frame: {run.stdout.strip()} (of {HEAVY_MODULES}); "
        "import them where they are used"
    )


# `brdf-lab app` parses its command line without importing the other features' CLIs.
PARSE_SCRIPT = """
import contextlib, io, sys
from lab.cli import main
with contextlib.redirect_stdout(io.StringIO()) as shown, contextlib.suppress(SystemExit):
    main(sys.argv[1:])
others = ("lab.grading", "lab.web", "lab.ibl.cli", "lab.measured.cli", "urllib.request")
print("--bench" in shown.getvalue(), ",".join(m for m in others if m in sys.modules) or "none")
"""


def test_app_command_line_loads_no_other_feature():
    for argv in (["app", "--help"], ["--help"]):
        run = subprocess.run(
            [sys.executable, "-c", PARSE_SCRIPT, *argv], capture_output=True, text=True, timeout=60
        )
        assert run.returncode == 0, run.stderr[-2000:]
        shown, loaded = run.stdout.split()
        if argv[0] == "app":
            assert (shown, loaded) == ("True", "none"), run.stdout  # the app's own help
        else:  # the whole command's help lists every feature's sub-commands
            assert "lab.grading" in loaded and "lab.web" in loaded, run.stdout

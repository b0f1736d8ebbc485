"""Run in a copy of the lab with the hemisphere view's four files added: looks for the view
in the CLI, the presets, the app (when there is a display) and the page with its address,
and prints what it found as JSON (tests/test_web_new_view.py judges it)."""

from __future__ import annotations

import base64
import json
import os
import sys
import tempfile

import numpy as np
from PIL import Image

import lab
from lab import views
from lab.cli import main as cli
from lab.presets import check_settings

found: dict = {"lab": lab.__file__, "views": [v.name for v in views.all_views()]}
work = tempfile.mkdtemp()
for model, extra in (("lambert", []), ("phong", ["--set", "kd=0"])):
    png = os.path.join(work, f"{model}.png")
    found[f"cli_{model}"] = cli(["render", model, "--view", "hemi", "-o", png, *extra])
    with Image.open(png) as picture:
        pixels = np.asarray(picture.convert("RGBA"), dtype=float)
    disc = pixels[pixels[..., 3] > 0][:, 0]
    found[f"png_{model}"] = [float(disc.min()), float(disc.max()), int(disc.size)]
found["preset"] = check_settings({"hemi_gain": 10.0}, "p.toml")

if os.environ.get("DISPLAY"):
    from PyQt6.QtWidgets import QApplication

    from lab.app.renderer import AppRenderer
    from lab.app.window import MainWindow, close_for_exit
    from lab.gl import get_context
    from lab.models import load_model

    app = QApplication([])
    window = MainWindow(AppRenderer(get_context()))
    window.lab.add(load_model("lambert"))
    found["dock"] = "hemi" in window.docks
    widget = window.docks["hemi"].widget()
    widget.redraw()
    found["dock_text"] = widget.label.text()
    close_for_exit(app, window)

from lab.web.browser import chromium  # noqa: E402
from lab.web.site import export, serving  # noqa: E402

site = export(os.path.join(work, "site")).parent
with serving(site) as url, chromium() as browser:
    page = browser.new_page(viewport={"width": 1300, "height": 900})
    errors: list[str] = []
    page.on("console", lambda m: m.type == "error" and errors.append(m.text))
    page.on("pageerror", lambda e: errors.append(str(e)))
    page.goto(f"{url}index.html#model=lambert&light=30,0&views=hemi&hemi_gain=2")
    page.evaluate("window.brdfLab.ready")
    found["choice"] = page.evaluate(
        "[...document.querySelectorAll('#view-choice input')].map(b => [b.value, b.checked])"
    )
    found["control"] = page.evaluate(
        "(e => e && [e.type, e.min, e.max, e.value])(document.querySelector('#hemi-gain'))"
    )
    view = page.evaluate("brdfLab.readView(0, 'hemi')")
    data = np.frombuffer(base64.b64decode(view["data"]), dtype=np.float32).reshape(-1, 4)
    disc = data[data[:, 3] > 0][:, 0]
    found["page_lambert"] = [float(disc.min()), float(disc.max()), int(disc.size)]
    page.evaluate("brdfLab.setSettings({hemi_gain: 3})")
    found["hash"] = page.evaluate("location.hash")
    found["notes"] = page.evaluate("brdfLab.notes()")
    found["errors"] = errors
json.dump(found, sys.stdout)

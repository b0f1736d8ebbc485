"""The web lab in headless Chromium, opened as the page tests open it."""

from __future__ import annotations

import base64
from collections.abc import Iterator
from contextlib import contextmanager

import numpy as np


@contextmanager
def open_page(tmp_path_factory, address: str, width: int = 1400, height: int = 900) -> Iterator:
    """The exported site served locally and opened at `index.html#address`, ready to use;
    `tab.errors` collects console errors and uncaught exceptions."""
    from lab.web.browser import chromium
    from lab.web.site import export, serving

    site = export(tmp_path_factory.mktemp("site")).parent
    with serving(site) as url, chromium() as browser:
        tab = browser.new_page(viewport={"width": width, "height": height})
        errors: list[str] = []
        tab.on("console", lambda m: m.type == "error" and errors.append(m.text))
        tab.on("pageerror", lambda e: errors.append(str(e)))
        tab.goto(f"{url}index.html#{address}")
        tab.evaluate("window.brdfLab.ready")
        tab.errors = errors
        yield tab


class LabTab:
    """A tab of the lab (in its own browser context) at `index.html#address` of the site
    `browser.base_url` serves, ready to use; `errors` collects console errors and uncaught
    exceptions. `context_options` go to the context (has_touch, accept_downloads...)."""

    def __init__(
        self, browser, address: str, width: int = 1300, height: int = 900, **context_options
    ):
        self.context = browser.new_context(
            viewport={"width": width, "height": height}, **context_options
        )
        self.page = self.context.new_page()
        self.errors: list[str] = []
        self.page.on("console", lambda m: m.type == "error" and self.errors.append(m.text))
        self.page.on("pageerror", lambda e: self.errors.append(str(e)))
        self.page.goto(f"{browser.base_url}index.html#{address}")
        self.page.evaluate("window.brdfLab.ready")

    def js(self, expression: str, arg=None):
        return self.page.evaluate(expression, arg)

    def sphere(self, panel: int = 0) -> np.ndarray:
        """Panel `panel`'s float render of the sphere, rows from the top (RGBA)."""
        out = self.js("i => brdfLab.readSphere(i)", panel)
        data = np.frombuffer(base64.b64decode(out["data"]), dtype=np.float32)
        return data.reshape(out["height"], out["width"], 4)

    def close(self) -> None:
        self.context.close()

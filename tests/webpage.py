"""The web lab in headless Chromium, opened as the page tests open it."""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager


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

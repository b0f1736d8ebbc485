"""Headless Chromium (the system one) through Playwright, for tests, benchmarks and PDFs."""

from __future__ import annotations

import contextlib
import shutil
from collections.abc import Iterator
from pathlib import Path

CHROMIUM_FLAGS = [
    "--headless=new",
    "--no-sandbox",
    "--enable-unsafe-swiftshader",  # WebGL2 on the CPU when there is no GPU
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--no-first-run",
    "--disable-features=WebUIOmniboxPopup,PreloadTopChromeWebUI",
]


def chromium_path() -> str | None:
    for candidate in ("/usr/bin/chromium", "/usr/bin/chromium-browser"):
        if Path(candidate).exists():
            return candidate
    return shutil.which("chromium")


class BrowserMissing(RuntimeError):
    """Playwright or Chromium is not installed."""


@contextlib.contextmanager
def chromium(flags: tuple[str, ...] = ()) -> Iterator[object]:
    """A launched headless Chromium (Playwright Browser) with CHROMIUM_FLAGS and `flags`;
    never downloads one."""
    try:
        from playwright.sync_api import sync_playwright
    except ImportError:
        raise BrowserMissing(
            "Playwright is not installed: run .venv/bin/pip install playwright"
        ) from None
    executable = chromium_path()
    if executable is None:
        raise BrowserMissing("Chromium is not installed: run apt-get install -y chromium")
    with sync_playwright() as playwright:
        browser = playwright.chromium.launch(
            executable_path=executable, args=[*CHROMIUM_FLAGS, *flags], headless=True
        )
        try:
            yield browser
        finally:
            browser.close()


@contextlib.contextmanager
def sibling(browser) -> Iterator[object]:
    """Another Chromium launched by the Playwright that launched `browser` (one thread may
    run one Playwright): its own processes, so the WebGL contexts of `browser`'s pages do
    not count against its own (Chromium keeps only so many alive at once)."""
    fresh = browser.browser_type.launch(
        executable_path=chromium_path(), args=list(CHROMIUM_FLAGS), headless=True
    )
    try:
        yield fresh
    finally:
        fresh.close()

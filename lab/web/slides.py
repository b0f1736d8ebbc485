"""The lecture deck: `brdf-lab slides build` and `brdf-lab slides pdf`.

The deck's Markdown lives in slides/lecture.md; slides/build.mjs turns it into a reveal.js
page (equations by KaTeX at build time). reveal.js, KaTeX and marked come from npm with the
committed lockfile (`npm ci`); they are copied into the built deck, never into the repo.
"""

from __future__ import annotations

import contextlib
import json
import shutil
import subprocess
import time
from pathlib import Path

from lab.resources import data_dir
from lab.web.site import export, serving

SLIDES_DIR = data_dir("slides")


def workdir() -> Path:
    """Where npm installs and build.mjs runs: slides/ in a clone; for an installed lab
    (site-packages may be read-only) a copy of the sources in the user's cache."""
    import os

    from lab import __version__

    if os.access(SLIDES_DIR, os.W_OK) and not (SLIDES_DIR.parent.name == "_data"):
        return SLIDES_DIR
    cache = Path(os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache")
    work = cache / "brdf-lab" / f"slides-{__version__}"
    work.mkdir(parents=True, exist_ok=True)
    for item in SLIDES_DIR.iterdir():
        if item.is_file():
            shutil.copy2(item, work / item.name)
    return work


class SlidesError(RuntimeError):
    """The deck cannot be built or printed (one line, says what to do)."""


def _run(command: list[str], what: str, timeout: float = 300) -> str:
    try:
        result = subprocess.run(
            command, cwd=workdir(), capture_output=True, text=True, timeout=timeout
        )
    except FileNotFoundError:
        raise SlidesError(f"{command[0]} is not installed: apt-get install nodejs npm") from None
    except subprocess.TimeoutExpired:
        raise SlidesError(f"{what} took longer than {timeout:.0f} s") from None
    if result.returncode != 0:
        lines = [ln for ln in (result.stderr or result.stdout).splitlines() if ln.strip()]
        detail = lines[-1] if lines else f"exit status {result.returncode}"
        raise SlidesError(f"{what} failed: {detail}")
    return result.stdout


def install() -> None:
    """`npm ci` in slides/ unless node_modules already matches the lockfile."""
    lock = workdir() / "package-lock.json"
    installed = workdir() / "node_modules" / ".package-lock.json"
    if installed.is_file() and installed.stat().st_mtime >= lock.stat().st_mtime:
        return
    _run(["npm", "ci", "--prefer-offline", "--no-audit", "--no-fund"], "npm ci in slides/")


def build(outdir: Path, figures: bool = True) -> Path:
    """Build the deck into `outdir`; returns its index.html."""
    for tool in ("node", "npm"):
        if shutil.which(tool) is None:
            raise SlidesError(f"{tool} is not installed: apt-get install nodejs npm")
    try:
        outdir.mkdir(parents=True, exist_ok=True)
    except OSError as err:
        raise SlidesError(f"cannot create {outdir}: {err.strerror}") from None
    install()
    if figures:
        from lab.figures import lecture_figures

        lecture_figures(outdir / "figures")
        from lab.app.steps import render_steps  # the object view's four SVBRDF steps

        render_steps(outdir / "figures")
    export(outdir / "lab")  # the live demos' iframes load the web lab from here
    _run(["node", str(workdir() / "build.mjs"), str(outdir.resolve())], "building the deck")
    return outdir / "index.html"


def deck_info(deck: Path) -> dict:
    """What build.mjs wrote about the deck: slide count, demos, figures."""
    return json.loads((deck / "deck.json").read_text(encoding="utf-8"))


def pdf(deck: Path, output: Path, browser=None, converge_s: float = 60.0) -> Path:
    """Print the built deck to a PDF (reveal.js print layout, one slide per page).

    `browser`: an already launched Playwright browser to use (one per thread at a time);
    `converge_s`: how long the Monte Carlo demos may run toward their sample targets.
    """
    if not (deck / "index.html").is_file():
        raise SlidesError(f"{deck} holds no deck: run 'brdf-lab slides build {deck}' first")
    if output.parent and not output.parent.is_dir():
        raise SlidesError(f"cannot write {output}: folder {output.parent} does not exist")
    with serving(deck) as url, _browser(browser) as browser:
        page = browser.new_page(viewport={"width": 1280, "height": 800})
        page.goto(f"{url}index.html?print-pdf", wait_until="networkidle")
        page.wait_for_function("window.Reveal && Reveal.isReady()")
        # Load every demo (reveal loads them lazily) and let each render before printing.
        page.evaluate(
            "document.querySelectorAll('iframe.demo').forEach(f => {"
            " if (!f.src) f.src = f.dataset.src; })"
        )
        _wait_for_first_pictures(page, DEMOS_RENDERED)
        # The Monte Carlo demo: loaded too, and printed once it shows a first image.
        page.evaluate(
            "document.querySelectorAll('iframe.ibl-demo').forEach(f => {"
            " if (!f.src) f.src = f.dataset.src; })"
        )
        _wait_for_first_pictures(page, IBL_DEMOS_RENDERED)
        _wait_for_convergence(page, converge_s)
        page.pdf(path=str(output), width="1280px", height="800px", print_background=True)
        page.close()
    return output


# Whether each demo of a kind has drawn its first picture (or, for Monte Carlo, failed).
DEMOS_RENDERED = """() => [...document.querySelectorAll('iframe.demo')].map((f) =>
  !!(f.contentWindow && f.contentWindow.brdfLab &&
     f.contentWindow.brdfLab.state.firstRenderMs !== null))"""
IBL_DEMOS_RENDERED = """() => [...document.querySelectorAll('iframe.ibl-demo')].map((f) =>
  !!(f.contentWindow && f.contentWindow.iblDemo &&
     (f.contentWindow.iblDemo.state.firstRenderMs !== null ||
      f.contentWindow.iblDemo.state.error)))"""


def _wait_for_first_pictures(page, rendered_js: str, stall_s: float = 120.0) -> None:
    """Wait until every demo has drawn, for as long as they keep finishing.

    All demos load at once and each compiles its programs at its first draw, so on a busy
    machine without a GPU the whole set can take minutes; only a stall of `stall_s` with
    no demo finishing is an error.
    """
    done = page.evaluate(rendered_js)
    last_change = time.monotonic()
    while not all(done):
        page.wait_for_timeout(250)
        now = page.evaluate(rendered_js)
        if sum(now) > sum(done):
            last_change = time.monotonic()
        done = now
        if time.monotonic() - last_change > stall_s:
            missing = ", ".join(str(i + 1) for i, d in enumerate(done) if not d)
            raise SlidesError(
                f"demo(s) {missing} of {len(done)} drew nothing for {stall_s:.0f} s; "
                "open the deck in a browser to see their errors"
            )


# Each Monte Carlo demo's samples per pixel (the fewest of its panels) and its target.
IBL_PROGRESS = """() => [...document.querySelectorAll('iframe.ibl-demo')].map((f) => {
  const d = f.contentWindow && f.contentWindow.iblDemo;
  if (!d || d.state.error) return null;
  return [Math.min(...d.panels.map((p) => p.samples)), d.state.target];
})"""

# Beneath a demo printed before it converged: what the handout shows is a snapshot.
SNAPSHOT_NOTE = """([index, samples, target]) => {
  const frame = document.querySelectorAll('iframe.ibl-demo')[index];
  const note = document.createElement('p');
  note.className = 'snapshot';
  note.textContent = `Snapshot at ${samples} of ${target} samples per pixel: ` +
    'the live demo converges further.';
  note.style.cssText = 'font-size: 0.92em; color: #555; margin: 0.2em 0;';
  frame.after(note);
}"""


def _wait_for_convergence(page, seconds: float) -> None:
    """Let every Monte Carlo demo reach its sample target (the handout should show MIS
    beating uniform sampling, not 8 samples of noise); one that has not by then is printed
    with a note saying it is a snapshot."""
    deadline = time.monotonic() + seconds
    while True:
        progress = page.evaluate(IBL_PROGRESS)
        pending = [(i, p) for i, p in enumerate(progress) if p is not None and p[0] < p[1]]
        if not pending or time.monotonic() > deadline:
            break
        page.wait_for_timeout(250)
    for index, (samples, target) in pending:
        page.evaluate(SNAPSHOT_NOTE, [index, samples, target])


@contextlib.contextmanager
def _browser(browser=None):
    from lab.web.browser import chromium

    if browser is not None:
        yield browser
        return
    with chromium() as launched:
        yield launched


def pdf_or_error(deck: Path, output: Path) -> Path:
    """pdf(), with the browser's time-outs turned into a SlidesError."""
    from playwright.sync_api import Error as PlaywrightError

    try:
        return pdf(deck, output)
    except PlaywrightError as err:
        first = str(err).strip().splitlines()[0] if str(err).strip() else type(err).__name__
        raise SlidesError(f"printing the deck failed: {first}") from None

"""`brdf-lab web-bench`: how fast the web lab draws in headless Chromium (SwiftShader)."""

from __future__ import annotations

import contextlib
import statistics
import tempfile
from dataclasses import dataclass, field
from pathlib import Path

FIRST_RENDER_TARGET_MS = 300.0
ALL_VIEWS = "lobe3d,sh,terms,slice,albedo,object"  # with the sphere and the polar plot: every view
SLIDER_P95_TARGET_MS = 33.0
VIEWPORT = {"width": 1920, "height": 2000}  # every view on screen at 512 px
# A user's tab is open and idle before the address is typed (Chromium even keeps a spare
# renderer process ready); a page Playwright has just opened is still starting its renderer
# for a few hundred milliseconds, which the first load would otherwise be timed with.
TAB_IDLE_MS = 500
# Every view box that is not wholly inside the window.
OFFSCREEN_JS = """[...document.querySelectorAll('#panels .view')].filter(v => {
  const r = v.getBoundingClientRect();
  return r.top < 0 || r.bottom > innerHeight || r.left < 0 || r.right > innerWidth;
}).map(v => v.dataset.view)"""


@dataclass
class WebBench:
    size: int
    model: str
    first_render_ms: list[float]
    frame_ms: list[float]
    renderer: str
    views: str = ""
    offscreen: tuple[str, ...] = ()  # views not wholly inside the window (they would wait)
    full_render_ms: list[float] = field(default_factory=list)  # every view at full quality
    # With --compare: the other site's directory and its first and full-quality renders.
    compared: tuple[str, list[float], list[float]] | None = None
    # First renders of the sphere and the polar plot alone, loaded in turn with the others:
    # what this machine takes before any further view costs anything.
    floor_ms: list[float] = field(default_factory=list)

    @property
    def p95(self) -> float:
        ordered = sorted(self.frame_ms)
        return ordered[min(len(ordered) - 1, round(0.95 * (len(ordered) - 1)))]

    def report(self) -> str:
        first = statistics.median(self.first_render_ms)
        verdict = lambda ok: "ok" if ok else "MISSED"  # noqa: E731
        first_line = (
            f"  first render after load (every view drawn, the costly ones coarse): median "
            f"{first:.0f} ms over {len(self.first_render_ms)} loads "
            f"(max {max(self.first_render_ms):.0f} ms); "
            f"target <= {FIRST_RENDER_TARGET_MS:.0f} ms: "
            f"{verdict(first <= FIRST_RENDER_TARGET_MS)}"
        )
        if self.floor_ms:
            floor = statistics.median(self.floor_ms)
            first_line += (
                f"\n  sphere and polar plot alone (this machine's floor): median {floor:.0f} ms; "
                f"the other views add {first - floor:+.0f} ms"
            )
        if self.full_render_ms:
            first_line += (
                f"\n  every view at full quality: median "
                f"{statistics.median(self.full_render_ms):.0f} ms after load"
            )
        slider_line = (
            f"  slider frame: p50 {statistics.median(self.frame_ms):.1f} ms, "
            f"p95 {self.p95:.1f} ms over {len(self.frame_ms)} frames; "
            f"target p95 <= {SLIDER_P95_TARGET_MS:.0f} ms: "
            f"{verdict(self.p95 <= SLIDER_P95_TARGET_MS)}"
        )
        shown = f"sphere, polar, {self.views.replace(',', ', ')}" if self.views else "sphere, polar"
        header = f"web lab, headless Chromium ({self.renderer}), {self.model} at "
        lines = [header + f"{self.size}x{self.size}, views {shown}:", first_line, slider_line]
        if self.compared:
            lines.append(self.comparison())
        if self.offscreen:
            lines.append(f"  NOT all visible (off screen: {', '.join(self.offscreen)})")
        return "\n".join(lines)

    def comparison(self) -> str:
        """Both builds' medians, loaded in turn in one browser (the machine's drift between
        runs, tens of ms, is then the same for both)."""
        where, first, full = self.compared
        mine, theirs = statistics.median(self.first_render_ms), statistics.median(first)
        text = (
            f"  compared with {where} (loads in turn, one browser): first render median "
            f"{theirs:.0f} ms there, {mine:.0f} ms here ({mine - theirs:+.0f} ms)"
        )
        if full and self.full_render_ms:
            here, there = statistics.median(self.full_render_ms), statistics.median(full)
            text += (
                f"; full quality {there:.0f} ms there, {here:.0f} ms here ({here - there:+.0f} ms)"
            )
        return text


def first_float_param(model_name: str) -> str:
    from lab.models import load_model

    model = load_model(model_name)
    for p in model.params.values():
        if p.kind == "float":
            return p.name
    raise ValueError(f"model {model_name} has no float parameter to move")


class BenchError(ValueError):
    """What the bench was asked cannot be done (a --compare directory that is not a site)."""


def run(
    size: int = 512,
    model: str = "phong",
    loads: int = 5,
    steps: int = 120,
    views: str = ALL_VIEWS,
    compare: Path | None = None,
) -> WebBench:
    """Time page load -> first render of every view (performance.now() at the first finished
    frame, i.e. since navigation start in a new tab left idle for TAB_IDLE_MS; the costly
    views coarse, as while a student drags) -> every view at full quality (the next frame),
    and the frame time while a slider moves (the costly views coarse). With `compare` (a
    site written by `brdf-lab web-export`), its page loads after each of this build's; with
    `views`, the page with none of them (sphere and polar plot) loads after each too."""
    from lab.web.browser import chromium
    from lab.web.site import export, serving

    param = first_float_param(model)
    if compare is not None and not (Path(compare) / "index.html").is_file():
        raise BenchError(
            f"{compare}: no index.html there: give a directory that 'brdf-lab web-export DIR' "
            "wrote (run it in the checkout to compare with)"
        )
    shown = f"&views={views}" if views else ""
    address = f"index.html#model={model}&size={size}&light=30,0{shown}"
    with contextlib.ExitStack() as stack:
        tmp = stack.enter_context(tempfile.TemporaryDirectory())
        url = stack.enter_context(serving(export(tmp).parent))
        other = stack.enter_context(serving(compare)) if compare is not None else None
        browser = stack.enter_context(chromium())
        first, full, frames, floor = [], [], [], []
        their_first: list[float] = []
        their_full: list[float] = []
        renderer = "?"
        offscreen: tuple[str, ...] = ()
        for _ in range(max(1, loads)):
            page = _load(browser, url + address, first, full)
            offscreen = tuple(page.evaluate(OFFSCREEN_JS))
            if not frames:
                renderer = page.evaluate(
                    "(() => { const gl = brdfLab.panel(0).gl;"
                    " const ext = gl.getExtension('WEBGL_debug_renderer_info');"
                    " return ext ? gl.getParameter(ext.UNMASKED_RENDERER_WEBGL)"
                    " : gl.getParameter(gl.RENDERER); })()"
                )
                page.evaluate(f"brdfLab.sliderFrames(0, '{param}', 10)")  # warm up
                frames = page.evaluate(f"brdfLab.sliderFrames(0, '{param}', {steps})")
            page.close()
            if other is not None:
                _load(browser, other + address, their_first, their_full).close()
            if views:
                _load(browser, url + address.removesuffix(shown), floor, []).close()
    compared = (str(compare), their_first, their_full) if compare is not None else None
    return WebBench(
        size, model, first, frames, renderer, views, offscreen, full, compared, floor_ms=floor
    )


def _load(browser, address: str, first: list[float], full: list[float]):
    """Opens `address` in a new tab left idle first (tall enough that every view is on
    screen: views out of sight do not render); appends its first and full-quality render
    times and returns the page."""
    page = browser.new_page(viewport=VIEWPORT)
    page.wait_for_timeout(TAB_IDLE_MS)
    page.goto(address)
    page.evaluate("window.brdfLab.ready")
    first.append(page.evaluate("brdfLab.state.firstRenderMs"))
    page.wait_for_function("brdfLab.state.fullRenderMs !== null")
    full.append(page.evaluate("brdfLab.state.fullRenderMs"))
    return page

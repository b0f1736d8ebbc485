"""`brdf-lab web-bench`: how fast the web lab draws in headless Chromium (SwiftShader).

On a machine without a GPU Chromium compiles each WebGL program at its first draw, so no
fixed time holds everywhere; the targets are ratios to this machine's floor, the page
with the sphere and the polar plot alone, loaded in turn with the page under test in
the same browser (the machine's drift then falls on both)."""

from __future__ import annotations

import contextlib
import statistics
import tempfile
from dataclasses import dataclass, field
from pathlib import Path

# The page with every view against the floor page: its first picture (every panel's sphere
# and polar plot), every view inside the window drawn, and the slider's p95 frame.
FIRST_RATIO = 1.1
VIEWS_RATIO = 1.4
SLIDER_RATIO = 1.3
VIEWPORT = {"width": 1400, "height": 900}  # views out of it draw when scrolled to or idle
# A user's tab is open and idle before the address is typed (Chromium even keeps a spare
# renderer process ready); a page Playwright has just opened is still starting its renderer
# for a few hundred milliseconds, which the first load would otherwise be timed with.
TAB_IDLE_MS = 500
# Every load compiles its programs as a first visit does: no program kept by the GPU process
# from an earlier load (the floor page's would otherwise be ready for the next page's).
BENCH_FLAGS = ("--disable-gpu-program-cache", "--disable-gpu-shader-disk-cache")
# Every view box wholly out of the window (the page draws those when idle or scrolled to).
OFFSCREEN_JS = """[...document.querySelectorAll('#panels .view')].filter(v => {
  const r = v.getBoundingClientRect();
  return r.bottom <= 0 || r.top >= innerHeight || r.right <= 0 || r.left >= innerWidth;
}).map(v => v.dataset.view)"""


RENDERER_JS = """(() => { const gl = brdfLab.panel(0).gl;
  const ext = gl.getExtension('WEBGL_debug_renderer_info');
  return ext ? gl.getParameter(ext.UNMASKED_RENDERER_WEBGL) : gl.getParameter(gl.RENDERER); })()"""


def all_views() -> str:
    """Every view the page draws besides the sphere and the polar plot (the registry's
    views with a page module), comma-separated."""
    from lab.web.site import view_pages

    return ",".join(view_pages())


def paired(times: list[float], floor: list[float]) -> list[float]:
    """Each load's time over the floor page's load of the same turn."""
    if len(times) != len(floor):
        return [median(times) / median(floor)] if times and floor else [float("nan")]
    return [t / f for t, f in zip(times, floor, strict=True)]


def median(values: list[float]) -> float:
    return statistics.median(values) if values else float("nan")


def p95(values: list[float]) -> float:
    ordered = sorted(values)
    return (
        ordered[min(len(ordered) - 1, round(0.95 * (len(ordered) - 1)))]
        if ordered
        else float("nan")
    )


@dataclass
class WebBench:
    size: int
    model: str
    first_render_ms: list[float]  # every panel's sphere and polar plot on screen
    frame_ms: list[float]  # slider frames with the views on
    renderer: str
    views: str = ""
    offscreen: tuple[str, ...] = ()  # views not wholly inside the window (they wait)
    full_render_ms: list[float] = field(default_factory=list)  # every view at full quality
    # With --compare: the other site's directory and its first and full-quality renders.
    compared: tuple[str, list[float], list[float]] | None = None
    # The floor page (the sphere and the polar plot alone), loaded in turn with the others.
    floor_ms: list[float] = field(default_factory=list)
    views_ms: list[float] = field(default_factory=list)  # every view in the window drawn
    floor_frame_ms: list[float] = field(default_factory=list)  # slider frames of the floor page

    @property
    def p95(self) -> float:
        return p95(self.frame_ms)

    def ratios(self) -> dict[str, float]:
        """first, views and slider against the floor page's (nan where not measured): the
        load times as the median of each load's ratio to the floor page's load of the same
        turn (the machine's drift between turns then cancels), the slider as p95 to p95."""
        return {
            "first": median(paired(self.first_render_ms, self.floor_ms)),
            "views": median(paired(self.views_ms, self.floor_ms)),
            "slider": self.p95 / p95(self.floor_frame_ms),
        }

    def spread(self, key: str) -> str:
        """' (loads 0.98-1.12)': the lowest and highest ratio of one load ('' for one)."""
        times = self.first_render_ms if key == "first" else self.views_ms
        ratios = paired(times, self.floor_ms)
        return f" (loads {min(ratios):.2f}-{max(ratios):.2f})" if len(ratios) > 1 else ""

    def report(self) -> str:
        verdict = lambda ok: "ok" if ok else "MISSED"  # noqa: E731
        first = median(self.first_render_ms)
        shown = f"sphere, polar, {self.views.replace(',', ', ')}" if self.views else "sphere, polar"
        window = f"{VIEWPORT['width']}x{VIEWPORT['height']} window"
        header = f"web lab, headless Chromium ({self.renderer}), {self.model} at "
        lines = [header + f"{self.size}x{self.size} in a {window}, views {shown}:"]
        lines.append(
            f"  first picture (every sphere and polar plot): median {first:.0f} ms after "
            f"navigation over {len(self.first_render_ms)} loads "
            f"(max {max(self.first_render_ms):.0f} ms)"
        )
        ratios = self.ratios()
        if self.floor_ms:
            lines.append(
                f"  floor page (sphere and polar plot alone): median "
                f"{median(self.floor_ms):.0f} ms; "
                f"first picture / floor = {ratios['first']:.2f}{self.spread('first')} (target <= "
                f"{FIRST_RATIO}): {verdict(ratios['first'] <= FIRST_RATIO)}"
            )
        if self.views_ms and self.floor_ms:
            lines.append(
                f"  every view in the window drawn (the costly ones coarse): median "
                f"{median(self.views_ms):.0f} ms; / floor = {ratios['views']:.2f}"
                f"{self.spread('views')} (target <= {VIEWS_RATIO}): "
                f"{verdict(ratios['views'] <= VIEWS_RATIO)}"
            )
        if self.full_render_ms:
            lines.append(
                f"  every view at full quality: median {median(self.full_render_ms):.0f} ms "
                "after load"
            )
        slider = (
            f"  slider frame: p50 {median(self.frame_ms):.1f} ms, p95 {self.p95:.1f} ms over "
            f"{len(self.frame_ms)} frames"
        )
        if self.floor_frame_ms:
            slider += (
                f"; floor page p50 {median(self.floor_frame_ms):.1f} ms, "
                f"p95 {p95(self.floor_frame_ms):.1f} ms; p95 / floor = "
                f"{ratios['slider']:.2f} (target <= {SLIDER_RATIO}): "
                f"{verdict(ratios['slider'] <= SLIDER_RATIO)}"
            )
        lines.append(slider)
        if self.compared:
            lines.append(self.comparison())
        if self.offscreen:
            lines.append(
                f"  out of the window (drawn when scrolled to or idle): {', '.join(self.offscreen)}"
            )
        if self.views and len(self.offscreen) >= len(self.views.split(",")):
            lines.append(
                "  no view is inside the window at this size: the views figure is a frame with "
                "none to draw (a smaller --size brings views into sight)"
            )
        return "\n".join(lines)

    def comparison(self) -> str:
        """Both builds' medians, loaded in turn in one browser (the machine's drift between
        runs, tens of ms, is then the same for both)."""
        where, first, full = self.compared
        mine, theirs = median(self.first_render_ms), median(first)
        text = (
            f"  compared with {where} (loads in turn, one browser): first render median "
            f"{theirs:.0f} ms there, {mine:.0f} ms here ({mine - theirs:+.0f} ms)"
        )
        if full and self.full_render_ms:
            here, there = median(self.full_render_ms), median(full)
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
    views: str | None = None,
    compare: Path | None = None,
) -> WebBench:
    """Loads the page with `views` (default: every view) and the floor page in turn (after
    one untimed load of each), each in a new tab left idle for TAB_IDLE_MS: the first
    picture, every view in the window drawn and every view at full quality
    (performance.now() since navigation start), then the frame times while a slider moves
    through `steps` positions on both pages, in turns of SLIDER_TURN frames, on every load.
    With `compare` (a site written by `brdf-lab web-export`), its page loads after each of
    this build's."""
    from lab.web.browser import chromium
    from lab.web.site import export, serving

    views = all_views() if views is None else views
    param = first_float_param(model)
    if compare is not None and not (Path(compare) / "index.html").is_file():
        raise BenchError(
            f"{compare}: no index.html there: give a directory that 'brdf-lab web-export DIR' "
            "wrote (run it in the checkout to compare with)"
        )
    shown = f"&views={views}" if views else ""
    address = f"index.html#model={model}&size={size}&light=30,0{shown}"
    result = WebBench(size, model, [], [], "?", views)
    their_first: list[float] = []
    their_full: list[float] = []
    with contextlib.ExitStack() as stack:
        tmp = stack.enter_context(tempfile.TemporaryDirectory())
        url = stack.enter_context(serving(export(tmp).parent))
        other = stack.enter_context(serving(compare)) if compare is not None else None
        browser = stack.enter_context(chromium(BENCH_FLAGS))
        floor_address = url + address.removesuffix(shown)
        # One load of each page, untimed: the browser's own first-load costs (its GPU
        # process starting) fall on neither page.
        _load(browser, floor_address, [], [], []).close()
        if views:
            _load(browser, url + address, [], [], []).close()

        def load_views():
            page = _load(
                browser,
                url + address,
                result.first_render_ms,
                result.full_render_ms,
                result.views_ms,
            )
            result.offscreen = tuple(page.evaluate(OFFSCREEN_JS))
            result.renderer = page.evaluate(RENDERER_JS)
            if other is not None:
                _load(browser, other + address, their_first, their_full, []).close()
            return page

        def load_floor():
            return _load(browser, floor_address, result.floor_ms, [], [])

        for k in range(max(1, loads)):
            # In turn, the other way round every other time: neither page is always the one
            # loaded after the other.
            if not views:
                pages = [load_views()]
            elif k % 2 == 0:
                pages = [load_views(), load_floor()]
            else:
                pages = [load_floor(), load_views()][::-1]
            # Slider frames on every load, the two pages' in short turns: both then share
            # the machine's ups and downs (a few seconds of another process's work would
            # otherwise fall on one page's frames).
            frames = _slider_in_turn(pages, param, steps)
            result.frame_ms += frames[0]
            if len(frames) > 1:
                result.floor_frame_ms += frames[1]
            for page in pages:
                page.close()
    if compare is not None:
        result.compared = (str(compare), their_first, their_full)
    return result


SLIDER_TURN = 20  # slider frames of one page before the other page's turn


def _slider_in_turn(pages: list, param: str, steps: int) -> list[list[float]]:
    """Each page's slider frame times, `steps` in all per page, taken in turns of
    SLIDER_TURN frames (first page first, then the other way round)."""
    for page in pages:
        page.evaluate(f"brdfLab.sliderFrames(0, '{param}', 10)")  # warm up
    frames: list[list[float]] = [[] for _ in pages]
    turn = 0
    while len(frames[0]) < steps:
        n = min(SLIDER_TURN, steps - len(frames[0]))
        order = range(len(pages)) if turn % 2 == 0 else reversed(range(len(pages)))
        for i in order:
            frames[i] += pages[i].evaluate(f"brdfLab.sliderFrames(0, '{param}', {n})")
        turn += 1
    return frames


def _load(browser, address: str, first: list[float], full: list[float], shown: list[float]):
    """Opens `address` in a new tab left idle first; appends its first picture, every view
    in the window drawn and full quality times and returns the page."""
    page = browser.new_page(viewport=VIEWPORT)
    page.wait_for_timeout(TAB_IDLE_MS)
    page.goto(address)
    page.evaluate("window.brdfLab.ready")
    first.append(page.evaluate("brdfLab.state.firstRenderMs"))
    shown.append(page.evaluate("brdfLab.state.viewsRenderMs"))
    page.wait_for_function("brdfLab.state.fullRenderMs !== null")
    full.append(page.evaluate("brdfLab.state.fullRenderMs"))
    # The views out of the window draw while the page is idle: done before the next page
    # loads, so that no page is timed while another's programs still compile.
    page.wait_for_function("brdfLab.state.idleDrawnMs !== null", timeout=60_000)
    return page

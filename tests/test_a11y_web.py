"""The web lab for every student (WCAG 2.1 AA): axe-core finds no violation in the states
the issue audited; every control has a name and is reached and operated by the keyboard;
values speak in their unit; errors are text tied to their field; a practice run is announced
once; Monte Carlo progress is not a torrent and can be paused; the page reflows at 320 px."""

from __future__ import annotations

from pathlib import Path

import pytest

from lab.web.browser import chromium_path
from tests.axe import VIEWS, lab_states, open_lab, violations

pytestmark = pytest.mark.skipif(chromium_path() is None, reason="needs Chromium")
ROOT = Path(__file__).resolve().parent.parent
SOLUTION = (ROOT / "solutions" / "01_lambert" / "lambert.glsl").read_text(encoding="utf-8")
# Every control the keyboard should reach, as the page shows it.
CONTROLS = """() => [...document.querySelectorAll(
    "input, select, button, canvas[tabindex], .cm-content, a[href]")]
  .filter((e) => e.getClientRects().length && !e.disabled && !e.closest("[hidden]")
    && getComputedStyle(e).visibility !== "hidden")
  .map((e) => e.id || e.outerHTML.slice(0, 80))"""
# A page setting by its registry name (a page from before the registry: a field of its state).
SETTING = """async (name) => (await import('./plotread.js')).setting(brdfLab.state, name)"""
# The live region's texts, collected as they are set.
COLLECT = """() => { window.said = []; new MutationObserver(() => {
  const t = document.getElementById('announce').textContent; if (t) said.push(t); })
  .observe(document.getElementById('announce'),
    { childList: true, characterData: true, subtree: true }); }"""


@pytest.fixture(scope="module")
def browser(tmp_path_factory):
    from lab.web.browser import chromium
    from lab.web.site import export, serving

    site = export(tmp_path_factory.mktemp("site")).parent
    with serving(site) as url, chromium() as browser:
        browser.base_url = url
        yield browser


def ready(page) -> None:
    """The accessibility module attached (after the lab's first frame) and settled."""
    page.wait_for_function("window.brdfLabA11y && window.brdfLabA11y.plots")
    page.evaluate("brdfLabA11y.refresh()")


def test_axe_finds_no_violation_in_the_audited_states(browser):
    found = {}
    for name, page in lab_states(browser, browser.base_url):
        ready(page)
        found[name] = [(v["id"], v["nodes"][:3]) for v in violations(page)]
    assert found == {name: [] for name in found}, found


def test_keyboard_reaches_every_control_with_a_visible_focus_ring(browser):
    page = open_lab(browser, browser.base_url, f"model=phong&views={VIEWS}")
    ready(page)
    wanted = set(page.evaluate(CONTROLS))
    reached = set()
    for _ in range(3 * len(wanted) + 20):
        page.keyboard.press("Tab")
        focus = page.evaluate(
            """() => { const e = document.activeElement; const s = getComputedStyle(e);
              return [e.id || e.outerHTML.slice(0, 80), s.outlineStyle,
                      parseFloat(s.outlineWidth)]; }"""
        )
        reached.add(focus[0])
        if focus[0] in wanted and not focus[0].startswith('<input type="file"'):
            assert focus[1] != "none" and focus[2] >= 2, focus  # the ring shows where focus is
    assert wanted - reached == set()
    page.close()


def test_sliders_say_their_value_and_operate_by_keys(browser):
    page = open_lab(browser, browser.base_url, "model=phong")
    ready(page)
    theta = page.locator("#light-theta")
    assert page.evaluate("document.querySelector('#light-theta').labels[0].textContent").startswith(
        "θi"
    )
    assert theta.get_attribute("aria-valuetext") == "45 degrees"
    theta.focus()
    for _ in range(4):
        page.keyboard.press("ArrowRight")
    assert page.evaluate("brdfLab.state.lights[0].theta") == 47
    page.wait_for_timeout(50)
    assert theta.get_attribute("aria-valuetext") == "47 degrees"
    ke = page.locator('[data-param="ke"] input[type=range]')
    label = page.evaluate(
        "document.querySelector('[data-param=\"ke\"] input[type=range]').labels[0].textContent"
    )
    assert label == "ke" and ke.get_attribute("aria-valuetext") == "50"
    page.close()


def test_a_bad_value_is_text_tied_to_its_field(browser):
    page = open_lab(browser, browser.base_url, "model=phong")
    ready(page)
    page.evaluate(COLLECT)
    box = page.locator('[data-param="ke"] input.value')
    box.fill("fifty")
    box.press("Enter")
    page.wait_for_function(
        "document.querySelector('[data-param=\"ke\"] input.value').getAttribute('aria-invalid')"
    )
    described = box.get_attribute("aria-describedby").split()
    texts = [page.evaluate("i => document.getElementById(i).textContent", i) for i in described]
    message = box.get_attribute("title")
    assert message and message in texts
    page.wait_for_function("said.length > 0")
    assert page.evaluate("said") == [message]
    box.fill("20")
    box.press("Enter")
    page.wait_for_function(
        "!document.querySelector('[data-param=\"ke\"] input.value').hasAttribute('aria-invalid')"
    )
    assert not page.query_selector(".field-error")
    page.close()


def test_keyboard_only_exercise_from_the_list_to_the_announced_result(browser):
    """The exercise list opens on Enter (not on each arrow); the editor takes the solution by
    keyboard; the result is announced once per run."""
    page = open_lab(browser, browser.base_url, "model=phong&size=96")
    ready(page)
    page.evaluate(COLLECT)
    page.focus("#exercise-pick")
    page.keyboard.press("ArrowDown")
    page.wait_for_timeout(300)
    assert page.evaluate("brdfLab.exercises?.exercise ?? null") is None  # not opened by an arrow
    page.keyboard.press("Enter")
    page.wait_for_function("brdfLab.exercises && brdfLab.exercises.runs > 0", timeout=60_000)
    assert page.evaluate("brdfLab.exercises.exercise.name") == "01_lambert"
    page.wait_for_function("said.length > 0")
    page.focus("#editor .cm-content")
    runs = page.evaluate("brdfLab.exercises.runs")
    page.keyboard.press("Control+A")
    page.keyboard.insert_text(SOLUTION)
    page.wait_for_function(f"brdfLab.exercises.runs > {runs}", timeout=60_000)
    page.wait_for_function("said.some(t => t.includes('Every check passed'))", timeout=10_000)
    said = page.evaluate("said")
    final = page.evaluate("brdfLab.exercises.runs")
    # One announcement per run (the error of the stub's first run included), none twice.
    assert len(said) == len(set(said)) <= final, said
    assert said[-1].startswith(f"Practice run {final}: 10 / 10 points")
    page.close()


def test_plot_description_table_and_cursor(browser):
    from lab import describe

    page = open_lab(browser, browser.base_url, "model=phong&ke=20&model=ggx&alpha=0.3")
    ready(page)
    canvas = page.locator(".panel:not(#overlay) canvas.polar").first
    assert canvas.get_attribute("role") == "img"
    lobe = page.evaluate("brdfLab.readLobe(0)")
    lum = [
        sum(w * lobe[4 * i + c] for c, w in enumerate((0.2126, 0.7152, 0.0722))) for i in range(181)
    ]
    import numpy as np

    ours = describe.Lobe("phong", np.arange(-90.0, 91.0), np.array(lum))
    assert canvas.get_attribute("aria-label") == "Polar plot. " + describe.describe([ours], 45.0)
    ref = describe.summarise(describe.reference_lobe("phong", {"ke": 20.0}, 45.0))
    assert f"{describe.fmt(ref.peak)} sr⁻¹" in canvas.get_attribute("aria-label")
    # The overlay compares the two; its table marks each peak and the mirror.
    page.click("#overlay .plot-table-toggle")
    rows = page.evaluate(
        "[...document.querySelectorAll('#overlay .plot-table tr')]"
        ".map(r => [...r.cells].map(c => c.textContent))"
    )
    assert rows[0][:3] == ["θo (deg)", "phong", "ggx"] and len(rows) == 38
    assert any(r[0] == "45°" and "mirror" in r[-1] and "peak phong" in r[-1] for r in rows)
    assert "Highest peak" in page.locator("#overlay canvas[role=img]").get_attribute("aria-label")
    canvas.focus()
    for key in ("ArrowRight", "ArrowRight", "ArrowRight", "ArrowRight", "ArrowRight"):
        page.keyboard.press(key)
    said = page.locator(".panel:not(#overlay) .plot-cursor").first.text_content()
    at = describe.cursor(ours, 40, "f_r")
    assert said == at and said.startswith("θo 40°, f_r ")
    page.close()


def test_orbit_the_3d_lobe_by_keys(browser):
    page = open_lab(browser, browser.base_url, "model=phong&views=lobe3d")
    ready(page)
    canvas = page.locator("canvas.lobe3d").first
    before = [page.evaluate(SETTING, "lobe_yaw"), canvas.evaluate("c => c.toDataURL()")]
    canvas.focus()
    page.keyboard.press("ArrowLeft")
    page.keyboard.press("+")  # the focus stays on the lobe after the first key
    page.evaluate("brdfLab.renderNow()")
    after = [page.evaluate(SETTING, "lobe_yaw"), canvas.evaluate("c => c.toDataURL()")]
    assert after[0] == pytest.approx(before[0] - 0.2)
    assert page.evaluate(SETTING, "lobe_zoom") == pytest.approx(1.2)
    assert after[1] != before[1]  # the picture turned
    page.close()


def test_monte_carlo_progress_is_calm_and_can_pause(browser):
    # 256 px: the estimate is still refining after the 3 s below (at 64 px SwiftShader
    # reaches its last sample in about 2 s, and "continue" would have nothing to add)
    page = open_lab(browser, browser.base_url, "model=ggx&size=256&views=ibl")
    ready(page)
    page.evaluate(COLLECT)
    status = page.locator(".ibl-status").first
    assert status.get_attribute("role") is None and status.get_attribute("aria-live") is None
    page.wait_for_timeout(3000)
    assert len(page.evaluate("said")) <= 1  # at most one per PROGRESS_MS (5 s)
    page.click("button.pause")
    page.wait_for_timeout(200)
    samples = page.evaluate("brdfLab.panel(0).extra.ibl.samples")
    page.wait_for_timeout(700)
    assert page.evaluate("brdfLab.panel(0).extra.ibl.samples") == samples
    assert page.locator("button.pause").get_attribute("aria-pressed") == "true"
    page.click("button.pause")
    page.wait_for_function(f"brdfLab.panel(0).extra.ibl.samples > {samples}")
    page.close()


def test_reduced_motion_starts_estimates_paused(browser):
    context = browser.new_context(reduced_motion="reduce", viewport={"width": 1000, "height": 800})
    page = context.new_page()
    page.goto(f"{browser.base_url}index.html#model=ggx&size=64&views=ibl")
    page.evaluate("window.brdfLab.ready")
    ready(page)
    samples = page.evaluate("brdfLab.panel(0).extra.ibl.samples")
    page.wait_for_timeout(500)
    assert page.evaluate("brdfLab.panel(0).extra.ibl.samples") == samples
    assert page.locator("button.pause").text_content() == "continue"
    context.close()


@pytest.mark.parametrize("address", ["model=phong", f"model=phong&model=ggx&views={VIEWS}"])
def test_reflow_at_320_css_px(browser, address):
    page = open_lab(browser, browser.base_url, address, width=320, height=700)
    ready(page)
    assert (
        page.evaluate("document.documentElement.scrollWidth - document.documentElement.clientWidth")
        == 0
    )
    page.close()


def test_sonification_pitch_follows_the_lobe_and_pans_as_drawn(browser):
    """The sweep rendered offline: the highest pitch where f_r peaks (θo = θi, the mirror, left
    of the normal as drawn), the left channel louder there than the right."""
    page = open_lab(browser, browser.base_url, "model=phong&ke=20&kd=0,0,0&light=45,0")
    ready(page)
    out = page.evaluate(
        """async () => {
          const { sonify } = await import('./plotread.js');
          const reader = [...brdfLabA11y.plots.readers.values()][0];  // panel 1's plot
          const rate = 8000, ctx = new OfflineAudioContext(2, rate * 3.2, rate);
          sonify(reader.lobes(), 45, ctx);
          const buf = await ctx.startRendering();
          const [l, r] = [buf.getChannelData(0), buf.getChannelData(1)];
          // zero crossings (pitch) and energy per channel in 0.1 s windows
          const win = rate / 10, rows = [];
          for (let s = 0; s + win <= l.length; s += win) {
            let z = 0, el = 0, er = 0;
            for (let i = s + 1; i < s + win; i++) {
              if ((l[i - 1] + r[i - 1] < 0) !== (l[i] + r[i] < 0)) z++;
              el += l[i] * l[i]; er += r[i] * r[i];
            }
            rows.push([z, el, er]);
          }
          return rows; }"""
    )
    # 0.05 s lead-in; the sweep covers θo -90..90 in 3 s: θo = 45 at 0.05 + 2.25 s.

    def at(theta: float) -> int:
        return int((0.05 + (theta + 90) / 180 * 3) * 10)

    assert out[at(45)][0] > 2 * out[at(-45)][0]  # the peak sounds higher than the far side
    assert out[at(45)][1] > out[at(45)][2]  # mirror side (left as drawn) in the left ear
    assert out[at(-60)][2] > out[at(-60)][1]  # the light's side in the right ear
    page.close()


def test_the_decks_monte_carlo_demo_pauses_and_names_its_pictures(browser):
    page = browser.new_page(viewport={"width": 900, "height": 500})
    page.goto(f"{browser.base_url}ibl_demo.html#model=ggx&size=64&target=100000")
    page.wait_for_function("window.iblDemo && iblDemo.state.samples.length === 2")
    canvas = page.locator("canvas").first
    assert canvas.get_attribute("role") == "img"
    label = page.evaluate(
        "() => document.getElementById("
        "document.querySelector('canvas').getAttribute('aria-labelledby')).textContent"
    )
    assert " spp" in label
    page.focus("#pause")
    page.keyboard.press("Space")
    page.wait_for_timeout(200)
    samples = page.evaluate("iblDemo.state.samples")
    page.wait_for_timeout(600)
    assert page.evaluate("iblDemo.state.samples") == samples
    assert page.locator("#pause").get_attribute("aria-pressed") == "true"
    page.keyboard.press("Space")
    page.wait_for_function(f"iblDemo.state.samples[0] > {samples[0]}")
    assert violations(page) == []
    page.close()


def test_leaving_a_list_after_arrows_keeps_the_old_choice(browser):
    page = open_lab(browser, browser.base_url, "model=phong")
    ready(page)
    page.focus("#preset")
    page.keyboard.press("ArrowDown")
    page.keyboard.press("Tab")
    assert page.evaluate("document.querySelector('#preset').value") == ""
    assert page.evaluate("brdfLab.state.panels.map(p => p.name)") == ["phong"]
    page.focus("#preset")
    page.keyboard.press("ArrowDown")
    page.keyboard.press("Enter")
    page.wait_for_function("location.hash !== '#model=phong'")  # Enter applied the first preset
    page.close()


def test_editor_status_is_said_when_it_turns_not_at_each_key(browser):
    page = open_lab(browser, browser.base_url, "model=phong")
    ready(page)
    page.evaluate("brdfLab.edit(0)")
    page.wait_for_selector("#editor .cm-content")
    page.evaluate("brdfLab.renderNow()")
    page.wait_for_timeout(100)
    page.evaluate(COLLECT)
    status = page.locator("#editor .editor-status")
    assert status.get_attribute("role") is None
    page.focus("#editor .cm-content")
    page.keyboard.press("Control+End")
    for key in "float oops = ;":
        page.keyboard.type(key)
    page.wait_for_function("said.length > 0")
    page.wait_for_timeout(300)
    said = page.evaluate("said")
    assert said == [status.text_content()]  # once, the error the line shows
    assert said[0].startswith("1 error in phong.glsl")
    page.close()


def test_a_controls_meaning_shows_on_keyboard_focus_and_escape_hides_it(browser):
    page = open_lab(browser, browser.base_url, "model=phong")
    ready(page)
    page.focus("#reset")
    page.keyboard.press("Shift+Tab")  # keyboard focus onto the exercise list
    tip = page.locator("#focus-tip")
    assert tip.is_visible() and "exercise" in tip.text_content()
    page.keyboard.press("Escape")
    assert not tip.is_visible()
    assert page.evaluate("document.activeElement.id") == "exercise-pick"
    page.close()

"""While a slider moves the page's address follows at most every 250 ms (each history
update can cost a frame milliseconds, and browsers refuse them past a few hundred in ten
seconds), and it holds the final values once the hand stops; single actions update it at
once."""

from __future__ import annotations

import pytest
from webpage import open_page

from lab.web.browser import chromium_path

pytestmark = pytest.mark.skipif(
    chromium_path() is None, reason="Chromium is not installed (apt-get install chromium)"
)

COUNT_UPDATES = """() => {
  window.addressUpdates = 0;
  const replace = history.replaceState.bind(history);
  history.replaceState = (...args) => { window.addressUpdates++; return replace(...args); };
}"""


@pytest.fixture(scope="module")
def page(tmp_path_factory):
    with open_page(tmp_path_factory, "model=phong&views=sh") as tab:
        tab.evaluate(COUNT_UPDATES)
        yield tab


def test_dragged_slider_updates_the_address_a_few_times_and_at_the_end(page):
    page.wait_for_timeout(300)  # no update in the last 250 ms: the first one goes at once
    page.evaluate("window.addressUpdates = 0")
    # 40 slider positions within one task, as fast as a hand could never move.
    last = page.evaluate(
        "() => { const slider = document.querySelector('[data-param=ke] input[type=range]');"
        " for (let k = 1; k <= 40; k++) { slider.value = 10 * k;"
        " slider.dispatchEvent(new Event('input', {bubbles: true})); }"
        " return brdfLab.values(0).ke; }"
    )
    assert page.evaluate("window.addressUpdates") == 1  # the first position, not 40
    assert f"ke={last:g}" not in page.evaluate("location.hash")
    page.wait_for_function(f"location.hash.includes('ke={last:g}')", timeout=2000)
    page.wait_for_timeout(300)  # the hand stopped: the coarse views settle
    assert page.evaluate("brdfLab.state.fast") is False
    assert page.evaluate("window.addressUpdates") <= 3


def test_single_actions_update_the_address_at_once(page):
    page.evaluate("document.querySelector('#polar-log').click()")
    assert "polar_log=1" in page.evaluate("location.hash")
    page.evaluate("document.querySelector('#polar-log').click()")
    assert "polar_log=1" not in page.evaluate("location.hash")
    value = page.evaluate("brdfLab.moveSlider(0, 'ke', 420)")  # the test API: at once
    assert f"ke={value:g}" in page.evaluate("location.hash")
    assert page.errors == []


def test_settings_go_by_their_registry_names_and_old_keys_still_read(page):
    """A view setting is one name in Python, the page and the address (phi_d, lobe_yaw,
    sh_order, polar_cos...): its default and range come from the registry; an older
    address's keys (phid, lyaw, sh, cos) still read and are written anew; a value out of
    range is named with the registry's range."""
    from lab import views

    specs = views.all_settings()
    page.evaluate("location.hash = 'model=phong&views=slice,sh&phid=45&lyaw=0.3&sh=4&cos=1'")
    page.wait_for_function("brdfLab.state.settings.phi_d === 45")
    got = page.evaluate(
        "(s => [s.phi_d, s.lobe_yaw, s.sh_order, s.polar_cos, s.shape])(brdfLab.state.settings)"
    )
    assert got == [45, 0.3, 4, True, specs["shape"].default]
    address = page.evaluate("location.hash")
    for key in ("phi_d=45", "lobe_yaw=0.3", "sh_order=4", "polar_cos=1"):
        assert key in address, (key, address)
    assert "phid=" not in address and "lyaw=" not in address
    # The φd slider is built from the registry's range and shows the setting.
    slider = page.evaluate("(e => [e.min, e.max, e.value])(document.querySelector('#phi-d'))")
    assert slider == [f"{specs['phi_d'].minimum:g}", f"{specs['phi_d'].maximum:g}", "45"]
    page.evaluate("location.hash = 'model=phong&sh_order=40&shape=torus'")
    page.wait_for_function("brdfLab.notes().length > 0")
    notes = page.evaluate("brdfLab.notes()")
    assert notes == ["sh_order=40: give a number from 0 to 16"]
    assert page.evaluate("brdfLab.state.settings.shape") == 0  # a choice by its name
    assert page.errors == []

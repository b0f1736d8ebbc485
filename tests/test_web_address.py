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

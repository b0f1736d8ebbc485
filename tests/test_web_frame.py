"""A frame of every view draws them interleaved (each view's JS while the GPU works on the
next one, in the order of their page modules' queue): every view's result equals the same
view drawn on its own."""

from __future__ import annotations

import pytest
from webpage import open_page

from lab.web.bench import all_views
from lab.web.browser import chromium_path

pytestmark = pytest.mark.skipif(
    chromium_path() is None, reason="Chromium is not installed (apt-get install chromium)"
)

# The largest difference between what each view holds after a whole frame and after it
# draws again on its own (its data read back, or the SH coefficients, or the albedo).
COMPARE = """() => {
  const panel = brdfLab.panel(0);
  brdfLab.renderNow();
  const held = (v) =>
    Array.from(v.data instanceof Float32Array ? v.data : v.data?.coefficients ?? v.raw ?? []);
  const out = {};
  for (const name of brdfLab.state.views) {
    const view = panel.extra[name];
    const before = held(view);
    view.render();
    const after = held(view);
    let diff = before.length === after.length ? 0 : Infinity;
    for (let k = 0; k < before.length; k++) {
      const a = before[k], b = after[k];
      const same = a === b || (Number.isNaN(a) && Number.isNaN(b));
      if (!same) diff = Math.max(diff, Math.abs(a - b));
    }
    out[name] = [before.length, diff];
  }
  return out;
}"""


# Every view but the IBL one, which goes on adding passes after a frame (tests/test_web_ibl.py).
VIEWS = ",".join(v for v in all_views().split(",") if v != "ibl")


@pytest.fixture(scope="module")
def page(tmp_path_factory):
    address = f"model=cook_torrance&m=0.3&views={VIEWS}&light=35,20"
    with open_page(tmp_path_factory, address, width=1920, height=2400) as tab:
        yield tab


def test_interleaved_frame_equals_each_view_alone(page):
    result = page.evaluate(COMPARE)
    assert set(result) == set(VIEWS.split(","))
    for name, (count, diff) in result.items():
        if name != "terms":  # drawn whole (no GPU pass to overlap)
            assert count > 0, name
        assert diff == 0, f"{name}: {diff}"
    assert page.evaluate("brdfLab.errors(0)") == ""
    assert page.errors == []

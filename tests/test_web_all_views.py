"""The page with every view, the new ones included (3D lobe, spherical harmonics, D, G, F, IBL),
at the issue's three screen sizes: nothing past the right edge; screenshots saved."""

from __future__ import annotations

import pytest

from lab.web.browser import chromium_path

pytestmark = pytest.mark.skipif(
    chromium_path() is None, reason="Chromium is not installed (apt-get install chromium)"
)

VIEWS = "lobe3d,sh,terms,slice,albedo,object,ibl"


@pytest.fixture(scope="module")
def browser(tmp_path_factory):
    from lab.web.browser import chromium
    from lab.web.site import export, serving

    site = export(tmp_path_factory.mktemp("site")).parent
    with serving(site) as url, chromium() as browser:
        browser.base_url = url
        yield browser


@pytest.mark.parametrize("width,height", [(1400, 900), (768, 1024), (390, 844)])
def test_every_view_fits(browser, output_dir, width, height):
    context = browser.new_context(
        viewport={"width": width, "height": height}, has_touch=width < 800
    )
    page = context.new_page()
    errors: list[str] = []
    page.on("pageerror", lambda e: errors.append(str(e)))
    page.on("console", lambda m: m.type == "error" and errors.append(m.text))
    try:
        page.goto(f"{browser.base_url}index.html#model=cook_torrance&model=ggx&views={VIEWS}")
        page.evaluate("window.brdfLab.ready")
        page.evaluate("brdfLab.renderNow()")
        shown = page.evaluate("[...document.querySelectorAll('.view')].map(v => v.dataset.view)")
        for name in ("3D lobe", "spherical harmonics", "microfacet terms"):
            assert shown.count(name) == 2, (name, shown)
        over = page.evaluate(
            """() => {
              const w = document.documentElement.clientWidth;
              const out = {page: document.documentElement.scrollWidth - w};
              for (const e of document.querySelectorAll('input, select, button, canvas, label')) {
                const r = e.getBoundingClientRect();
                if (r.width && r.right > w + 0.5) out[e.outerHTML.slice(0, 60)] = r.right - w;
              }
              return out;
            }"""
        )
        assert over == {"page": 0}, over
        page.screenshot(path=output_dir / f"web_all_views_{width}x{height}.png", full_page=True)
        assert errors == []
    finally:
        context.close()

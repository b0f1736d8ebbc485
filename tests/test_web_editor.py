"""The page's shader editor (CodeMirror 6, bundled from npm): live recompile, errors at the
file's own lines, the last good version keeps rendering, open/save/reset, nothing fetched
from outside the host."""

from __future__ import annotations

import base64
import json
from pathlib import Path

import numpy as np
import pytest

from lab.constants import LOOP_WARNING
from lab.models import SHADER_DIR, ModelError, load_model, parse_model
from lab.web.browser import chromium_path

pytestmark = pytest.mark.skipif(
    chromium_path() is None, reason="Chromium is not installed (apt-get install chromium)"
)

SIZE = 96
LIGHT = (30.0, 0.0)
EDITOR_DIR = Path(__file__).resolve().parents[1] / "lab" / "web" / "editor"
PHONG = (SHADER_DIR / "brdfs" / "phong.glsl").read_text()


@pytest.fixture(scope="module")
def site(tmp_path_factory):
    from lab.web.site import export

    return export(tmp_path_factory.mktemp("site")).parent


@pytest.fixture(scope="module")
def page(site):
    from lab.web.browser import chromium
    from lab.web.site import serving

    with serving(site) as url, chromium() as browser:
        viewport = {"width": 1300, "height": 900}
        context = browser.new_context(viewport=viewport, accept_downloads=True)
        tab = context.new_page()
        tab.requests = []
        tab.on("request", lambda r: tab.requests.append(r.url))
        tab.errors = []
        tab.on("console", lambda m: m.type == "error" and tab.errors.append(m.text))
        tab.on("pageerror", lambda e: tab.errors.append(str(e)))
        tab.goto(f"{url}index.html#model=phong&size={SIZE}&light={LIGHT[0]:g},{LIGHT[1]:g}")
        tab.evaluate("window.brdfLab.ready")
        tab.base_url = url
        yield tab


def sphere(page) -> np.ndarray:
    out = page.evaluate("brdfLab.readSphere(0)")
    data = np.frombuffer(base64.b64decode(out["data"]), dtype=np.float32)
    return data.reshape(out["height"], out["width"], 4)


def edit(page, text: str) -> list[dict]:
    """Types `text` into the editor as a whole and waits for the live check."""
    before = page.evaluate("brdfLab.editor.checks")
    page.evaluate("t => brdfLab.editor.editor.setText(t)", text)
    page.wait_for_function(f"brdfLab.editor.checks > {before}")
    page.evaluate("brdfLab.renderNow()")
    return page.evaluate("brdfLab.editor.editor.errors()")


def test_editor_is_codemirror_with_glsl_highlighting(page):
    page.evaluate("brdfLab.edit(0)")
    assert page.locator("#editor .cm-editor").is_visible()
    assert page.evaluate("brdfLab.editor.editor.text") == PHONG
    # The GLSL mode marks keywords and types: more than one kind of token on screen.
    classes = page.evaluate(
        "[...new Set([...document.querySelectorAll('#editor .cm-line span')]"
        ".map(s => s.className))]"
    )
    assert len([c for c in classes if c]) >= 3, classes
    assert page.errors == []


def test_live_recompile_matches_desktop(page, renderer, tmp_path):
    page.evaluate("brdfLab.edit(0)")
    edited = PHONG.replace("ks * pow(RoV, ke)", "ks * pow(RoV, ke) * vec3(1.0, 0.5, 0.25)")
    assert edit(page, edited) == []
    assert "compiles" in page.locator(".editor-status").inner_text()
    path = tmp_path / "phong.glsl"
    path.write_text(edited)
    desktop = renderer.sphere(parse_model(edited, path), {}, light=LIGHT, size=SIZE)
    web = sphere(page)
    on = desktop[..., 3] > 0
    assert np.abs(web[on] - desktop[on]).max() <= 1e-5 + 1e-3 * np.abs(desktop[on]).max()
    original = renderer.sphere(load_model("phong"), {}, light=LIGHT, size=SIZE)
    assert np.abs(web[on] - original[on]).max() > 0.01  # it really changed


def test_errors_at_the_files_lines_and_last_good_keeps_rendering(page):
    page.evaluate("brdfLab.edit(0)")
    good = PHONG.replace("ks * pow(RoV, ke)", "ks * pow(RoV, ke) * 0.5")
    assert edit(page, good) == []
    shown = sphere(page)
    lines = good.splitlines()
    line = next(i for i, t in enumerate(lines, 1) if "float RoV" in t)
    lines[line - 1] = "    float RoV = max(dot(R, V), undefined_name);"
    errors = edit(page, "\n".join(lines) + "\n")
    assert errors and {e["line"] for e in errors} == {line}, errors
    assert "undefined_name" in " ".join(e["message"] for e in errors)
    assert page.locator("#editor .cm-lintRange-error").count() >= 1
    status = page.locator(".editor-status").inner_text()
    assert f"(line {line})" in status and "last version that compiled" in status
    np.testing.assert_array_equal(sphere(page), shown)  # still the good version
    assert page.evaluate("brdfLab.errors(0)") == ""
    # A header error: the same words as the desktop lab, at the header's line.
    bad = PHONG.replace("@param ke float 1 1000 50 log", "@param ke float 1 1000 5000 log")
    errors = edit(page, bad)
    with pytest.raises(ModelError) as desktop:
        parse_model(bad, "shaders/brdfs/phong.glsl")
    assert [e["line"] for e in errors] == [desktop.value.line]
    assert errors[0]["message"] in str(desktop.value)
    np.testing.assert_array_equal(sphere(page), shown)


def test_reset_save_and_open(page, tmp_path):
    page.evaluate("brdfLab.edit(0)")
    edit(page, PHONG.replace("0.5 0.5 0.5", "0.25 0.25 0.25"))
    assert page.evaluate("brdfLab.values(0).ks") == [0.25, 0.25, 0.25]
    with page.expect_download() as info:
        page.locator("#editor button", has_text="save").click()
    assert info.value.suggested_filename == "phong.glsl"
    assert Path(info.value.path()).read_text() == page.evaluate("brdfLab.editor.editor.text")
    page.locator("#editor button", has_text="reset").click()
    assert page.evaluate("brdfLab.editor.editor.text") == PHONG
    assert page.evaluate("brdfLab.values(0).ks") == [0.5, 0.5, 0.5]
    mine = tmp_path / "mine.glsl"
    mine.write_text(PHONG.replace("kd * INV_PI", "kd * INV_PI * 0.5"))
    page.locator("#editor input[type=file]").set_input_files(str(mine))
    page.wait_for_function("brdfLab.editor.editor.text.includes('INV_PI * 0.5')")
    page.evaluate("brdfLab.editor.check()")
    assert page.evaluate("brdfLab.editor.editor.errors()") == []
    page.locator("#editor button", has_text="reset").click()
    assert page.errors == []


def test_no_request_leaves_the_host(page):
    assert page.requests, "no requests seen"
    outside = [u for u in page.requests if not u.startswith((page.base_url, "data:", "blob:"))]
    assert outside == []


def test_bundle_is_built_from_the_committed_lockfile():
    """The bundle ships in the page; its sources are pinned by package-lock.json."""
    lock = json.loads((EDITOR_DIR / "package-lock.json").read_text())
    package = json.loads((EDITOR_DIR / "package.json").read_text())
    for name in package["devDependencies"]:
        assert f"node_modules/{name}" in lock["packages"], name
    bundle = (Path(__file__).resolve().parents[1] / "lab/web/static/editor.js").read_text()
    assert "createEditor" in bundle and "cm-lintRange" in bundle


def test_loop_guard_warning_names_the_line(page):
    """A loop that does not end is stopped by the guard; the page says where."""
    page.evaluate("brdfLab.edit(0)")
    lines = PHONG.splitlines()
    at = next(i for i, t in enumerate(lines) if "float RoV" in t)
    lines.insert(at + 1, "    for (int i = 0; i >= 0; i++) { RoV *= 1.0; }")
    assert edit(page, "\n".join(lines) + "\n") == []
    warning = page.evaluate("brdfLab.loopWarning(0)")
    assert warning.startswith(f"shaders/brdfs/phong.glsl:{at + 2}: the loop at line {at + 2}")
    assert "did not end within 10,000 iterations at θo = " in warning
    # one sentence, the desktop's too: the template after {where} is the same
    assert warning.endswith(LOOP_WARNING.split("{where}")[1])
    assert page.locator(".loop-warning").is_visible()
    edit(page, PHONG)
    assert page.evaluate("brdfLab.loopWarning(0)") == ""

"""What the page keeps in the browser: opened model files survive a reload (the address
holds only their names), their editor works (a .glsl, a .brdf; a table says why not), and
the editor's unsaved text comes back after a reload, for a library model and an exercise."""

from __future__ import annotations

import base64
from pathlib import Path

import numpy as np
import pytest
from webpage import open_page

from lab.brdf_explorer import parse_brdf
from lab.measured.merl import MerlTable, write_merl
from lab.models import SHADER_DIR, parse_model
from lab.web.browser import chromium_path

pytestmark = pytest.mark.skipif(
    chromium_path() is None, reason="Chromium is not installed (apt-get install chromium)"
)

ROOT = Path(__file__).resolve().parents[1]
SIZE = 64
LIGHT = (30.0, 0.0)
PHONG = (SHADER_DIR / "brdfs" / "phong.glsl").read_text()
# A student's copy of a library model under another file name (its @model stays phong).
MINE = PHONG.replace("ks * pow(RoV, ke)", "ks * pow(RoV, ke) * vec3(1.0, 0.6, 0.3)")
TINT = """\
analytic
::begin parameters
color tint 0.8 0.4 0.2
::end parameters
::begin shader
vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) { return tint / 3.14159265; }
::end shader
"""


@pytest.fixture(scope="module")
def page(tmp_path_factory):
    with open_page(tmp_path_factory, f"model=phong&size={SIZE}&light=30,0") as tab:
        yield tab


@pytest.fixture(scope="module")
def files(tmp_path_factory) -> dict[str, Path]:
    folder = tmp_path_factory.mktemp("files")
    (folder / "my phong.glsl").write_text(MINE)
    (folder / "tint.brdf").write_text(TINT)
    rgb = np.full((4, 3, 6, 3), 0.05)
    write_merl(MerlTable.from_rgb(rgb), folder / "grey.binary")
    return {p.name: p for p in folder.iterdir()}


def sphere(page, panel: int) -> np.ndarray:
    out = page.evaluate("i => brdfLab.readSphere(i)", panel)
    data = np.frombuffer(base64.b64decode(out["data"]), dtype=np.float32)
    return data.reshape(out["height"], out["width"], 4)


def panel_names(page) -> list[str]:
    return page.evaluate("brdfLab.state.panels.map(p => p.name)")


def reload(page, address: str) -> None:
    """Opens the page afresh at `address` (the page rewrites its address as it goes)."""
    url = page.url.split("#")[0]
    page.goto("about:blank")
    page.goto(f"{url}#{address}")
    page.evaluate("brdfLab.ready")
    page.evaluate("brdfLab.renderNow()")


def edit(page, panel: int, text: str) -> list[dict]:
    """Opens the editor on `panel`, types `text` and waits for the live check."""
    page.evaluate("i => brdfLab.edit(i)", panel)
    before = page.evaluate("brdfLab.editor.checks")
    page.evaluate("t => brdfLab.editor.editor.setText(t)", text)
    page.wait_for_function(f"brdfLab.editor.checks > {before}")
    page.evaluate("brdfLab.renderNow()")
    return page.evaluate("brdfLab.editor.editor.errors()")


def test_opened_files_survive_a_reload(page, files, renderer):
    page.set_input_files("#open-file", [str(p) for p in files.values()])
    page.wait_for_function("brdfLab.state.panels.length === 4", timeout=60_000)
    assert sorted(panel_names(page)) == ["grey", "my_phong", "phong", "tint"]
    page.evaluate("brdfLab.renderNow()")
    before = {name: sphere(page, i) for i, name in enumerate(panel_names(page))}
    address = page.evaluate("location.hash.slice(1)")
    reload(page, address)
    assert sorted(panel_names(page)) == ["grey", "my_phong", "phong", "tint"]
    for i, name in enumerate(panel_names(page)):
        assert page.evaluate(f"brdfLab.errors({i})") == "", name
        np.testing.assert_array_equal(sphere(page, i), before[name], err_msg=name)
    # What they show is the files' BRDF (the desktop's render of the same file).
    i = panel_names(page).index("my_phong")
    desktop = renderer.sphere(parse_model(MINE, "my phong.glsl"), {}, light=LIGHT, size=SIZE)
    on = desktop[..., 3] > 0
    assert np.abs(sphere(page, i)[on] - desktop[on]).max() <= 1e-5 + 1e-3 * desktop[on].max()
    assert page.errors == []


def test_an_address_naming_a_file_not_opened_here_says_what_to_do(page):
    reload(page, f"model=phong&model=not_opened_here&size={SIZE}")
    notes = " ".join(page.evaluate("brdfLab.notes()"))
    assert "unknown model not_opened_here" in notes
    assert "no file of that name was opened in this browser" in notes and "open file" in notes
    assert page.locator("#notes").is_visible()
    assert panel_names(page) == ["phong"]


def test_edit_works_on_opened_glsl_and_brdf_files(page, files, app_renderer):
    reload(page, f"model=my_phong&model=tint&model=grey&size={SIZE}&light=30,0")
    # The .glsl (its @model is phong, its name my_phong): the edit applies as typed.
    page.evaluate("brdfLab.edit(0)")
    assert page.evaluate("brdfLab.editor.editor.text") == MINE
    redder = MINE.replace("vec3(1.0, 0.6, 0.3)", "vec3(1.0, 0.2, 0.1)")
    assert edit(page, 0, redder) == []
    assert "compiles" in page.locator(".editor-status").inner_text()
    desktop = app_renderer.sphere(parse_model(redder, "x.glsl"), {}, light=LIGHT, size=SIZE)
    on = desktop[..., 3] > 0
    assert np.abs(sphere(page, 0)[on] - desktop[on]).max() <= 1e-5 + 1e-3 * desktop[on].max()
    # The .brdf: the whole file is the editor's text; its lines are the file's.
    page.evaluate("brdfLab.edit(1)")
    assert page.evaluate("brdfLab.editor.editor.text") == TINT
    greener = TINT.replace("color tint 0.8 0.4 0.2", "color tint 0.1 0.9 0.2")
    assert edit(page, 1, greener) == []
    desktop = app_renderer.sphere(parse_brdf(greener, "tint.brdf"), {}, light=LIGHT, size=SIZE)
    assert np.abs(sphere(page, 1)[on] - desktop[on]).max() <= 1e-5 + 1e-3 * desktop[on].max()
    broken = TINT.replace("/ 3.14159265;", "/ 3.14159265")
    errors = edit(page, 1, broken)
    assert {e["line"] for e in errors} == {6}, errors  # the .brdf file's own line
    # The table: the edit button says why there is no text.
    page.locator("#panels .panel").nth(2).locator("button.edit").click()
    assert "numbers, not text" in page.locator("#tip-text").inner_text()
    assert page.errors == []


def test_unsaved_edits_come_back_after_a_reload(page, renderer):
    reload(page, f"model=phong&size={SIZE}&light=30,0")
    original = sphere(page, 0)
    half = PHONG.replace("ks * pow(RoV, ke)", "0.5 * ks * pow(RoV, ke)")
    assert edit(page, 0, half) == []
    edited = sphere(page, 0)
    reload(page, f"model=phong&size={SIZE}&light=30,0")
    np.testing.assert_array_equal(sphere(page, 0), edited)
    assert any("your edited version" in n for n in page.evaluate("brdfLab.notes()"))
    page.evaluate("brdfLab.edit(0)")
    assert page.evaluate("brdfLab.editor.editor.text") == half
    # Text that does not compile is kept too: the original shows, the editor has the text.
    broken = half.replace("float RoV", "float RoV = undefined_name; float x")
    assert edit(page, 0, broken)
    reload(page, f"model=phong&size={SIZE}&light=30,0")
    np.testing.assert_array_equal(sphere(page, 0), original)
    assert any("has an error" in n for n in page.evaluate("brdfLab.notes()"))
    page.evaluate("brdfLab.edit(0)")
    assert page.evaluate("brdfLab.editor.editor.text") == broken
    # Reset goes back to the library's file, and nothing is kept any more.
    page.locator("#editor button", has_text="reset").click()
    reload(page, f"model=phong&size={SIZE}&light=30,0")
    assert page.evaluate("brdfLab.notes()") == []
    np.testing.assert_array_equal(sphere(page, 0), original)


def test_an_exercise_and_its_text_come_back_after_a_reload(page):
    solution = (ROOT / "solutions" / "01_lambert" / "lambert.glsl").read_text()
    page.evaluate("n => brdfLab.openExercise(n)", "01_lambert")
    runs = page.evaluate("brdfLab.exercises.runs")
    page.evaluate("t => brdfLab.editor.editor.setText(t)", solution)
    page.wait_for_function(f"brdfLab.exercises.runs > {runs}")
    address = page.evaluate("location.hash.slice(1)")
    assert "model=01_lambert" in address
    reload(page, address)
    page.wait_for_function("brdfLab.exercises?.runs > 0", timeout=60_000)
    assert page.evaluate("brdfLab.editor.editor.text") == solution
    results = page.evaluate("brdfLab.exercises.results.map(r => r.passed)")
    assert results and all(results)
    assert page.errors == []


def test_a_file_replacing_a_library_model_says_so_and_forget_brings_it_back(page, tmp_path):
    reload(page, f"model=phong&size={SIZE}&light=30,0")
    library = sphere(page, 0)
    mine = tmp_path / "phong.glsl"
    mine.write_text(MINE)
    page.set_input_files("#open-file", str(mine))
    # Kept once the forget button names it (the browser's store writes asynchronously).
    page.wait_for_function("document.getElementById('forget-files').title.includes('phong.glsl')")
    reload(page, f"model=phong&model=tint&size={SIZE}&light=30,0")
    notes = " ".join(page.evaluate("brdfLab.notes()"))
    assert "your phong.glsl (kept in this browser) is shown instead of the library's" in notes
    assert np.abs(sphere(page, 0) - library).max() > 0.01  # the student's version
    forget = page.locator("#forget-files")
    assert forget.is_visible() and "tint.brdf" in forget.get_attribute("title")
    with page.expect_navigation():
        forget.click()
    page.evaluate("brdfLab.ready")
    page.evaluate("brdfLab.renderNow()")
    np.testing.assert_array_equal(sphere(page, 0), library)
    assert panel_names(page) == ["phong"]  # tint is no longer kept
    assert any("unknown model tint" in n for n in page.evaluate("brdfLab.notes()"))
    assert not page.locator("#forget-files").is_visible()
    assert page.errors == []


def test_slides_show_the_library_whatever_this_browser_keeps(page):
    """An embedded lab (a slide's demo) ignores the kept edits and files: a presenter's
    experiment in the lab does not change the lecture's demos."""
    reload(page, f"model=phong&size={SIZE}&light=30,0")
    original = sphere(page, 0)
    assert edit(page, 0, PHONG.replace("ks * pow(RoV, ke)", "0.25 * ks * pow(RoV, ke)")) == []
    reload(page, f"model=phong&size={SIZE}&light=30,0&embed=1")
    np.testing.assert_array_equal(sphere(page, 0), original)
    assert page.evaluate("brdfLab.notes()") == []
    reload(page, f"model=phong&size={SIZE}&light=30,0")  # the lab itself keeps the edit
    assert np.abs(sphere(page, 0) - original).max() > 0.01
    page.evaluate("brdfLab.edit(0)")
    page.locator("#editor button", has_text="reset").click()
    assert page.errors == []

"""A new view is its own files: the test-only retroreflection view (tests/extra_views, with
its page module retro.js) shows on the page, and a view added to a copy of the lab as four
files (module, template, widget, page module: tests/new_view) shows in the CLI, the
presets, the app, the page and its address, with no other edit."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from lab import views
from lab.web.browser import chromium_path

ROOT = Path(__file__).resolve().parents[1]
NEW = Path(__file__).resolve().parent / "new_view"
# Where the four files go in the copy.
PLACES = {
    "hemi_view.py": "lab/views/hemi.py",
    "hemi.glsl": "shaders/views/hemi.glsl",
    "hemi_widget.py": "lab/app/views/hemi.py",
    "hemi.js": "lab/web/static/views/hemi.js",
}

pytestmark = pytest.mark.skipif(chromium_path() is None, reason="needs Chromium")


@pytest.fixture
def extra_view():
    views.add_package("extra_views")
    yield views.view("retro")
    views._PACKAGES.remove("extra_views")
    views._cache = None


def test_the_test_only_view_draws_on_the_page(extra_view, tmp_path):
    from lab.web.browser import chromium
    from lab.web.site import export, manifest, serving

    entry = next(v for v in manifest()["views"] if v["name"] == "retro")
    assert entry["page"] == "views/retro.js" and entry["settings"]["retro_gain"]["max"] == 4.0
    site = export(tmp_path / "site").parent
    assert (site / "views" / "retro.js").is_file()
    with serving(site) as url, chromium() as browser:
        page = browser.new_page(viewport={"width": 1300, "height": 900})
        page.goto(f"{url}index.html#model=lambert&views=retro&retro_gain=2")
        page.evaluate("window.brdfLab.ready")
        flat = np.array(page.evaluate("brdfLab.readView(0, 'retro').lum"))
        page.evaluate("brdfLab.setModel(0, 'phong', {kd: [0, 0, 0]})")
        peaked = np.array(page.evaluate("brdfLab.readView(0, 'retro').lum"))
        address = page.evaluate("location.hash")
        assert page.evaluate("brdfLab.notes()") == []
    # Lambert: 2 x albedo luminance / pi at every angle; Phong's lobe: V = R only at 0°.
    np.testing.assert_allclose(flat, 2 * 0.8 / np.pi, rtol=1e-4)
    assert peaked[0] > 10 * peaked[60]
    assert "views=retro" in address and "retro_gain=2" in address


def test_a_view_of_four_files_appears_everywhere(tmp_path):
    copy = tmp_path / "lab-copy"
    copy.mkdir()
    skip = shutil.ignore_patterns("__pycache__", "node_modules", "*.pyc")
    for part in ("lab", "shaders"):
        shutil.copytree(ROOT / part, copy / part, ignore=skip)
    for part in ("exercises", "solutions", "pyproject.toml"):
        (copy / part).symlink_to(ROOT / part)
    for name, place in PLACES.items():
        shutil.copy(NEW / name, copy / place)
    env = {**os.environ, "PYTHONPATH": str(copy)}
    run = subprocess.run(
        [sys.executable, str(NEW / "drive.py")],
        cwd=copy,
        env=env,
        capture_output=True,
        text=True,
        timeout=300,
        check=False,
    )
    assert run.returncode == 0, run.stderr[-3000:]
    found = json.loads(run.stdout.splitlines()[-1])  # after the CLI's "wrote ..." lines
    assert found["lab"] == str(copy / "lab" / "__init__.py")
    assert found["views"][-1] == "hemi"
    # The CLI draws it from its template: Lambert the same everywhere, Phong's lobe not.
    assert found["cli_lambert"] == 0 and found["cli_phong"] == 0
    low, high, count = found["png_lambert"]
    assert count > 2000 and high - low <= 1
    low, high, _ = found["png_phong"]
    assert high - low > 50
    assert found["preset"] == {"hemi_gain": 4.0}  # clamped to its range
    if os.environ.get("DISPLAY"):
        assert found["dock"] and found["dock_text"] == f"peak {0.8 / np.pi:.4g} 1/sr"
    # The page: a box to show it, its setting's slider from the registry, its picture.
    assert ["hemi", True] in found["choice"]
    assert found["control"] == ["range", "0.5", "4", "2"]
    low, high, count = found["page_lambert"]
    assert count > 2000
    np.testing.assert_allclose([low, high], 2 * 0.8 / np.pi, rtol=1e-4)
    assert "views=hemi" in found["hash"] and "hemi_gain=3" in found["hash"]
    assert found["notes"] == [] and found["errors"] == []


def test_the_live_server_serves_a_plug_in_views_page_module(extra_view):
    """`brdf-lab serve` finds views/NAME.js where the registry's view is (beside a plug-in's
    module), as the exported site has it."""
    import urllib.request

    from lab.web.site import serving

    with serving() as url:
        text = urllib.request.urlopen(url + "views/retro.js").read().decode()
        page = json.loads(urllib.request.urlopen(url + "manifest.json").read())
    assert text == (ROOT / "tests" / "extra_views" / "retro.js").read_text(encoding="utf-8")
    assert {"name": "retro", "page": "views/retro.js"}.items() <= next(
        v for v in page["views"] if v["name"] == "retro"
    ).items()

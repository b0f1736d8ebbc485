"""The page asks for every module of lab.js's static import graph and for the manifest at
once (index.html's preload links): without them the browser finds the modules one import
level after another, and the manifest only once they have all run."""

from __future__ import annotations

import re
from pathlib import Path

STATIC = Path(__file__).resolve().parent.parent / "lab" / "web" / "static"
IMPORT = re.compile(r'^\s*import\s[^;]*?\sfrom\s+"\./([\w.-]+\.js)"', re.M)


def static_imports(entry: str) -> set[str]:
    """Every module `entry` imports, directly or not (dynamic import() left out)."""
    found: set[str] = set()
    todo = [entry]
    while todo:
        for name in IMPORT.findall((STATIC / todo.pop()).read_text(encoding="utf-8")):
            if name not in found and name != entry:
                found.add(name)
                todo.append(name)
    return found


def test_every_module_of_the_page_is_preloaded():
    page = (STATIC / "index.html").read_text(encoding="utf-8")
    preloaded = set(re.findall(r'<link rel="modulepreload" href="([^"]+)">', page))
    wanted = static_imports("lab.js")
    assert {"panel.js", "state.js", "header.js"} <= wanted  # the parser finds the graph
    assert preloaded == wanted, (
        f'index.html: add <link rel="modulepreload"> for {sorted(wanted - preloaded)}, '
        f"remove those for {sorted(preloaded - wanted)}"
    )
    assert "editor.js" not in preloaded  # the editor (400 kB) loads when it is opened
    # The manifest, as load() fetches it (same URL, CORS mode, no credentials across sites).
    assert '<link rel="preload" href="manifest.json" as="fetch" crossorigin="anonymous">' in page
    assert 'fetchText("manifest.json")' in (STATIC / "files.js").read_text(encoding="utf-8")

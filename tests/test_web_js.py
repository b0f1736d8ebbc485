"""The page's JavaScript held to the Python side's standard: ESLint clean, every module
under the size cap and opening with a header, no import cycles, layers that import only
downward, and no page module that names a view (views come from the registry)."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

from lab.web import jslint

pytestmark = pytest.mark.skipif(
    shutil.which("node") is None or shutil.which("npm") is None,
    reason="needs node and npm (apt-get install nodejs npm)",
)


def test_eslint_is_clean():
    findings = jslint.eslint()
    assert findings == "", f"ESLint (lab/web/lint/eslint.config.js):\n{findings}"


def test_every_module_is_under_the_cap_and_says_what_it_owns():
    found = jslint.modules()
    assert len(found) > 30  # the page, its views and the checks
    for path in found:
        lines = path.read_text(encoding="utf-8").splitlines()
        too_long = f"{path.name}: {len(lines)} lines, split it by concern"
        assert len(lines) < jslint.MAX_LINES, too_long
        assert lines[0].startswith("//"), f"{path.name}: open with a comment saying what it owns"


# The modules that restate a Python rule (the page must work alone: on files a student
# opens or edits, and in practice mode), each with the test that holds it to the Python.
MIRRORS = {
    "header.js": "test_web_mirrors.py",  # and tests/fixtures/headers via check_fixtures.mjs
    "assemble.js": "test_web_fixtures.py",
    "values.js": "test_web_mirrors.py",
    "geometry.js": "test_web_mirrors.py",
    "plotscale.js": "test_web_mirrors.py",
    "sh.js": "test_web_sh_mirror.py",
    "diagnosis.js": "test_diagnosis_shape.py",
    "flip.js": "test_web_flip.py",
    "explorer.js": "test_web_files.py",
    "measured.js": "test_web_files.py",
    "sampling.js": "test_web_exercise.py",
    "submission.js": "test_web_exercise.py",
    "properties.js": "test_web_practice.py",
    "iblcheck.js": "test_web_practice.py",
    "objectcheck.js": "test_web_practice.py",
}


def test_each_mirror_of_python_says_why_and_has_its_parity_test():
    tests = Path(__file__).resolve().parent
    for name, parity in MIRRORS.items():
        header = []
        for line in (jslint.STATIC / name).read_text(encoding="utf-8").splitlines():
            if not line.startswith("//"):
                break
            header.append(line)
        assert "Why in JavaScript too:" in "\n".join(header), f"{name}: say why it is mirrored"
        assert (tests / parity).is_file(), f"{name}: its parity test {parity} is gone"


def test_no_import_cycles():
    graph = {p.resolve(): jslint.imports(p) for p in jslint.modules()}
    done: set = set()

    def visit(node, path):
        if node in path:
            cycle = path[path.index(node) :] + [node]
            pytest.fail("import cycle: " + " -> ".join(p.name for p in cycle))
        if node in done:
            return
        for nxt in graph.get(node, []):
            visit(nxt, [*path, node])
        done.add(node)

    for node in graph:
        visit(node, [])
    assert any(graph.values())  # the parser sees imports


def test_layers_import_only_downward():
    names = {"base": 0, "views": 1, "page": 2}
    layer_of = {p.resolve(): jslint.layer(p) for p in jslint.modules()}
    assert set(layer_of.values()) == set(names.values())
    for path in jslint.modules():
        for target in jslint.imports(path):
            if target.name in jslint.BUNDLES:
                continue
            mine, theirs = jslint.layer(path), layer_of[target]
            wrong = f"{path.name} (layer {mine}) imports {target.name} (layer {theirs})"
            assert theirs <= mine, wrong
            # The page finds its views by name in the manifest: none is imported by hand.
            assert not (mine == 2 and theirs == 1), f"{path.name} imports the view {target.name}"


def test_a_cycle_and_a_wrong_layer_are_found(tmp_path, monkeypatch):
    """The graph tests can fail: two modules that import each other, a base module that
    imports a page one."""
    (tmp_path / "views").mkdir()
    (tmp_path / "a.js").write_text('// a\nimport { b } from "./b.js";\n')
    (tmp_path / "b.js").write_text('// b\nimport { a } from "./a.js";\n')
    (tmp_path / "header.js").write_text('// base\nimport { x } from "./a.js";\n')
    (tmp_path / "views" / "v.js").write_text('// a view\nimport { h } from "../header.js";\n')
    monkeypatch.setattr(jslint, "STATIC", tmp_path)
    monkeypatch.setattr(jslint, "WEB", tmp_path / "none")
    with pytest.raises(pytest.fail.Exception, match="import cycle: a.js -> b.js -> a.js"):
        test_no_import_cycles()
    with pytest.raises(AssertionError, match=r"header.js \(layer 0\) imports a.js \(layer 2\)"):
        test_layers_import_only_downward()

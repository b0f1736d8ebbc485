"""The header parser and GLSL assembly agree between Python and the web lab's JavaScript.

Both sides are checked against the same fixture files (tests/fixtures/headers/), and the
JavaScript assembly of every library model is compared with the Python one.
"""

from __future__ import annotations

import importlib.util
import itertools
import json
import shutil
import subprocess
from pathlib import Path

import pytest

from lab import glsl
from lab.models import load_model, model_names

ROOT = Path(__file__).resolve().parent.parent
FIXTURES = ROOT / "tests" / "fixtures" / "headers"
CHECKER = ROOT / "lab" / "web" / "check_fixtures.mjs"


def _regenerate_module():
    spec = importlib.util.spec_from_file_location("regenerate", FIXTURES / "regenerate.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_python_side_matches_fixtures():
    results, texts = _regenerate_module().fixture_results()
    expected = json.loads((FIXTURES / "expected.json").read_text(encoding="utf-8"))
    hint = "if the change is deliberate, run tests/fixtures/headers/regenerate.py"
    for name, entry in expected["files"].items():
        assert results["files"][name] == entry, f"{name}: Python result differs ({hint})"
    assert set(results["files"]) == set(expected["files"]), hint
    for name, text in texts.items():
        assert (FIXTURES / name).read_text(encoding="utf-8") == text, f"{name} differs ({hint})"


def test_fixtures_cover_errors_and_models():
    expected = json.loads((FIXTURES / "expected.json").read_text(encoding="utf-8"))["files"]
    errors = [e for e in expected.values() if "error" in e]
    assembly_errors = [
        v for e in expected.values() for v in e.get("assembly", {}).values() if "error" in v
    ]
    assert len(errors) >= 15 and len(assembly_errors) >= 4
    assert expected["basic.glsl"]["model"]["params"][1]["default"] == [1.0, 1.0, 1.0]
    assert expected["crlf.glsl"]["model"]["delta"] is True


# The views the page assembles as the desktop does (the object view's template includes the
# shapes file: both sides must put it in the same place).
LIBRARY_VIEWS = ("sphere", "probe", "slice", "albedo", "object")


def _library_programs() -> dict:
    """Python assembly of every library model, view and enum choice (the JS must match)."""
    programs = {}
    for name in model_names():
        model = load_model(name)
        enum_params = [p for p in model.params.values() if p.kind == "enum"]
        combos = itertools.product(*[p.choices for p in enum_params]) if enum_params else [()]
        for combo in combos:
            enums = {p.name: c for p, c in zip(enum_params, combo, strict=True)}
            tag = ",".join(f"{k}={v}" for k, v in enums.items())
            for view in LIBRARY_VIEWS:
                source = glsl.assemble_fragment(model, view, target="300es", enums=enums)
                programs[f"{name}/{view}/{tag}"] = {
                    "text": source.text,
                    "origins": _regenerate_module().runs(source.origins),
                }
    return programs


@pytest.mark.skipif(shutil.which("node") is None, reason="node is not installed (apt nodejs)")
def test_javascript_side_matches_fixtures_and_python(tmp_path):
    library = tmp_path / "library.json"
    library.write_text(json.dumps(_library_programs()), encoding="utf-8")
    run = subprocess.run(
        ["node", str(CHECKER), str(library)], capture_output=True, text=True, timeout=60
    )
    assert run.stdout, run.stderr
    report = json.loads(run.stdout)
    assert report["mismatches"] == [], json.dumps(report["mismatches"][:3], indent=1)[:3000]
    assert run.returncode == 0
    assert report["checked"] == len(list(FIXTURES.glob("*.glsl"))) - len(
        list(FIXTURES.glob("*.assembled.glsl"))
    )
    assert report["library"] >= len(LIBRARY_VIEWS) * len(model_names())

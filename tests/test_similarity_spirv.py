"""Similarity on optimised SPIR-V (lab/grading/spirv.py): a copy of the solution with a
dummy statement between its lines and new variable names scores 1.00 (tokens: 0.21 to
0.92), the library's lobe sampler inlined by hand matches the library's own code, and
independent rewrites stay below the threshold (0.32 to 0.65 measured). Without spirv-opt the
report falls back to tokens and says so."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from lab.grading import similarity, spirv
from lab.grading.exercise import find_exercises, load_exercise

ROOT = Path(__file__).resolve().parent.parent
FIXTURES = ROOT / "tests" / "fixtures" / "similarity"
EXERCISES = {e.name: e for e in find_exercises(ROOT / "exercises")}
needs_tools = pytest.mark.skipif(not spirv.available(), reason="spirv-tools not installed")


def disguised(text: str) -> str:
    """The copy: new names for the usual variables and a dead statement after each line."""
    for old, new in {"NoL": "a1", "NoV": "a2", "NoH": "a3", "VoH": "a4", "H": "hh"}.items():
        text = re.sub(rf"\b{old}\b", new, text)
    out, depth = [], 0
    for number, line in enumerate(text.splitlines()):
        out.append(line)
        depth += line.count("{") - line.count("}")
        if depth > 0 and line.rstrip().endswith(";") and "return" not in line:
            out.append(f"    float unused{number} = {number}.0 * 2.0;")
    return "\n".join(out) + "\n"


def documents(exercise, texts: dict[str, str]) -> dict[str, similarity.Document]:
    stub = exercise.stub.read_text(encoding="utf-8")
    base = set(similarity.fingerprints(stub))
    docs = {name: similarity.document(name, name, text, base) for name, text in texts.items()}
    for doc in similarity.spirv_library(exercise, base):
        docs["library"] = doc
    similarity.add_features(exercise, stub, list(docs.values()))
    return docs


@needs_tools
@pytest.mark.parametrize("name", sorted(EXERCISES))
def test_a_disguised_copy_scores_high(name):
    exercise = EXERCISES[name]
    solution = exercise.solution.read_text(encoding="utf-8")
    docs = documents(exercise, {"solution": solution, "copy": disguised(solution)})
    assert docs["copy"].features, "the copy compiles"
    assert similarity.score(docs["solution"], docs["copy"]) >= 0.9


@needs_tools
def test_independent_rewrites_stay_below_the_threshold_and_inlining_shows():
    sampling = EXERCISES["10_importance_sampling"]
    texts = {f.stem: f.read_text(encoding="utf-8") for f in FIXTURES.glob("*10*.glsl")}
    texts["solution"] = sampling.solution.read_text(encoding="utf-8")
    docs = documents(sampling, texts)
    assert similarity.score(docs["inlined10"], docs["library"]) >= 0.9
    for a, b in [("honest10a", "honest10b"), ("honest10a", "solution"), ("honest10b", "solution")]:
        assert similarity.score(docs[a], docs[b]) < similarity.SPIRV_THRESHOLD, (a, b)
    for name in ("honest10a", "honest10b"):
        assert similarity.score(docs[name], docs["library"]) < similarity.SPIRV_THRESHOLD
    cook = EXERCISES["09_cook_torrance"]
    texts = {f.stem: f.read_text(encoding="utf-8") for f in FIXTURES.glob("*09*.glsl")}
    texts["solution"] = cook.solution.read_text(encoding="utf-8")
    docs = documents(cook, texts)
    for a, b in [("honest09a", "honest09b"), ("honest09a", "solution"), ("honest09b", "solution")]:
        assert similarity.score(docs[a], docs[b]) < similarity.SPIRV_THRESHOLD, (a, b)


@needs_tools
def test_the_class_report_lists_the_disguised_copy_and_the_inlined_library():
    exercise = load_exercise(ROOT / "exercises" / "10_importance_sampling")
    solution = exercise.solution.read_text(encoding="utf-8")
    files = {
        "copier": {exercise.name: (disguised(solution), None)},
        "inliner": {exercise.name: ((FIXTURES / "inlined10.glsl").read_text("utf-8"), None)},
        "honest": {exercise.name: ((FIXTURES / "honest10a.glsl").read_text("utf-8"), None)},
    }
    pairs = {(m.a.owner, m.b.owner, m.method) for m in similarity.compare_class(files, [exercise])}
    assert ("copier", "solution", "SPIR-V") in pairs
    assert ("inliner", "library", "SPIR-V") in pairs
    assert not any("honest" in pair[:2] for pair in pairs), pairs


def test_without_spirv_tools_the_report_uses_tokens_and_says_so(monkeypatch, tmp_path):
    monkeypatch.setattr(spirv, "available", lambda: False)
    exercise = load_exercise(ROOT / "exercises" / "03_blinn_phong")
    library = (ROOT / "shaders" / "brdfs" / "blinn_phong.glsl").read_text(encoding="utf-8")
    files = {"copier": {exercise.name: (library, None)}}
    matches = similarity.compare_class(files, [exercise])
    assert matches and all(m.method == "tokens" for m in matches)
    assert "tokens only (spirv-opt or glslangValidator is not installed" in (
        similarity.method_note()
    )
    similarity.write_html(matches, tmp_path / "s.html")
    assert "tokens only" in (tmp_path / "s.html").read_text(encoding="utf-8")

"""The unfinished exercise file (the stub), the commonest wrong submission, is told that its
TODO steps are not done, not a stored mistake whose values it happens to give (02's stub
was told that R points the wrong way, 07's to take the min of masking and shadowing)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from lab.cli import main
from lab.grading import mistakes
from lab.grading.exercise import find_exercises

ROOT = Path(__file__).resolve().parent.parent
EXERCISES = find_exercises(ROOT / "exercises")


def likely(output: str) -> str:
    return output.split("Likely: ", 1)[1].split("\n")[0] if "Likely: " in output else ""


@pytest.mark.parametrize("seed", [None, 7], ids=["committed", "hidden"])
def test_every_stub_is_told_its_todos_are_not_done(tmp_path, seed):
    said = {}
    for exercise in EXERCISES:
        out = tmp_path / f"{exercise.name}.json"
        extra = [] if seed is None else ["--seed", str(seed)]
        main(["grade", str(exercise.folder), "--json", str(out), *extra])
        failed = [t for t in json.loads(out.read_text())["tests"] if t["status"] != "passed"]
        assert failed, exercise.name  # a stub passes nothing worth mentioning
        said[exercise.name] = {likely(t["output"]) for t in failed}
    stub = mistakes.STUB_HINT
    for name, sentences in said.items():
        # Every failed check names the stub, or (hidden mode: a check whose random
        # settings the stored stub's values do not cover) nothing wrong instead.
        assert sentences <= {f"{stub}.", ""} and f"{stub}." in sentences, (name, sentences)


def test_the_stub_is_stored_with_the_hints_not_read_from_the_folder():
    """At grading time the exercise's file may be the student's own: the stub's text comes
    from the references, written when they were made from the course's pristine stub."""
    for exercise in EXERCISES:
        variants = mistakes.variants(exercise, exercise.solution.read_text(encoding="utf-8"))
        first = variants[0]
        assert first.key == mistakes.STUB, exercise.name
        assert first.code == exercise.stub.read_text(encoding="utf-8"), exercise.name

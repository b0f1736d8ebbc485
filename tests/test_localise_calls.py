"""The trace names two more kinds of slip by values (lab.grading.calls): another function
called on the solution's arguments (min for max), and a wrong constant, told by the named
factor it leaves where it is used (2π for π: half the solution's value)."""

from __future__ import annotations

from pathlib import Path

import pytest

from lab.grading.calls import arguments
from lab.grading.exercise import find_exercises
from lab.grading.runner import Pool, Task

ROOT = Path(__file__).resolve().parent.parent
EXERCISES = {e.name: e for e in find_exercises(ROOT / "exercises")}


def test_arguments_split_at_top_level_commas_only():
    assert arguments("float NoH = min(dot(N, H), 0.0);", "min") == ["dot(N, H)", "0.0"]
    assert arguments("acos(clamp(c, 0.0, 1.0))", "acos") == ["clamp(c, 0.0, 1.0)"]
    assert arguments("pow(x, ke)", "max") is None


def grade(tmp_path: Path, exercise: str, edits: list[tuple[str, str]]) -> list[str]:
    ex = EXERCISES[exercise]
    text = ex.solution.read_text(encoding="utf-8")
    for old, new in edits:
        assert old in text, old
        text = text.replace(old, new)
    path = tmp_path / exercise / ex.student_file
    path.parent.mkdir(parents=True)
    path.write_text(text, encoding="utf-8")
    task = Task(ex, path)
    with Pool(1, timeout=30.0) as pool:
        pool.run([task])
    assert task.score < task.max_score
    return [r.diagnosis for r in task.checks() if r.diagnosis]


@pytest.mark.parametrize(
    ("exercise", "edits", "said", "unsaid"),
    [
        (
            "03_blinn_phong",
            [("max(dot(N, H), 0.0)", "min(dot(N, H), 0.0)")],
            "calls min(…) where the solution calls max(…) with the same arguments",
            "",
        ),
        (
            "01_lambert",
            [("return albedo * INV_PI;", "float sr = 2.0 * PI;\n    return albedo / sr;")],
            "is 1/2 × albedo",
            "calls",
        ),
        (  # one argument for three: acos(x) is not clamp(x, 0, 1) misnamed
            "08_fresnel",
            [("float c = clamp(VoH, 0.0, 1.0);", "float c = acos(clamp(VoH, 0.0, 1.0));")],
            "",
            "where the solution calls",
        ),
    ],
    ids=["min for max", "2 pi", "angle for cosine"],
)
def test_slips_named_by_values(tmp_path, exercise, edits, said, unsaid):
    hints = grade(tmp_path, exercise, edits)
    assert hints, "a wrong submission gets a hint"
    if said:
        assert any(said in h for h in hints), hints
    if unsaid:
        assert not any(unsaid in h for h in hints), hints


def test_several_lights_are_told_apart_light_by_light(tmp_path):
    """Radiance is linear in the lights: exercise 04 with the ambient term added once per
    light is told that the ambient light alone differs while every light alone matches."""
    wrong = [
        ("vec3 color = ka * ambient;", "vec3 color = vec3(0.0);"),
        (
            "        if (l >= count) break;\n",
            "        if (l >= count) break;\n        color += ka * ambient;\n",
        ),
    ]
    hints = grade(tmp_path, "04_phong_illumination", wrong)
    told = [h for h in hints if "light by light" in h.lower()]
    assert told and all("the ambient light alone differs" in h for h in told), hints

"""Hidden mode's diagnosis: the likely wrong programs are rendered live at the random
settings, so a mistake the committed settings cannot show is named too.

08's f0.r mistake (a scalar where the colour f0 belongs) is invisible wherever f0 is grey:
its committed probe.schlick check uses f0 = 0.04 in all three channels. Hidden mode draws
a coloured f0 there, the check fails, and the stored mistake's own hint is named.
"""

from __future__ import annotations

import shutil
from pathlib import Path

import numpy as np

from lab.grading import diagnosis, mistakes
from lab.grading.exercise import find_exercises
from lab.grading.runner import Pool, Task

ROOT = Path(__file__).resolve().parent.parent
SCALAR_F0 = (
    "return f0 + (vec3(1.0) - f0) * (k2 * k2 * k);",
    "return vec3(f0.r + (1.0 - f0.r) * (k2 * k2 * k));",
)


def graded(exercise, text: str, folder: Path, seed: int | None) -> Task:
    path = folder / f"seed{seed}" / exercise.student_file
    path.parent.mkdir(parents=True)
    path.write_text(text, encoding="utf-8")
    task = Task(exercise, path, seed=seed)
    with Pool(1, timeout=30.0) as pool:
        pool.run([task])
    return task


def f0_hint(exercise) -> str:
    hints = mistakes.read_hints(exercise)
    return next(h for h in hints.values() if "f0.r" in h)


def test_a_check_the_committed_settings_pass_is_diagnosed_in_hidden_mode(tmp_path):
    """At the committed settings probe.schlick passes (the student's values match no stored
    variant there: the mistake has none for that check); in hidden mode it fails and the
    known mistake rendered live at the drawn f0 names it."""
    exercise = next(e for e in find_exercises(ROOT / "exercises") if e.name == "08_fresnel")
    with np.load(exercise.references / mistakes.VALUES) as data:
        key = next(k for k, h in mistakes.read_hints(exercise).items() if "f0.r" in h)
        assert f"probe.schlick|{key}" not in data.files  # nothing stored to match there
    wrong = exercise.solution.read_text(encoding="utf-8").replace(*SCALAR_F0)
    committed = graded(exercise, wrong, tmp_path, None)
    assert committed.results["probe.schlick"].passed
    hidden = graded(exercise, wrong, tmp_path, 5)
    schlick = hidden.results["probe.schlick"]
    assert not schlick.passed, schlick.message
    assert schlick.diagnosis.startswith(diagnosis.sentence(f0_hint(exercise))), schlick.message


def test_a_mistake_no_committed_check_shows_is_kept_and_named_in_hidden_mode(tmp_path):
    """An exercise whose every check has a grey f0: the references keep the f0.r mistake
    all the same (hidden mode's draws show it), with no stored values; the committed
    checks give it full marks, and hidden mode names it on the checks it fails."""
    for part in ("exercises", "solutions"):
        shutil.copytree(ROOT / part / "08_fresnel", tmp_path / part / "08_fresnel")
    folder = tmp_path / "exercises" / "08_fresnel"
    shutil.rmtree(folder / "references")
    (folder / "references").mkdir()
    toml = folder / "exercise.toml"
    blocks = toml.read_text(encoding="utf-8").split("[[checks]]")
    toml.write_text("[[checks]]".join(b for b in blocks if "schlick_metal" not in b), "utf-8")
    (tmp_path / "solutions" / "08_fresnel" / mistakes.MISTAKES_FILE).write_text(
        f"[[mistake]]\nedits = [['{SCALAR_F0[0]}', '{SCALAR_F0[1]}']]\n"
        'hint = "f0 is a colour: use all three channels, not f0.r"\n',
        encoding="utf-8",
    )
    from lab.grading.references import make_references

    make_references(tmp_path / "exercises")
    (exercise,) = find_exercises(tmp_path / "exercises")
    assert mistakes.read_hints(exercise)["mistake.0"] == f0_hint(exercise)
    with np.load(exercise.references / mistakes.VALUES) as data:
        assert not [k for k in data.files if k.endswith("|mistake.0")]  # none to store
    wrong = exercise.solution.read_text(encoding="utf-8").replace(*SCALAR_F0)
    assert graded(exercise, wrong, tmp_path, None).passed
    hidden = graded(exercise, wrong, tmp_path, 5)
    failed = [r for r in hidden.checks() if not r.passed]
    assert failed, "hidden mode's draw shows no coloured f0"
    named = [r for r in failed if r.diagnosis.startswith(diagnosis.sentence(f0_hint(exercise)))]
    assert named, [r.message for r in failed]


def test_a_sampler_mistake_is_named_in_hidden_mode_by_its_fingerprint(tmp_path):
    """10's checks are matched by the sampler's fingerprint (samples and pdf at fixed
    inputs) at the drawn settings: the half circle of φ gets its stored hint on every
    failed check; the solution itself, in hidden mode, passes with no diagnosis."""
    exercise = next(
        e for e in find_exercises(ROOT / "exercises") if e.name == "10_importance_sampling"
    )
    solution = exercise.solution.read_text(encoding="utf-8")
    hidden = graded(exercise, solution.replace("2.0 * PI * u.y", "u.y * PI"), tmp_path, 3)
    failed = [r for r in hidden.checks() if not r.passed]
    assert failed and all("whole circle" in r.diagnosis for r in failed), [
        r.message for r in failed
    ]
    right = graded(exercise, solution, tmp_path / "right", 3)
    assert right.passed and not [r.diagnosis for r in right.checks() if r.diagnosis]

"""The diagnosis of a failed check, with the renders it needs (runs in the grading worker).

Order of evidence, best first: a known mistake or single-edit mutant whose values the
student's match (its hint); which declared term is wrong and the shape of its error; the
shape of the whole error; L and V or the X and Y axes swapped; the lobe's peak or width.
Nothing matches: nothing is said.
"""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import numpy as np

from lab.glsl import ShaderCompileError
from lab.grading import diagnosis, mistakes
from lab.grading.checks import Grader, expected_value, render
from lab.grading.exercise import Check, Exercise, ExerciseError, SubmissionError, build_model
from lab.grading.kinds import kind_of
from lab.models import Model, ModelError


def differs(check: Check, values: np.ndarray, reference: np.ndarray) -> bool:
    """Would these values fail the check against the reference?"""
    return kind_of(check).differs(check, values, reference)


# -- references: the variants' values, rendered from the solution ----------------------------
def make_diagnosis(exercise: Exercise, grader: Grader) -> list[Path]:
    """Write references/diagnosis.npz and diagnosis.json (hints and terms) for an exercise."""
    solution = exercise.solution.read_text(encoding="utf-8")
    references = {
        c.name: expected_value(render(grader.renderer, grader.solution_model(exercise), c), c)
        for c in exercise.checks
    }
    values: dict[str, np.ndarray] = {}
    hints: dict[str, str] = {}
    kept: list[dict[str, np.ndarray]] = []
    by_name = {c.name: c for c in exercise.checks}
    for variant in mistakes.variants(exercise, solution):
        model = _variant_model(exercise, variant, solution)
        if model is None:
            if variant.key.startswith("mistake."):
                raise ExerciseError(f"{mistakes.mistakes_file(exercise)}: {variant.key} fails")
            continue
        mine = {}
        for check in exercise.checks:
            try:
                got = expected_value(render(grader.renderer, model, check), check)
            except (ShaderCompileError, ModelError):
                mine = {}
                break
            if differs(check, got, references[check.name]):
                mine[check.name] = got
        duplicate = any(
            mine.keys() == other.keys()
            and all(not differs(by_name[n], mine[n], other[n]) for n in mine)
            for other in kept
        )
        if not mine or (duplicate and variant.key.startswith("mutant.")):
            continue
        kept.append(mine)
        hints[variant.key] = variant.hint
        values.update({f"{name}|{variant.key}": v for name, v in mine.items()})
    terms = mistakes.declared_terms(exercise)
    model = grader.solution_model(exercise)
    for check in exercise.checks:
        if not kind_of(check).diagnose_terms:
            continue
        for name, spec in terms.items():
            params, defines, _ = mistakes.term_parts(spec)
            term_check = replace(check, params={**check.params, **params})
            term_model = mistakes.with_defines(model, defines)
            values[f"{check.name}|term.{name}"] = render(grader.renderer, term_model, term_check)
    folder = exercise.references
    np.savez_compressed(folder / mistakes.VALUES, **values)
    return [folder / mistakes.VALUES, mistakes.write_hints(exercise, hints, terms)]


def _finest(wrong: list[str], right: list[str], parent: dict[str, str]):
    """The terms to name: a term's factors (D, G, F within "specular") where some of them
    are right; the term itself where all are wrong (what they share is wrong); a right
    term's factors go unsaid."""
    for whole in {p for p in parent.values() if p}:
        parts = [t for t, p in parent.items() if p == whole]
        if whole in right:
            right = [t for t in right if t not in parts]
        elif whole in wrong and parts and all(t in wrong for t in parts):
            wrong = [t for t in wrong if t not in parts]
        elif whole in wrong:
            wrong = [t for t in wrong if t != whole]
    return wrong, right


def _variant_model(exercise: Exercise, variant: mistakes.Variant, solution: str) -> Model | None:
    try:
        return build_model(exercise, exercise.solution, variant.apply(solution))
    except (SubmissionError, ExerciseError, ModelError):
        return None


# -- grading: explain one failed check ------------------------------------------------------
class Explainer:
    """Per worker: the stored variant values and the live-rendered variants, cached."""

    def __init__(self, grader: Grader) -> None:
        self.grader = grader
        self._stored: dict[Path, dict[str, np.ndarray]] = {}
        self._models: dict[tuple[Path, str], Model | None] = {}
        self._variants: dict[Path, list[mistakes.Variant]] = {}
        self._solution_code: dict[Path, str] = {}

    def variants(self, exercise: Exercise) -> list[mistakes.Variant]:
        """Known mistakes and single-edit mutants of the solution (hidden mode renders
        them live), made once per worker."""
        path = exercise.solution
        if path not in self._variants:
            self._solution_code[path] = path.read_text(encoding="utf-8")
            self._variants[path] = mistakes.variants(exercise, self._solution_code[path])
        return self._variants[path]

    def stored(self, exercise: Exercise) -> dict[str, np.ndarray]:
        folder = exercise.references
        if folder not in self._stored:
            path = folder / mistakes.VALUES
            try:
                with np.load(path) as data:
                    self._stored[folder] = {k: data[k] for k in data.files}
            except (OSError, ValueError):
                self._stored[folder] = {}
        return self._stored[folder]

    def candidates(
        self, exercise: Exercise, check: Check, live: bool, model: Model | None = None
    ) -> dict[str, np.ndarray]:
        """The variants' values for this check: stored, or (hidden mode) rendered now.

        Hidden mode renders live only the variant (known mistake or generated mutant) that
        the student's program matches at the check's committed settings, where the stored
        values are: one compile, not one per variant, within grade-bench's budget."""
        if not live:
            prefix = f"{check.name}|"
            return {
                k[len(prefix) :]: v
                for k, v in self.stored(exercise).items()
                if k.startswith(prefix) and not k.startswith(prefix + "term.")
            }
        original = next((c for c in exercise.checks if c.name == check.name), None)
        kept = mistakes.read_hints(exercise)  # the variants the references kept
        stored = self.candidates(exercise, original, False) if original else {}
        stored = {k: v for k, v in stored.items() if k in kept}
        if not stored or model is None:
            return {}
        kind = kind_of(original)
        try:
            mine = kind.stored(render(self.grader.renderer, model, original), original)
            want = self.grader.expected(exercise, original, live=False)
        except (ShaderCompileError, ModelError, OSError, KeyError):
            return {}
        key = kind.nearest(original, mine, want, stored)
        variant = next((v for v in self.variants(exercise) if v.key == key), None)
        if variant is None:
            return {}
        cached = (exercise.solution, variant.key)
        if cached not in self._models:
            solution = self._solution_code[exercise.solution]
            self._models[cached] = _variant_model(exercise, variant, solution)
        if self._models[cached] is None:
            return {}
        try:
            raw = render(self.grader.renderer, self._models[cached], check)
        except (ShaderCompileError, ModelError):
            return {}
        return {variant.key: expected_value(raw, check)}

    def explain(
        self,
        exercise: Exercise,
        check: Check,
        model: Model,
        expected: np.ndarray,
        raw: np.ndarray,
        live: bool,
    ) -> str:
        """'Likely: ...' for a failed check, or '' when the evidence names nothing."""
        hints = mistakes.read_hints(exercise)
        kind = kind_of(check)
        got = kind.stored(raw, check)  # the form of the reference and the variants' values
        candidates = {
            k: v
            for k, v in self.candidates(exercise, check, live, model).items()
            if k in hints and (not live or kind.differs(check, v, expected))
        }
        key = kind.nearest(check, got, expected, candidates)
        if key:
            return diagnosis.sentence(hints[key])
        return diagnosis.sentence(kind.explain(self, exercise, check, model, expected, got, live))

    def terms(
        self, exercise: Exercise, check: Check, model: Model, angles: np.ndarray, live: bool
    ) -> str:
        """Evaluate each declared term alone; name the wrong one and the shape of its error.

        A term seen through macros (D with G and F made 1) counts only where the student's
        code calls what the macros replace."""
        terms = mistakes.read_terms(exercise)
        if len(terms) < 2:
            return ""
        wrong, right, detail, parent = [], [], {}, {}
        for name, spec in terms.items():
            params, defines, within = mistakes.term_parts(spec)
            if defines and not mistakes.calls_all(model.code, defines):
                continue
            parent[name] = within
            term_check = replace(check, params={**check.params, **params})
            if live:
                solution = mistakes.with_defines(self.grader.solution_model(exercise), defines)
                want = render(self.grader.renderer, solution, term_check)
            else:
                want = self.stored(exercise).get(f"{check.name}|term.{name}")
                if want is None:
                    return ""
            mine = render(self.grader.renderer, mistakes.with_defines(model, defines), term_check)
            if diagnosis.within(check, mine, want, slack=1.0).all():
                right.append(name)
            else:
                wrong.append(name)
                detail[name] = diagnosis.shape(term_check, angles, want, mine) or kind_of(
                    check
                ).lobe(term_check, angles, want, mine)
        wrong, right = _finest(wrong, right, parent)
        if not wrong or not right:
            return ""
        return diagnosis.terms_sentence(
            wrong, right, detail.get(wrong[0], "") if len(wrong) == 1 else ""
        )

    def swaps(self, check: Check, model: Model, angles: np.ndarray, expected) -> str:
        """L and V exchanged, or the tangent axes X and Y: render the swap and compare."""
        renderer = self.grader.renderer
        got = renderer.eval_angles(model, check.params, angles)
        if diagnosis.same(check, got, expected):
            return ""  # nearly right: a swap would look right too, and say nothing
        swapped = renderer.eval_angles(model, check.params, angles[:, [2, 3, 0, 1]])
        if diagnosis.same(check, swapped, expected) and not diagnosis.same(check, swapped, got):
            return (
                "your BRDF(L, V) gives the solution's BRDF(V, L) — L and V are swapped "
                "somewhere (the solution is not symmetric in them)"
            )
        mirrored = angles.copy()
        mirrored[:, [1, 3]] = (90.0 - angles[:, [1, 3]]) % 360.0
        axes = renderer.eval_angles(model, check.params, mirrored)
        if diagnosis.same(check, axes, expected) and not diagnosis.same(check, axes, got):
            return "the X and Y axes are swapped — alpha_x belongs with X, alpha_y with Y"
        return ""

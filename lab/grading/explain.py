"""The diagnosis of a failed check, with the renders it needs (runs in the grading worker).

Order of evidence, best first: a known mistake or single-edit mutant whose values the
student's match (its hint); which declared term is wrong and the shape of its error; the
shape of the whole error; L and V or the X and Y axes swapped; the lobe's peak or width.
Nothing matches: nothing is said.
"""

from __future__ import annotations

import os
import traceback
from dataclasses import replace
from pathlib import Path

import numpy as np

from lab.glsl import ShaderCompileError
from lab.grading import diagnosis, mistakes, superpose
from lab.grading.checks import Grader, expected_value, hidden_variant, render
from lab.grading.evidence import Located, TraceEvidence
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
    kept: list[tuple[str, dict[str, np.ndarray]]] = []  # (variant key, its failing values)
    hidden_only: list[list[np.ndarray]] = []
    by_name = {c.name: c for c in exercise.checks}
    # The unfinished file, read here where it is the course's own (see mistakes.variants).
    stub = exercise.stub.read_text(encoding="utf-8") if exercise.stub.is_file() else ""
    variants = mistakes.variants(exercise, solution, stub if stub != solution else "")
    for variant in variants:
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
        twin = next(
            (
                key
                for key, other in kept
                if mine.keys() == other.keys()
                and all(not differs(by_name[n], mine[n], other[n]) for n in mine)
            ),
            None,
        )
        if not mine:  # the same as the solution at every committed setting
            seen = _hidden_values(exercise, grader, model)
            if seen and not any(_same_values(seen, other) for other in hidden_only):
                hidden_only.append(seen)  # it shows under hidden mode's random settings
                hints[variant.key] = variant.hint
            continue
        if twin == mistakes.STUB:
            # Alike with the stub: the stub's hint stands (it is the likelier cause), and
            # names a stored mistake that may be the student's too.
            if variant.key.startswith("mistake."):
                hints[twin] = mistakes.either(hints[twin], variant.hint)
            continue
        if twin and variant.key.startswith("mutant."):
            # Two edits that behave alike: the student may have made either (2 N·H / N·H
            # and 2 V·H / V·H), so a generated hint names both; a stored one stands.
            if twin.startswith("mutant."):
                hints[twin] = mistakes.either(hints[twin], variant.hint)
            continue
        kept.append((variant.key, mine))
        hints[variant.key] = variant.hint
        values.update({f"{name}|{variant.key}": v for name, v in mine.items()})
    values.update(_fingerprints(exercise, grader, [v for v in variants if v.key in hints]))
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
    stored_stub = stub if mistakes.STUB in hints else ""
    return [folder / mistakes.VALUES, mistakes.write_hints(exercise, hints, terms, stored_stub)]


FINGERPRINT = "fingerprint"  # stored as fingerprint|<variant key> and fingerprint|solution


def _fingerprints(exercise: Exercise, grader: Grader, variants: list) -> dict[str, np.ndarray]:
    """For a kind whose live values describe the program (a sampler's fingerprint): each
    kept variant's and the solution's at the first such check's committed settings, which
    hidden mode compares the student's with to pick the plausible variants."""
    fixed = next((c for c in exercise.checks if kind_of(c).by_program), None)
    if fixed is None:
        return {}
    kind, solution = kind_of(fixed), exercise.solution.read_text(encoding="utf-8")
    out = {
        f"{FINGERPRINT}|solution": kind.live_values(
            grader.renderer, grader.solution_model(exercise), fixed
        )
    }
    for variant in variants:
        model = _variant_model(exercise, variant, solution)
        if model is not None:
            out[f"{FINGERPRINT}|{variant.key}"] = kind.live_values(grader.renderer, model, fixed)
    return out


HIDDEN_DRAWS = (1, 2, 3)  # seeds of hidden mode tried on a variant the committed checks miss


def _hidden_values(exercise: Exercise, grader: Grader, model: Model) -> list[np.ndarray]:
    """A variant's live values at a few of hidden mode's draws ([] when it fails no check
    there: then it is no mistake hidden mode could name, perhaps an equivalent program)."""
    solution, values, fails = grader.solution_model(exercise), [], False
    for seed in HIDDEN_DRAWS:
        for index, check in enumerate(exercise.checks):
            drawn = hidden_variant(check, solution, seed, index)
            kind = kind_of(drawn)
            try:
                mine = expected_value(render(grader.renderer, model, drawn), drawn)
                live = kind.live_values(grader.renderer, model, drawn) if kind.by_program else mine
            except (ShaderCompileError, ModelError):
                return []
            want = expected_value(render(grader.renderer, solution, drawn), drawn)
            fails = fails or kind.differs(drawn, mine, want)
            values.append(live)
    return values if fails else []


def _same_values(a: list[np.ndarray], b: list[np.ndarray]) -> bool:
    return all(
        x.shape == y.shape and np.allclose(x, y, rtol=1e-3, atol=1e-4, equal_nan=True)
        for x, y in zip(a, b, strict=True)
    )


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
        return build_model(exercise, exercise.solution, variant.apply(solution), trusted=True)
    except (SubmissionError, ExerciseError, ModelError):
        return None


# -- grading: explain one failed check ------------------------------------------------------
class Explainer(TraceEvidence):
    """Per worker: the stored variant values and the live-rendered variants, cached."""

    def __init__(self, grader: Grader) -> None:
        self.grader = grader
        self._stored: dict[Path, dict[str, np.ndarray]] = {}
        self._models: dict[tuple[Path, str], Model | None] = {}
        self._variants: dict[Path, list[mistakes.Variant]] = {}
        self._solution_code: dict[Path, str] = {}
        self._matched: dict[tuple[Path, str], str | None] = {}
        self._shown: dict[tuple[Path, str], dict[str, np.ndarray]] = {}
        self._traces: dict = {}  # programs traced (lab.grading.evidence)
        self._elsewhere: dict[tuple, np.ndarray] = {}  # the program at other checks' settings

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

    def candidates(self, exercise: Exercise, check: Check) -> dict[str, np.ndarray]:
        """The stored values of the variants the references kept, for this check."""
        prefix = f"{check.name}|"
        return {
            k[len(prefix) :]: v
            for k, v in self.stored(exercise).items()
            if k.startswith(prefix) and not k.startswith(prefix + "term.")
        }

    def variant_model(self, exercise: Exercise, variant: mistakes.Variant) -> Model | None:
        """A variant built once per worker (None: it does not build)."""
        cached = (exercise.solution, variant.key)
        if cached not in self._models:
            self.variants(exercise)
            solution = self._solution_code[exercise.solution]
            self._models[cached] = _variant_model(exercise, variant, solution)
        return self._models[cached]

    def elsewhere(self, exercise: Exercise, check: Check, model: Model, key: str) -> bool:
        """Does the program agree with variant `key` at the committed settings of the other
        checks of this kind where the variant fails? One subject can make two mistakes give
        the same values (a cosine of V where cos θL belongs and f(V, L) on a model with the
        cosine inside): a variant the program matches on that check alone is not its
        mistake. Kinds whose renders are cheap opt in (`confirm_elsewhere`)."""
        kind, stored = kind_of(check), self.stored(exercise)
        for other in exercise.checks:
            theirs = stored.get(f"{other.name}|{key}")
            if other.name == check.name or kind_of(other) is not kind or theirs is None:
                continue
            want = self.grader.expected(exercise, other, live=False)
            if want is None or kind.live_same(other, theirs, want):
                continue  # the variant passes there: that check cannot tell
            memo = (exercise.references, other.name, model.code)
            if memo not in self._elsewhere:
                if len(self._elsewhere) >= 256:
                    self._elsewhere.clear()
                self._elsewhere[memo] = kind.live_values(self.grader.renderer, model, other)
            if kind.nearest(other, self._elsewhere[memo], want, {key: theirs}) != key:
                return False
        return True

    def live(self, exercise: Exercise, check: Check, model: Model, got, expected) -> str | None:
        """Hidden mode: the variants the references kept that are plausible (see
        `plausible`) rendered now at the check's random settings; the key of the one the
        student's values match, or None.

        A kind whose live values describe the program (a sampler's fingerprint) is
        matched once per submission, at the first failed check's settings."""
        kind = kind_of(check)
        if kind.by_program:
            # A sampler's or estimator's program is its sampler_code (model.code is the
            # library model's, the same for every submission)
            memo = (exercise.solution, model.code, getattr(model, "sampler_code", None))
            if memo not in self._matched:
                self._matched[memo] = self._live_match(exercise, check, model, None, None)
            return self._matched[memo]
        return self._live_match(exercise, check, model, got, expected)

    def plausible(self, exercise: Exercise, check: Check, model: Model) -> list[str]:
        """The kept variants worth rendering live for a check: at its committed settings
        (stored values) the one the student's program matches, or, where the student's
        program is right there, those that are right there too: they may show only under
        random settings. A few compiles, not one per variant."""
        kind, renderer, stored = kind_of(check), self.grader.renderer, self.stored(exercise)
        if kind.by_program:  # the fingerprint at the first such check's settings
            fixed = next(c for c in exercise.checks if kind_of(c).by_program)
            prefix, want = f"{FINGERPRINT}|", stored.get(f"{FINGERPRINT}|solution")
        else:
            fixed = next((c for c in exercise.checks if c.name == check.name), None)
            prefix = f"{check.name}|"
            want = self.grader.expected(exercise, fixed, live=False) if fixed else None
        hints = mistakes.read_hints(exercise)
        kept = [v.key for v in self.variants(exercise) if v.key in hints]
        if want is None:
            return kept  # references without them: every variant is plausible
        memo = (exercise.references, fixed.name)
        if memo not in self._shown:  # the variants the committed settings tell apart
            self._shown[memo] = {
                k: stored[prefix + k]
                for k in kept
                if prefix + k in stored and not kind.live_same(fixed, stored[prefix + k], want)
            }
        shown = self._shown[memo]
        mine = kind.live_values(renderer, model, fixed)
        if kind.live_same(fixed, mine, want):
            return [k for k in kept if k not in shown]
        if kind.by_program:
            match = kind.live_match(fixed, mine, want, shown)
        else:
            match = kind.nearest(fixed, mine, want, shown)
        return [match] if match else []

    def _live_match(self, exercise, check, model, got, expected) -> str | None:
        kind, renderer = kind_of(check), self.grader.renderer
        try:
            plausible = self.plausible(exercise, check, model)
            if not plausible:
                return None
            if got is None:
                got = kind.live_values(renderer, model, check)
                expected = kind.live_values(renderer, self.grader.solution_model(exercise), check)
            values = {}
            for variant in self.variants(exercise):
                wrong = self.variant_model(exercise, variant) if variant.key in plausible else None
                if wrong is not None:
                    values[variant.key] = kind.live_values(renderer, wrong, check)
        except (ShaderCompileError, ModelError, OSError, KeyError):
            return None
        return kind.live_match(check, got, expected, values)

    def explain(
        self,
        exercise: Exercise,
        check: Check,
        model: Model,
        expected: np.ndarray,
        raw: np.ndarray,
        live: bool,
        reading=None,
    ) -> str:
        """'Likely: ...' for a failed check, or '' when the evidence names nothing;
        `reading` is the grader's lab.grading.checks.Submission of the file, if any. A
        render with several lights also says which of them is wrong alone (superpose)."""
        said = self._explain(exercise, check, model, expected, raw, live, reading)
        try:
            solution = self.grader.solution_model(exercise)
            lights = superpose.light_by_light(self.grader.renderer, check, model, solution)
        except (OSError, ShaderCompileError, ModelError, SubmissionError):
            lights = ""
        if lights:
            lights = f"{lights[0].upper()}{lights[1:]}."
            return f"{said} {lights}" if said else lights
        return said

    def _explain(
        self,
        exercise: Exercise,
        check: Check,
        model: Model,
        expected: np.ndarray,
        raw: np.ndarray,
        live: bool,
        reading=None,
    ) -> str:
        hints = mistakes.read_hints(exercise)
        kind = kind_of(check)
        got = kind.stored(raw, check)  # the form of the reference and the variants' values
        if live:
            key = self.live(exercise, check, model, got, expected)
        else:
            candidates = {k: v for k, v in self.candidates(exercise, check).items() if k in hints}
            key = kind.nearest(check, got, expected, candidates)
        if key is not None and kind.confirm_elsewhere:
            try:
                key = key if self.elsewhere(exercise, check, model, key) else None
            except (ShaderCompileError, ModelError, OSError, KeyError):
                key = None
        try:
            located = self.locate(exercise, check, model, reading)
        except Exception:  # noqa: BLE001 - the stored hints stand without the trace
            if os.environ.get("BRDF_LAB_DEBUG"):
                traceback.print_exc()
            located = Located()
        where = located.text
        source = _source(model, reading)
        said = key in hints and self.consistent(exercise, check, key, located, source)
        if located.exit:  # stronger than any stored hint, which may say it in its words
            if said:
                return diagnosis.sentence(hints[key]) + f" Where: {where}."
            return diagnosis.sentence(where)
        if said:
            if key == mistakes.STUB:  # the file as handed out: nothing of theirs to locate
                return diagnosis.sentence(hints[key])
            return diagnosis.sentence(hints[key]) + (f" Where: {where}." if where else "")
        located_only = f" Where: {where}." if where else ""
        if key in hints and where:  # a hint the trace contradicts is left unsaid
            return located_only.strip()
        if not where:
            shape = kind.explain(self, exercise, check, model, expected, got, live)
            return diagnosis.sentence(shape)
        # With the trace's line, only what evaluating the code says besides: which declared
        # term is wrong, or L and V swapped (the shape of the values alone may mislead).
        angles = kind.angles(check)
        said = ""
        if kind.by_program:  # a sampler's: which of sampler and pdf is wrong, evaluated
            said = kind.explain(self, exercise, check, model, expected, got, live)
        elif angles is not None and located.finding is not None and not located.finding.relation:
            said = self.terms(exercise, check, model, angles, live, detail=False)
        return (diagnosis.sentence(said) + located_only).strip()

    def terms(
        self,
        exercise: Exercise,
        check: Check,
        model: Model,
        angles: np.ndarray,
        live: bool,
        detail: bool = True,
    ) -> str:
        """Evaluate each declared term alone; name the wrong one and the shape of its error.

        A term seen through macros (D with G and F made 1) counts only where the student's
        code calls what the macros replace."""
        terms = mistakes.read_terms(exercise)
        if len(terms) < 2:
            return ""
        wrong, right, details, parent = [], [], {}, {}
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
                details[name] = diagnosis.shape(term_check, angles, want, mine) or kind_of(
                    check
                ).lobe(term_check, angles, want, mine, exercise.model_name)
        wrong, right = _finest(wrong, right, parent)
        if not wrong or not right:
            return ""
        shape = details.get(wrong[0], "") if len(wrong) == 1 and detail else ""
        return diagnosis.terms_sentence(wrong, right, shape)

    def swaps(self, check: Check, model: Model, angles: np.ndarray, expected) -> str:
        """L and V exchanged, or the tangent axes X and Y: render the swap and compare."""
        renderer = self.grader.renderer
        got = renderer.eval_angles(model, check.params, angles)
        if diagnosis.same(check, got, expected):
            return ""  # nearly right: a swap would look right too, and say nothing
        swapped = renderer.eval_angles(model, check.params, angles[:, [2, 3, 0, 1]])
        if diagnosis.same(check, swapped, expected) and not diagnosis.same(check, swapped, got):
            return diagnosis.WORDS["swapped_lv"]
        mirrored = angles.copy()
        mirrored[:, [1, 3]] = (90.0 - angles[:, [1, 3]]) % 360.0
        axes = renderer.eval_angles(model, check.params, mirrored)
        if diagnosis.same(check, axes, expected) and not diagnosis.same(check, axes, got):
            return diagnosis.WORDS["swapped_xy"]
        return ""


def _source(model: Model, reading=None) -> str:
    """The student's file as read by the grader ('' where it cannot be read)."""
    if reading is not None:
        return reading.code
    path = getattr(model, "sampler_path", None) or model.path
    try:
        return Path(path).read_text(encoding="utf-8") if path else ""
    except (OSError, UnicodeError):
        return ""

"""What the traces of a submission say about a failed check (lab.grading.trace and
lab.grading.localise), for the Explainer: where the student's values first part from the
solution's, a missing early exit, and whether a stored hint agrees with them."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from lab.glsl import COMMENTS, ShaderCompileError, label_of
from lab.grading import localise, mistakes, trace
from lab.grading.exercise import Check, Exercise, SubmissionError
from lab.grading.kinds import kind_of
from lab.models import Model, ModelError


@dataclass
class Located:
    """What the traces say about a failed check (lab.grading.localise)."""

    text: str = ""
    finding: localise.Finding | None = None
    solution: trace.Trace | None = None
    angles: np.ndarray | None = None
    exit: bool = False  # the difference is a missing early exit
    source: str | None = None  # the student's file
    mine: trace.Trace | None = None  # the student's trace
    view: str = ""  # the trace harness (lab.grading.trace.HARNESS), '' for a BRDF's


def _bare(code: str) -> str:
    """Code without comments and white space: a file as handed out, edited or not."""
    return "".join(COMMENTS.sub("", code).split())


class TraceEvidence:
    """The Explainer's tracing part; it brings `grader`, `variants`, `variant_model` and a
    `_traces` cache (lab.grading.explain.Explainer)."""

    def consistent(
        self, exercise: Exercise, check: Check, key: str, located: Located, source: str = ""
    ) -> bool:
        """Does the likely wrong program whose values the student's match go wrong at the
        same quantity as the student's (a variable of the same name, or the same function's
        result), with the same values there? Where the trace found no fault in the student's
        code, nothing contradicts the hint (True); where it did, the hint must go wrong at
        the same place the same way. `source`: the student's file, for the stub's hint."""
        variant = next((v for v in self.variants(exercise) if v.key == key), None)
        if key == mistakes.STUB:  # said to the file as handed out, never to work written in
            # it whose values happen to resemble the stub's (a specular term that is 0 here)
            stub = variant.code if variant is not None else ""
            return bool(source) and _bare(source) == _bare(stub)
        if located.exit and key.startswith(mistakes.MUTANT):
            return False  # a generated edit's words ("which dot product") are vaguer than
            # the missing exit the trace names, and may send the student to a factor
        if located.exit or located.finding is None or located.solution is None:
            if not located.exit or located.solution is None:
                return True  # nothing the trace says contradicts the hint
        elif located.finding.point.loop:
            return True  # a loop's values are its last pass's: the trace is unsure
        model = self.variant_model(exercise, variant) if variant is not None else None
        if model is None:
            return False
        solution_text = exercise.solution.read_text(encoding="utf-8")
        theirs = self._trace(
            exercise, model, check, located.angles, solution_text, view=located.view
        )
        if theirs is None:
            return False
        if located.exit:  # the hint stands where its own program lacks the exit too
            return bool(localise.early_exit(theirs, located.solution))
        if localise.early_exit(theirs, located.solution):
            return False  # the variant's difference is a missing exit, the student's is not
        other = localise.locate(theirs, located.solution)
        # The trace found the student's fault: the hint is said only where its own program
        # goes wrong at the same quantity, or its first wrong value is the student's first
        # wrong value (the same slip, written another way).
        if other is None:
            return False
        mine = located.mine
        if mine is None:
            return False
        if localise.target(other) == localise.target(located.finding):
            # the same quantity, gone wrong the same way: a different slip in the same line
            # (1 − c⁵ for (1 − c)⁵) is not the stored one (f0 and 1 − f0 swapped)
            return localise.same_value(mine, located.finding, theirs, other)
        return localise.same_slip(mine, located.finding, theirs, other)

    def locate(self, exercise: Exercise, check: Check, model: Model, reading=None) -> Located:
        """The line where the student's values first part from the solution's, and how
        (lab.grading.localise), at the check's pairs or, for an image, pairs of its own;
        an empty text where the program cannot be traced or nothing stands out."""
        path = model.sampler_path if exercise.sampler_for else model.path
        if path is None:
            return Located()
        views = [trace.HARNESS[c.view] for c in exercise.checks if c.view in trace.HARNESS]
        harness = views[0] if views else ""
        if exercise.sampler_for:  # the sampler at random numbers u and views of its own
            angles = trace.sampler_rows()
        elif harness:  # an illumination model: at normals, under lights of the harness's
            angles = trace.normal_rows()
        else:
            angles = kind_of(check).angles(check)
            angles = trace.pairs() if angles is None else angles
        try:
            source = reading.code if reading is not None else Path(path).read_text("utf-8")
            mine = self._trace(exercise, model, check, angles, source, reading, harness)
            solution = self.grader.solution_model(exercise)
            wanted = self._trace(
                exercise,
                solution,
                check,
                angles,
                exercise.solution.read_text(encoding="utf-8"),
                view=harness,
            )
        except (OSError, ShaderCompileError, ModelError, SubmissionError):
            return Located()
        if mine is None or wanted is None:
            return Located()
        exit_missing = localise.early_exit(mine, wanted)
        if exit_missing:
            return Located(exit_missing, None, wanted, angles, exit=True, view=harness)
        finding = localise.locate(mine, wanted)
        said = localise.sentence(finding, source, label_of(path)) if finding else ""
        if exercise.wrapper:  # a term exercise: the student's F, D or G beside the solution's
            names = [f.split("(")[0].split()[-1] for f in exercise.functions]
            rows = localise.term_rows(mine, wanted, names)
            said = f"{said}. {rows[0].upper()}{rows[1:]}" if said and rows else said or rows
        return Located(said, finding, wanted, angles, source=source, mine=mine, view=harness)

    def _trace(
        self,
        exercise: Exercise,
        model: Model,
        check: Check,
        angles,
        source: str,
        reading=None,
        view: str = "",
    ):
        """A program's trace at a check's settings: the student's kept with their reading
        (instrumented once), the solution's and variants' once per worker."""
        params = tuple(sorted(map(str, check.params.items())))
        key = (model.code, getattr(model, "sampler_code", None), params, angles.tobytes(), view)
        cache = reading.traces if reading is not None else self._traces
        if key not in cache:
            if len(cache) > 64:
                cache.clear()
            wrapped = exercise.wrapper or exercise.sampler_for  # code after the student's
            last = len(source.splitlines()) if wrapped else 1 << 30
            kept = reading.instrumented if reading is not None else None
            cache[key] = trace.run(
                self.grader.renderer, model, check.params, angles, last, kept, view
            )
        return cache[key]

"""The checks themselves: render the student's model, compare with the solution.

This module needs OpenGL and runs inside the worker processes of lab.grading.runner;
each check returns a CheckResult that pickles back to the supervising process. What a
check renders and how it is compared belongs to its kind (lab.grading.kinds).
"""

from __future__ import annotations

import math
import os
from collections.abc import Iterator
from concurrent.futures import Future, ThreadPoolExecutor
from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np

from lab.constants import LOOP_TOTAL
from lab.glsl import SAMPLER_LINE_BASE, ShaderCompileError, label_of, loop_cause
from lab.grading import tables
from lab.grading.compare import (  # noqa: F401 - the names grading code has always used
    bad_values,
    compare_values,
    fmt_rgb,
    luminance,
    mean_flip,
    png,
    read_png,
    tonemap,
)
from lab.grading.exercise import (
    Check,
    Exercise,
    SubmissionError,
    build_model,
    header_notes,
    read_submission,
    wrapper_origin,
)
from lab.grading.kinds import VALUES_FILE, kind_of
from lab.grading.kinds.polar import polar_angles
from lab.grading.kinds.probe import probe_angles, special_angles
from lab.grading.result import CheckResult, failed
from lab.grading.spec import PURPOSES, ExerciseError, infer_purpose
from lab.grading.submission import portability_warnings
from lab.grading.words import DIAGNOSIS
from lab.models import Model, ModelError
from lab.render import Light, Renderer

__all__ = [
    "VALUES_FILE",
    "CheckResult",
    "Grader",
    "Submission",
    "expected_value",
    "failed",
    "hidden_variant",
    "polar_angles",
    "prepare",
    "probe_angles",
    "render",
    "special_angles",
    "stopped_where",
]


# -- inputs: hidden variants ------------------------------------------------------------------
def _drawn_theta(rng: np.random.Generator, purpose: str) -> float:
    low, high = PURPOSES[purpose]
    return float(rng.uniform(low, high))


def _drawn_param(rng: np.random.Generator, param, value, low: float, high: float):
    """One parameter drawn across [low, high]: log-uniform where its slider is log."""
    if param.kind == "float":
        if param.scale == "log" and low > 0.0:
            return float(np.exp(rng.uniform(math.log(low), math.log(high))))
        return float(rng.uniform(low, high))
    if param.kind == "color" and any(value):  # a term the check switched off stays off
        return tuple(float(c) for c in rng.uniform(low, high, 3))
    return value  # enums and switches: the term under test stays


def hidden_variant(check: Check, model: Model, seed: int, index: int) -> Check:
    """The check with random parameters, lights and directions drawn from `seed`.

    Each light keeps what it is for (the check's `purpose`, else what its committed angle
    says: spec.PURPOSES) and is drawn anew within that class; parameters are drawn across
    the header's range (log-uniform on log sliders) or the check's own `ranges`. What the
    check pins down stays: its enum choices (the term under test) and colours it sets to
    zero (terms switched off so that the one under test shows alone).
    """
    rng = np.random.default_rng([seed, index])
    model = kind_of(check).params_model(check, model)
    params = dict(check.params)
    for key, names in [("ranges", list(check.ranges)), ("same", sum(check.same, ()))]:
        for name in names:
            if name not in model.params:
                raise ExerciseError(
                    f"check {check.name}: {key} names {name!r}, which is no parameter of the "
                    f"model ({', '.join(model.params)}); fix the name in exercise.toml"
                )
    for name, param in model.params.items():
        low, high = check.ranges.get(name, (param.minimum, param.maximum))
        if low < param.minimum or high > param.maximum:
            raise ExerciseError(
                f"check {check.name}: ranges.{name} = [{low:g}, {high:g}] leaves the header's "
                f"range [{param.minimum:g}, {param.maximum:g}]; narrow it in exercise.toml"
            )
        params[name] = _drawn_param(rng, param, params.get(name, param.default), low, high)
    for group in check.same:  # drawn once: the first name's value for the whole group
        for name in group[1:]:
            params[name] = params[group[0]]
    aimed = kind_of(check).purpose_of
    purposes = list(check.purpose)
    if aimed != "lights" or not purposes:
        purposes = [infer_purpose(lt.theta) for lt in check.lights]
    lights = [
        Light(_drawn_theta(rng, purpose), float(rng.uniform(0, 360)), lt.rgb)
        for lt, purpose in zip(check.lights, purposes, strict=True)
    ]
    aim = check.purpose[0] if aimed == "theta_i" and check.purpose else None
    return replace(
        check,
        params=params,
        lights=lights,
        seed=int(rng.integers(1 << 30)),
        theta_i=_drawn_theta(rng, aim or infer_purpose(check.theta_i)),
        phi_i=float(rng.uniform(0, 360)),
        table=tables.hidden(check.table, seed),  # its own draw: the others stay as they were
    )


# -- rendering, by the check's kind -----------------------------------------------------------
def render(renderer: Renderer, model: Model, check: Check) -> np.ndarray:
    """The raw float output of `model` for a check (probe rows, polar curve, RGBA image...)."""
    return kind_of(check).render(renderer, model, check)


def expected_value(raw: np.ndarray, check: Check) -> np.ndarray:
    """What is stored as the reference: values as they are, images tone-mapped to 8 bits."""
    return kind_of(check).stored(raw, check)


def stopped_where(check: Check, x: int, y: int) -> str:
    """The directions at the pixel where the loop guard stopped a loop, in words."""
    return kind_of(check).where(check, x, y)


# -- the submission, before any OpenGL -------------------------------------------------------
@dataclass
class Submission:
    """One reading of a student's file, shared by every check, the diagnosis and the
    similarity report: its text, the model built from it (the preprocessed code, the
    header), the header lines the grader put back, the GLSL ES compile under way, and the
    diagnosis's traces of it (lab.grading.trace), made once however many checks fail."""

    code: str = ""  # the file's text, as read
    model: Model | None = None
    error: str = ""  # why it cannot be graded at all (every check gets it)
    portable: Future | None = None  # the portability warnings
    notes: list[str] = field(default_factory=list)  # header lines put back, in words
    traces: dict = field(default_factory=dict)  # the diagnosis's, by check setting
    instrumented: dict = field(default_factory=dict)  # its instrumented code, by part


def prepare(exercise: Exercise, submission: Path, root: Path | None = None) -> Submission:
    """Read and build the submission (no GL needed: a worker does this while its context is
    made). The GLSL ES compile runs beside the checks; its warnings go with the last one."""
    try:
        code = read_submission(submission, root)
        model = build_model(exercise, submission, code)
    except SubmissionError as err:
        return Submission(error=str(err))
    alone = model
    for kind in dict.fromkeys(kind_of(check) for check in exercise.checks):
        alone = kind.portable(exercise, alone)  # as the page compiles the file on its own
    executor = ThreadPoolExecutor(max_workers=1)
    portable = executor.submit(portability_warnings, alone, label_of(submission))
    executor.shutdown(wait=False)
    notes = header_notes(exercise, submission, code)
    return Submission(code, model, portable=portable, notes=notes)


# -- the grader -----------------------------------------------------------------------------
class Grader:
    """Grades submissions check by check with one OpenGL context (inside a worker)."""

    def __init__(self) -> None:
        self._renderer: Renderer | None = None
        self._solutions: dict[Path, Model] = {}
        self._references: dict[tuple, tuple] = {}
        self.explainer = None  # lab.grading.explain.Explainer, set by the runner
        self.reading: Submission | None = None  # the last submission graded

    @property
    def renderer(self) -> Renderer:
        if self._renderer is None:
            self._renderer = Renderer()
        return self._renderer

    def solution_model(self, exercise: Exercise) -> Model:
        path = exercise.solution
        if path not in self._solutions:
            if not path.is_file():
                raise FileNotFoundError(f"{path}: no solution (hidden mode and references need it)")
            self._solutions[path] = build_model(exercise, path, read_submission(path))
        return self._solutions[path]

    def expected(self, exercise: Exercise, check: Check, live: bool) -> np.ndarray:
        """The reference for a check: committed files, or the solution rendered now."""
        if live:
            return expected_value(
                render(self.renderer, self.solution_model(exercise), check), check
            )
        # Read once per worker (a class shares them), again when a file there changed.
        folder = exercise.references
        try:
            stamp = tuple(
                sorted((e.name, e.stat().st_mtime_ns, e.stat().st_size) for e in os.scandir(folder))
            )
        except OSError:
            stamp = ()
        key = (folder, check.name, check.kind)
        cached = self._references.get(key)
        if cached is None or cached[0] != stamp:
            reference = kind_of(check).load_reference(exercise, check)
            if isinstance(reference, np.ndarray):
                reference.flags.writeable = False
            cached = self._references[key] = (stamp, reference)
        return cached[1]

    def run(
        self,
        exercise: Exercise,
        submission: Path,
        seed: int | None = None,
        skip: frozenset[str] = frozenset(),
        root: Path | None = None,
        prepared: Submission | None = None,
    ) -> Iterator[CheckResult]:
        """Grade every check not in `skip`, yielding each result as soon as it is known.

        `root` is the submission's top folder (no link below it is followed); `prepared`
        is what prepare() made of the file already, if anything."""
        todo = [(i, c) for i, c in enumerate(exercise.checks) if c.name not in skip]
        ready = prepared or prepare(exercise, submission, root)
        self.reading = ready
        if ready.error:
            for _, check in todo:
                yield failed(check, ready.error, status="error")
            return
        code, model, portable = ready.code, ready.model, ready.portable
        for index, check in todo:
            try:
                if seed is not None:
                    check = hidden_variant(check, self.solution_model(exercise), seed, index)
                expected = self.expected(exercise, check, live=seed is not None)
            except (OSError, KeyError, ModelError, SubmissionError, ExerciseError) as err:
                result = failed(
                    check, f"cannot get the reference: {err} (ask your instructor)", status="error"
                )
            else:
                result = self.grade(
                    exercise, check, model, code, expected, seed is not None, reading=ready
                )
                if seed is not None:
                    result.setting = {
                        "seed": seed,
                        "params": check.params,
                        "theta_i": check.theta_i,
                        "lights": [(lt.theta, lt.phi) for lt in check.lights],
                        "probe_seed": check.seed,
                    }
                    if check.table:
                        result.setting["table"] = tables.describe(check.table)
            if index == todo[0][0]:  # header lines the grader put back, named once
                result.warnings = list(ready.notes)
            if index == todo[-1][0]:
                result.warnings = result.warnings + portable.result()
            yield result

    def grade(
        self,
        exercise: Exercise,
        check: Check,
        model: Model,
        code: str,
        expected: np.ndarray,
        live: bool = False,
        reading: Submission | None = None,
    ) -> CheckResult:
        twin = getattr(self.renderer, "_ibl_twin", None)  # a sampling exercise's passes
        if twin is not None:
            twin.loop_stopped = None
        try:
            model = tables.bound(self.renderer, model, check)  # the diagnosis reads it too
            raw = render(self.renderer, model, check)
        except ShaderCompileError as err:
            errors = []
            for e in err.errors:
                file, line = wrapper_origin(exercise, code, e.file, e.line)
                errors.append(f"{file}:{line}: {e.message}")
            errors = errors or [err.log.strip()]
            return failed(check, "the shader does not compile: " + errors[0], errors=errors)
        except ModelError as err:
            return failed(check, str(err), status="error")
        stop = self.renderer.loop_stop()
        twin = getattr(self.renderer, "_ibl_twin", None)
        if stop is None and twin is not None:
            stop, twin.loop_stopped = twin.loop_stopped, None
        if stop is not None:
            line, x, y = stop
            line, together = loop_cause(line)
            if line >= SAMPLER_LINE_BASE:  # a loop in a sampling exercise's file
                file, line = label_of(model.sampler_path), line - SAMPLER_LINE_BASE
            else:
                file, line = wrapper_origin(exercise, code, label_of(model.path), line)
            where = stopped_where(check, x, y)
            said = DIAGNOSIS["loops_total" if together else "loop_stopped"].format(
                file=file,
                line=line,
                limit=f"{model.loop_limit:,}",
                total=f"{LOOP_TOTAL:,}",
                where=where,
            )
            return failed(check, said, loop_line=line)
        result = self.compare(check, expected, raw)
        if not result.passed:
            result.diagnosis = self.diagnose(exercise, check, model, expected, raw, live, reading)
            if result.diagnosis:  # a loop is named only by the loop guard, above
                result.message += ". " + result.diagnosis
        return result

    def diagnose(self, exercise, check, model, expected, raw, live: bool, reading=None) -> str:
        """The likely mistake, from the explainer the runner plugs in (lab.grading.explain);
        a diagnosis never breaks grading."""
        if self.explainer is None:
            return ""
        try:
            with np.errstate(all="ignore"):  # broken values (inf, NaN) are evidence here
                return self.explainer.explain(
                    exercise, check, model, expected, raw, live, reading=reading
                )
        except Exception:  # noqa: BLE001 - no hint is better than no grade
            if os.environ.get("BRDF_LAB_DEBUG"):
                import traceback

                traceback.print_exc()
            return ""

    @staticmethod
    def compare(check: Check, expected: np.ndarray, raw: np.ndarray) -> CheckResult:
        return kind_of(check).compare(check, expected, raw)

"""The checks themselves: render the student's model, compare with the solution.

This module needs OpenGL and runs inside the worker processes of lab.grading.runner;
each check returns a CheckResult that pickles back to the supervising process.
"""

from __future__ import annotations

import io
import math
from collections.abc import Iterator
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np

from lab.constants import LUMA
from lab.geometry import direction
from lab.glsl import ShaderCompileError, label_of
from lab.grading.exercise import (
    Check,
    Exercise,
    SubmissionError,
    build_model,
    read_submission,
    wrapper_origin,
)
from lab.grading.submission import portability_warnings
from lab.grading.visuals import failing_overlay, signed_difference
from lab.models import Model, ModelError
from lab.render import Light, Renderer, light_uniforms

VALUES_FILE = "values.npz"


@dataclass
class CheckResult:
    """The outcome of one check, with everything the reports show."""

    name: str
    kind: str
    max_points: float
    points: float = 0.0
    status: str = "failed"  # passed | failed | error
    message: str = ""
    rows: list[tuple] = field(
        default_factory=list
    )  # probe: theta_i, phi_i, theta_o, phi_o, exp, got
    images: dict[str, bytes] = field(default_factory=dict)  # reference, student, diff (PNG)
    flip: float | None = None
    curve: dict | None = None  # polar: theta_o, expected, got (luminance)
    errors: list[str] = field(default_factory=list)  # compile errors, file:line: message
    diagnosis: str = ""  # "Likely: ..." (also the end of the message), or ""
    failing: list[int] = field(default_factory=list)  # polar: indices of failing points
    setting: dict | None = None  # hidden mode: the seed and parameter values used
    threshold: float = 0.0  # sphere: the per-pixel threshold (1/255) of the difference image
    loop_line: int = 0  # the student's line of a loop the guard stopped (0: none did)
    warnings: list[str] = field(default_factory=list)  # not scored: e.g. the web lab rejects

    @property
    def passed(self) -> bool:
        return self.status == "passed"


def failed(check: Check, message: str, status: str = "failed", **extra) -> CheckResult:
    return CheckResult(
        check.name, check.kind, check.points, status=status, message=message, **extra
    )


# -- inputs: direction pairs, hidden variants -----------------------------------------------
def probe_angles(check: Check) -> np.ndarray:
    """(pairs + 18, 4) rows theta_i, phi_i, theta_o, phi_o in degrees, fixed by the check's
    seed; the last 18 are the special directions (special_angles).

    Half the pairs are spread over the hemisphere, 3/8 lie near the mirror direction
    (where the highlights are) and 1/8 have L or V below the horizon (must give 0).
    """
    rng = np.random.default_rng(check.seed)
    n = check.pairs
    n_mirror, n_below = 3 * n // 8, n // 8
    n_spread = n - n_mirror - n_below
    theta_i = np.degrees(np.arccos(rng.uniform(0.05, 1.0, n)))
    phi_i = rng.uniform(0.0, 360.0, n)
    theta_o = np.degrees(np.arccos(rng.uniform(0.05, 1.0, n)))
    phi_o = rng.uniform(0.0, 360.0, n)
    near = slice(n_spread, n_spread + n_mirror)
    theta_o[near] = np.clip(theta_i[near] + rng.normal(0.0, 4.0, n_mirror), 0.5, 88.0)
    phi_o[near] = phi_i[near] + 180.0 + rng.normal(0.0, 6.0, n_mirror)
    below = slice(n_spread + n_mirror, n)
    flip_light = rng.random(n_below) < 0.5
    theta_i[below] = np.where(flip_light, 180.0 - theta_i[below], theta_i[below])
    theta_o[below] = np.where(flip_light, theta_o[below], 180.0 - theta_o[below])
    rows = np.stack([theta_i, phi_i % 360.0, theta_o, phi_o % 360.0], axis=1)
    return np.concatenate([rows, special_angles(float(rng.uniform(0.0, 360.0)))])


def special_angles(phi: float) -> np.ndarray:
    """Rows where formulas divide by zero or lose precision: L = N, V = N, L = V, the exact
    mirror direction, beside it in the plane of incidence and across it, and 89.9 degrees
    from the normal (an Inf or NaN at any of them fails the check)."""
    back = phi + 180.0
    rows = [
        (0.0, 0.0, 0.0, 0.0),  # L = V = N
        (0.0, 0.0, 35.0, phi),  # L = N
        (0.0, 0.0, 70.0, back),
        (35.0, phi, 0.0, 0.0),  # V = N
        (70.0, phi, 0.0, 0.0),
        (30.0, phi, 30.0, phi),  # L = V
        (75.0, phi, 75.0, phi),
        (20.0, phi, 20.0, back),  # the exact mirror direction
        (45.0, phi, 45.0, back),
        (70.0, phi, 70.0, back),
        (45.0, phi, 35.0, back),  # in the plane of incidence, beside the mirror
        (45.0, phi, 55.0, back),
        (45.0, phi, 45.0, phi + 90.0),  # perpendicular to the plane of incidence
        (45.0, phi, 45.0, phi + 270.0),
        (89.9, phi, 30.0, back),  # grazing light, grazing view, both
        (30.0, phi, 89.9, back),
        (89.9, phi, 89.9, back),
        (89.9, phi, 89.9, phi + 90.0),
    ]
    table = np.array(rows, dtype=np.float64)
    table[:, [1, 3]] %= 360.0
    return table


def polar_angles(check: Check) -> np.ndarray:
    """Rows for the plane of incidence, theta_o from -88 to 88 deg (negative: light side).

    Exactly grazing views are left out: there N.V is 0 up to rounding and f_r of
    microfacet models swings with the last bit of the driver's arithmetic.
    """
    theta = np.arange(-88.0, 88.5, 1.0)
    phi_o = np.where(theta >= 0.0, check.phi_i + 180.0, check.phi_i)
    return np.stack(
        [
            np.full_like(theta, check.theta_i),
            np.full_like(theta, check.phi_i),
            np.abs(theta),
            phi_o % 360.0,
        ],
        axis=1,
    )


def hidden_variant(check: Check, model: Model, seed: int, index: int) -> Check:
    """The check with random parameters, lights and directions drawn from `seed`.

    What the check pins down stays: its enum choices (the term under test) and colours it
    sets to zero (terms switched off so that the one under test shows alone).
    """
    rng = np.random.default_rng([seed, index])
    params = dict(check.params)
    for name, param in model.params.items():
        value = params.get(name, param.default)
        if param.kind == "float":
            value = float(
                np.clip(value * math.exp(rng.uniform(-0.35, 0.35)), param.minimum, param.maximum)
            )
        elif param.kind == "color" and any(value):  # a term the check switched off stays off
            value = tuple(float(c) for c in rng.uniform(0.05, 0.9, 3))
        params[name] = value
    lights = [
        Light(float(rng.uniform(5, 70)), float(rng.uniform(0, 360)), lt.rgb) for lt in check.lights
    ]
    return replace(
        check,
        params=params,
        lights=lights,
        seed=int(rng.integers(1 << 30)),
        theta_i=float(rng.uniform(15, 70)),
        phi_i=float(rng.uniform(0, 360)),
    )


# -- rendering ------------------------------------------------------------------------------
def tonemap(rgb: np.ndarray) -> np.ndarray:
    """Radiance to display values in [0, 1) without clipping highlights (x/(1+x), gamma 2.2)."""
    x = np.maximum(np.nan_to_num(rgb, nan=0.0, posinf=1e30, neginf=0.0), 0.0)
    return (x / (1.0 + x)) ** (1.0 / 2.2)


def render(renderer: Renderer, model: Model, check: Check) -> np.ndarray:
    """The raw float output of `model` for a check: probe rows, polar curve or RGBA image."""
    if check.kind == "probe":
        return renderer.eval_angles(model, check.params, probe_angles(check))
    if check.kind == "polar":
        return renderer.eval_angles(model, check.params, polar_angles(check))
    lights = check.lights
    uniforms = {
        **light_uniforms(lights),
        "u_resolution": (float(check.size), float(check.size)),
        "u_ambient": tuple(check.ambient),
        "u_multiply_cos": True,
    }
    preamble = f"const int LIGHT_COUNT = {len(lights)};"
    # The sphere view's own plumbing, so grading templates (shaders/views/grade_*.glsl) share it.
    return renderer.image(model, check.view, check.params, check.size, uniforms, preamble)


def expected_value(raw: np.ndarray, check: Check) -> np.ndarray:
    """What is stored as the reference: values as they are, images tone-mapped to 8 bits."""
    if check.kind != "sphere":
        return raw.astype(np.float32)
    rgb = (tonemap(raw[..., :3]) * 255.0 + 0.5).astype(np.uint8)
    alpha = (np.clip(raw[..., 3:], 0, 1) * 255 + 0.5).astype(np.uint8)
    return np.concatenate([rgb, alpha], axis=-1)


def png(image: np.ndarray) -> bytes:
    from PIL import Image

    buffer = io.BytesIO()
    Image.fromarray(image).save(buffer, format="PNG", compress_level=1)
    return buffer.getvalue()


def read_png(path: Path) -> np.ndarray:
    from PIL import Image

    with Image.open(path) as img:
        return np.asarray(img.convert("RGBA"))


def stopped_where(check: Check, x: int, y: int) -> str:
    """The directions at the pixel where the loop guard stopped a loop, in words."""
    if check.kind in ("probe", "polar"):
        angles = probe_angles(check) if check.kind == "probe" else polar_angles(check)
        row = angles[min(y * min(len(angles), 1024) + x, len(angles) - 1)]
        return "(θi, φi, θo, φo) = ({:.1f}°, {:.1f}°, {:.1f}°, {:.1f}°)".format(*row)
    px, py = ((np.array([x, y]) + 0.5) / check.size) * 2.0 - 1.0
    normal = np.array([px, py, math.sqrt(max(1.0 - px * px - py * py, 0.0))])
    light = check.lights[0] if check.lights else Light(45.0)
    theta_i = math.degrees(math.acos(np.clip(normal @ direction(light.theta, light.phi), -1, 1)))
    theta_o = math.degrees(math.acos(np.clip(normal[2], -1.0, 1.0)))
    angles = f"θi = {theta_i:.1f}°, θo = {theta_o:.1f}°"
    return f"pixel ({x}, {check.size - 1 - y}) of the sphere ({angles})"


# -- comparisons ----------------------------------------------------------------------------
def bad_values(values: np.ndarray) -> np.ndarray:
    """Mask of rows with NaN, Inf or negative output (no comparison may let these pass)."""
    return ~np.isfinite(values).all(axis=-1) | (np.nan_to_num(values) < 0.0).any(axis=-1)


def fmt_rgb(rgb) -> str:
    r, g, b = (float(c) for c in rgb)
    if r == g == b or (math.isnan(r) and math.isnan(g) and math.isnan(b)):
        return f"{r:.5g}"
    return f"({r:.4g}, {g:.4g}, {b:.4g})"


def compare_values(
    check: Check, angles: np.ndarray, expected: np.ndarray, got: np.ndarray, what: str
) -> CheckResult:
    """Values within atol + rtol |expected|; the six rows nearest (or beyond) the tolerance
    are kept with their directions: the failures, or for a pass the closest calls."""
    bad = bad_values(got)
    error = np.abs(np.nan_to_num(got, nan=np.inf) - expected)
    wrong = bad | (error > check.atol + check.rtol * np.abs(expected)).any(axis=-1)
    with np.errstate(over="ignore", invalid="ignore"):
        relative = (error / (check.atol + np.abs(expected))).max(-1)
    order = np.argsort(-np.where(bad, np.inf, relative))
    rows = [
        (*(round(float(a), 1) for a in angles[i]), fmt_rgb(expected[i]), fmt_rgb(got[i]))
        for i in order[:6]
    ]
    n, n_wrong = len(got), int(wrong.sum())
    if bad.any():
        return failed(
            check,
            f"{int(bad.sum())} of {n} {what} are NaN, infinite or negative; "
            "a BRDF is finite and >= 0 (guard divisions and pow of negatives)",
            rows=rows,
        )
    if n_wrong:
        return failed(
            check,
            f"{n_wrong} of {n} {what} differ from the solution by more than "
            f"{check.rtol:g} x value + {check.atol:g}",
            rows=rows,
        )
    return CheckResult(
        check.name,
        check.kind,
        check.points,
        check.points,
        "passed",
        f"all {n} {what} match",
        rows=rows,
    )


def compare_image(check: Check, reference: np.ndarray, raw: np.ndarray) -> CheckResult:
    """Per-channel threshold after tone mapping, a maximum failing fraction, and mean FLIP."""
    covered = reference[..., 3] > 127
    student = tonemap(raw[..., :3])
    student8 = (np.clip(student, 0, 1) * 255 + 0.5).astype(np.uint8)
    bad = bad_values(raw[..., :3]) & covered
    shown = np.where(bad[..., None], np.array([255, 0, 255], np.uint8), student8)
    delta = (student - reference[..., :3] / 255.0) * 255.0
    diff = np.abs(delta).max(axis=-1)
    diff[bad] = 255.0
    diff[~covered] = 0.0
    failing = diff > check.threshold
    fraction = float(failing.sum()) / max(int(covered.sum()), 1)
    flip = mean_flip(reference[..., :3], student8) if failing.any() or diff.max() >= 1.0 else 0.0
    # the channel that is off the most, with its sign: too bright or too dark
    pick = np.take_along_axis(delta, np.abs(delta).argmax(axis=-1)[..., None], axis=-1)[..., 0]
    signed = np.where(bad, 255.0, pick)
    images = {
        "reference": png(reference[..., :3]),
        "student": png(shown),
        "difference": png(signed_difference(signed, covered, check.threshold)),
        "failing pixels": png(failing_overlay(reference, failing)),
    }
    extra = {"images": images, "flip": flip, "threshold": check.threshold}
    summary = (
        f"{100 * fraction:.2f}% of pixels off by more than {check.threshold:g}/255 "
        f"(allowed {100 * check.max_fraction:.2f}%), mean FLIP {flip:.4f}"
    )
    if bad.any():
        return failed(
            check,
            f"{int(bad.sum())} pixels are NaN, infinite or negative (magenta); " + summary,
            **extra,
        )
    if fraction > check.max_fraction:
        return failed(check, summary, **extra)
    return CheckResult(
        check.name, check.kind, check.points, check.points, "passed", summary, **extra
    )


def mean_flip(reference8: np.ndarray, student8: np.ndarray) -> float:
    """Mean FLIP error (LDR) on 2x-downsampled images: FLIP's cost grows fast with size."""
    import flip_evaluator

    def half(image: np.ndarray) -> np.ndarray:
        x = image.astype(np.float32) / 255.0
        h, w = x.shape[0] // 2 * 2, x.shape[1] // 2 * 2
        return x[:h, :w].reshape(h // 2, 2, w // 2, 2, 3).mean(axis=(1, 3))

    return float(flip_evaluator.evaluate(half(reference8), half(student8), "LDR")[1])


def luminance(values: np.ndarray) -> list[float]:
    lum = np.nan_to_num(values, nan=0.0) @ np.array(LUMA)
    return [round(float(v), 6) for v in lum]


# -- the grader -----------------------------------------------------------------------------
class Grader:
    """Grades submissions check by check with one OpenGL context (inside a worker)."""

    def __init__(self) -> None:
        self._renderer: Renderer | None = None
        self._solutions: dict[Path, Model] = {}
        self.explainer = None  # lab.grading.explain.Explainer, set by the runner

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
        if check.kind == "sphere":
            return read_png(exercise.references / f"{check.name}.png")
        with np.load(exercise.references / VALUES_FILE) as data:
            return data[check.name]

    def run(
        self,
        exercise: Exercise,
        submission: Path,
        seed: int | None = None,
        skip: frozenset[str] = frozenset(),
        root: Path | None = None,
    ) -> Iterator[CheckResult]:
        """Grade every check not in `skip`, yielding each result as soon as it is known.

        `root` is the submission's top folder (no link below it is followed)."""
        todo = [(i, c) for i, c in enumerate(exercise.checks) if c.name not in skip]
        try:
            code = read_submission(submission, root)
            model = build_model(exercise, submission, code)
        except SubmissionError as err:
            for _, check in todo:
                yield failed(check, str(err), status="error")
            return
        # The GLSL ES compile runs beside the checks; its warnings go with the last one.
        executor = ThreadPoolExecutor(max_workers=1)
        portable = executor.submit(portability_warnings, model, label_of(submission))
        executor.shutdown(wait=False)
        for index, check in todo:
            try:
                if seed is not None:
                    check = hidden_variant(check, self.solution_model(exercise), seed, index)
                expected = self.expected(exercise, check, live=seed is not None)
            except (OSError, KeyError, ModelError, SubmissionError) as err:
                result = failed(
                    check, f"cannot get the reference: {err} (ask your instructor)", status="error"
                )
            else:
                result = self.grade(exercise, check, model, code, expected, live=seed is not None)
                if seed is not None:
                    result.setting = {
                        "seed": seed,
                        "params": check.params,
                        "theta_i": check.theta_i,
                        "lights": [(lt.theta, lt.phi) for lt in check.lights],
                        "probe_seed": check.seed,
                    }
            if index == todo[-1][0]:
                result.warnings = portable.result()
            yield result

    def grade(
        self,
        exercise: Exercise,
        check: Check,
        model: Model,
        code: str,
        expected: np.ndarray,
        live: bool = False,
    ) -> CheckResult:
        try:
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
        if stop is not None:
            line, x, y = stop
            file, line = wrapper_origin(exercise, code, label_of(model.path), line)
            where = stopped_where(check, x, y)
            return failed(
                check,
                f"{file}:{line}: the loop at line {line} did not end within "
                f"{model.loop_limit:,} iterations at {where}; check its exit condition "
                "(on a GPU such a loop freezes the screen)",
                loop_line=line,
            )
        result = self.compare(check, expected, raw)
        if not result.passed:
            result.diagnosis = self.diagnose(exercise, check, model, expected, raw, live)
            if result.diagnosis:  # a loop is named only by the loop guard, above
                result.message += ". " + result.diagnosis
        return result

    def diagnose(self, exercise, check, model, expected, raw, live: bool) -> str:
        """The likely mistake, from the explainer the runner plugs in (lab.grading.explain);
        a diagnosis never breaks grading."""
        if self.explainer is None:
            return ""
        try:
            with np.errstate(all="ignore"):  # broken values (inf, NaN) are evidence here
                return self.explainer.explain(exercise, check, model, expected, raw, live)
        except Exception:  # noqa: BLE001 - no hint is better than no grade
            return ""

    @staticmethod
    def compare(check: Check, expected: np.ndarray, raw: np.ndarray) -> CheckResult:
        if check.kind == "sphere":
            return compare_image(check, expected, raw)
        if check.kind == "polar":
            angles = polar_angles(check)
            result = compare_values(check, angles, expected, raw, "points of the polar curve")
            error = np.abs(np.nan_to_num(raw, nan=np.inf) - expected)
            wrong = bad_values(raw) | (error > check.atol + check.rtol * np.abs(expected)).any(-1)
            result.failing = np.nonzero(wrong)[0].tolist()
            theta = np.where(angles[:, 3] == check.phi_i % 360.0, -angles[:, 2], angles[:, 2])
            result.curve = {
                "theta_o": theta.tolist(),
                "expected": luminance(expected),
                "got": luminance(raw),
                "theta_i": check.theta_i,
            }
            return result
        return compare_values(check, probe_angles(check), expected, raw, "direction pairs")

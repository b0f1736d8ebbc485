"""`kind = "properties"`: a student's tests of BRDF properties (exercise 11), run on a model.

The student's file defines `directional_albedo(V, N, X, Y)` and `reciprocity_error(L, V,
N, X, Y)` and calls `BRDF(L, V, N, X, Y)`, which it does not define: the check links it with
its `target` (a library model, or a `.glsl` file beside exercise.toml such as a deliberately
broken one) and runs both functions in shaders/views/grade_properties.glsl: the albedo at
`albedo_rows` viewing angles (the last `grazing_rows` of them near the horizon) and the
reciprocity error at `pairs` direction pairs, in a shading frame turned away from the axes.

What the values should be is the grader's own measurement of the target, made apart from any
student code: the albedo by a fine quadrature (centred on the mirror direction, where lobes
are) of the target's BRDF evaluated on the GPU, the reciprocity error from f(L, V) and
f(V, L) evaluated there. Both travel with the render (row 1 of the raw values, the
program's are row 0), so a check never trusts the solution's numbers: a test that always
says "pass" gets nothing, and the verdicts (energy conserved? reciprocal?) follow from the
measured values. Hidden mode draws the target's parameters in the check's `ranges` (see
`params_model`) and the rows and the frame from the drawn seed.
"""

from __future__ import annotations

import functools
import html
from dataclasses import replace
from pathlib import Path

import numpy as np

from lab.constants import LUMA
from lab.glsl import CompileError, ShaderCompileError, label_of
from lab.grading.kinds import CheckKind
from lab.grading.result import CheckResult, failed, passed
from lab.grading.rowpass import row_at, run_rows
from lab.grading.spec import Check, ExerciseError
from lab.grading.words import PROPERTIES as WORDS
from lab.ibl.chisquare import random_frame
from lab.models import Model, load_model, model_names, parse_model

VIEW = "grade_properties"
PROTOTYPE = "vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y); "  # before the student's code
EPS = 1e-7  # terms/common.glsl's EPS: the floor of reciprocity_error's denominator
GRAZING = (80.0, 88.0)  # theta_V of the grazing albedo rows, degrees
SPREAD = 78.0  # the other albedo rows are stratified over [0, SPREAD] degrees
RECIPROCAL = 0.01  # a reciprocity error above this says "not reciprocal"
TRUTH_U, TRUTH_PSI = 256, 128  # the grader's albedo quadrature (per row: 32,768 directions)
_TRUTHS: dict[tuple, np.ndarray] = {}  # measurements by target, parameters and rows
CHANNELS = "|channels"  # values.npz: a check's measurement per channel, under name + this
# How a test may reduce its colour channels to one number, besides the largest (the right
# one: energy is conserved, reciprocity holds, only where every channel passes).
REDUCTIONS = {
    "smallest": lambda c: c.min(axis=1),
    "mean": lambda c: c.mean(axis=1),
    "red": lambda c: c[:, 0],
    "green": lambda c: c[:, 1],
    "blue": lambda c: c[:, 2],
    "luminance": lambda c: c @ np.array(LUMA),
}


@functools.lru_cache(maxsize=32)
def target_model(target: str) -> Model:
    """The model a check runs the student's tests on (a library name or a file's path)."""
    return load_model(Path(target) if target.endswith(".glsl") else target)


def linked(student: Model, target: Model) -> Model:
    """The student's tests with the target's BRDF after them (its prototype on the first line
    keeps the file's own line numbers), its parameters and included terms."""
    code = PROTOTYPE + student.code.rstrip("\n") + "\n" + target.code
    # The target's includes only: the stub's terms/brdf_stand_in.glsl defines a BRDF for
    # tools that compile the test alone, which the target's replaces here.
    return replace(target, path=student.path, code=code, loop_limit=student.loop_limit)


def _from_target(err: ShaderCompileError, student: Model, target: Model) -> ShaderCompileError:
    """Compile errors past the student's last line belong to the target's file: a helper
    of the student's named like one of the model's clashes there."""
    lines = len(student.code.rstrip("\n").splitlines())
    label = label_of(student.path)
    errors = []
    for e in err.errors:
        if e.file == label and e.line > lines:
            message = (
                f"{e.message} (the model your tests run on is linked after your file: rename "
                "your function or global if the model defines the same name)"
            )
            e = CompileError(label_of(target.path), e.line - lines, message)
        errors.append(e)
    return ShaderCompileError(errors, err.log)


def albedo_truth(renderer, target: Model, params: dict, views: np.ndarray) -> np.ndarray:
    """(views, 3): per colour channel, the integral of f(L, V) cos(theta_L) over the upper
    hemisphere, for each view (theta_V, phi_V) in degrees: directions L around the mirror
    direction of V at angle t = pi u^2 (u and the azimuth psi on midpoint grids; Jacobian
    sin t 2 pi u)."""
    u = (np.arange(TRUTH_U) + 0.5) / TRUTH_U
    psi = (np.arange(TRUTH_PSI) + 0.5) * (2.0 * np.pi / TRUTH_PSI)
    t = np.pi * u * u
    weight = np.sin(t) * 2.0 * np.pi * u * (1.0 / TRUTH_U) * (2.0 * np.pi / TRUTH_PSI)
    Ls, Vs, ws = [], [], []
    for theta_v, phi_v in np.radians(views):
        V = np.array([np.sin(theta_v) * np.cos(phi_v), np.sin(theta_v) * np.sin(phi_v)])
        V = np.append(V, np.cos(theta_v))
        R = np.array([-V[0], -V[1], V[2]])
        T1 = np.cross([0.0, 0.0, 1.0], R) if abs(R[2]) < 0.999 else np.array([1.0, 0.0, 0.0])
        T1 /= np.linalg.norm(T1)
        T2 = np.cross(R, T1)
        around = np.cos(psi)[None, :, None] * T1 + np.sin(psi)[None, :, None] * T2
        L = np.cos(t)[:, None, None] * R + np.sin(t)[:, None, None] * around
        Ls.append(L.reshape(-1, 3))
        Vs.append(np.broadcast_to(V, (L.shape[0] * L.shape[1], 3)))
        ws.append(np.repeat(weight, TRUTH_PSI))
    L, V, w = np.concatenate(Ls), np.concatenate(Vs), np.concatenate(ws)
    f = renderer.probe(target, params, L, V).astype(np.float64)
    return (f * (np.maximum(L[:, 2], 0.0) * w)[:, None]).reshape(len(views), -1, 3).sum(axis=1)


def reciprocity_truth(renderer, target: Model, params: dict, pairs: np.ndarray) -> np.ndarray:
    """(pairs, 3): per channel, |f(L, V) - f(V, L)| / max(f(L, V), f(V, L), EPS)."""
    both = np.concatenate([pairs, pairs[:, [2, 3, 0, 1]]])
    f = renderer.eval_angles(target, params, both).astype(np.float64).reshape(2, len(pairs), 3)
    top = np.maximum(np.maximum(f[0], f[1]), EPS)
    return np.abs(f[0] - f[1]) / top


class PropertiesKind(CheckKind):
    name = "properties"
    confirm_elsewhere = True  # a few pixels per render: one subject can make mistakes agree
    order = 60
    purpose_of = ""  # its rows and frame are drawn from `seed`
    fields = {"target": "", "albedo_rows": 6, "grazing_rows": 2}

    # -- inputs ------------------------------------------------------------------------------
    def validate(self, check: Check, where: str) -> None:
        o, here = check.options, f"{where}: check {check.name}"
        target = o["target"]
        if target.endswith(".glsl"):
            path = (Path(where).parent / target).resolve()
            if not path.is_file():
                raise ExerciseError(f"{here}: target {target}: no such file beside exercise.toml")
            o["target"] = str(path)
        elif target not in model_names():
            raise ExerciseError(
                f"{here}: target {target!r} is neither a library model ({', '.join(model_names())})"
                " nor a .glsl file beside exercise.toml"
            )
        if not 1 <= o["albedo_rows"] <= 64 or not 0 <= o["grazing_rows"] <= o["albedo_rows"]:
            raise ExerciseError(
                f"{here}: albedo_rows must be 1 to 64 and grazing_rows 0 to albedo_rows"
            )
        if not 0 <= check.pairs <= 1024:
            raise ExerciseError(f"{here}: pairs (reciprocity pairs) must be 0 to 1024")

    def portable(self, exercise, model: Model) -> Model:
        """Alone, the file compiles with the stub's includes (the BRDF stand-in), whatever it
        includes itself: the grader links its own model instead (linked), and the page's
        panel compiles it so (static/submission.js)."""
        stub = parse_model(exercise.stub.read_text(encoding="utf-8"), exercise.stub)
        return replace(model, includes=list(stub.includes))

    def params_model(self, check: Check, model: Model) -> Model:
        """Hidden mode draws the target's parameters (its header, the check's ranges)."""
        return target_model(check.options["target"])

    def rows(self, check: Check) -> np.ndarray:
        """(n, 4) rows theta_L, phi_L, theta_V, phi_V in degrees, fixed by the seed: first the
        albedo rows (theta_L = -1), stratified in theta_V with the last near the horizon,
        then the reciprocity pairs (both directions above the horizon)."""
        return _rows(
            int(check.seed),
            check.options["albedo_rows"],
            check.options["grazing_rows"],
            int(check.pairs),
        )

    def frame(self, check: Check) -> np.ndarray:
        """The shading frame, rows X, Y, N, turned away from the axes (from the seed)."""
        return random_frame(int(check.seed) * 7 + 3)

    def albedo_count(self, check: Check) -> int:
        return int(check.options["albedo_rows"])

    # -- render --------------------------------------------------------------------------
    def render(self, renderer, model: Model, check: Check) -> np.ndarray:
        """(2, n): the program's values at the rows, and the grader's measurement there."""
        target = target_model(check.options["target"])
        program = linked(model, target)
        # The measurement first: the loop guard's flag is read from the last view rendered,
        # which must be the student's (a loop it stopped is named, not values "differ").
        truth = self.truth(renderer, target, check)
        rows = self.rows(check)
        X, Y, N = self.frame(check)
        data = np.radians(rows).astype(np.float32)
        data[: self.albedo_count(check), 0] = -1.0
        uniforms = {"u_rows": 0, "u_X": tuple(X), "u_Y": tuple(Y), "u_N": tuple(N)}
        try:
            got = run_rows(renderer, program, VIEW, check.params, data, uniforms)[:, 0]
            got = got.astype(np.float64)
        except ShaderCompileError as err:
            raise _from_target(err, model, target) from None
        return np.stack([got, truth])

    def truth(self, renderer, target: Model, check: Check) -> np.ndarray:
        """The grader's measurement at the check's rows: each row's largest channel."""
        return self.channels(renderer, target, check).max(axis=1)

    def channels(self, renderer, target: Model, check: Check) -> np.ndarray:
        """(rows, 3) the measurement per colour channel, made once per setting and process
        (the solution, the student's program and every likely mistake share it)."""
        rows, n = self.rows(check), self.albedo_count(check)
        key = self._key(target, check)
        found = _TRUTHS.get(key)
        if found is None:
            albedo = albedo_truth(renderer, target, check.params, rows[:n, 2:])
            pairs = reciprocity_truth(renderer, target, check.params, rows[n:])
            if len(_TRUTHS) >= 64:
                _TRUTHS.clear()
            found = _TRUTHS[key] = np.concatenate([albedo, pairs])
        return found.copy()

    def _key(self, target: Model, check: Check) -> tuple:
        rows = self.rows(check)
        return (str(target.path), target.code, repr(sorted(check.params.items())), rows.tobytes())

    def save_reference(self, exercise, check: Check, reference: np.ndarray, values: dict):
        """The reference, and the measurement per channel that rendering it made (the page
        names a reduction of the channels other than the largest from it, as explain())."""
        values[check.name] = reference
        found = _TRUTHS.get(self._key(target_model(check.options["target"]), check))
        if found is not None:
            values[f"{check.name}{CHANNELS}"] = found.copy()
        return []

    def stored(self, raw: np.ndarray, check: Check) -> np.ndarray:
        return np.asarray(raw, np.float64)

    def where(self, check: Check, x: int, y: int) -> str:
        rows = self.rows(check)
        k = min(row_at(x, y), len(rows) - 1)
        if k < self.albedo_count(check):
            return WORDS["albedo_at"].format(theta=rows[k, 2])
        return WORDS["pair_at"].format(**dict(zip(("tl", "pl", "tv", "pv"), rows[k], strict=True)))

    # -- compare -------------------------------------------------------------------------
    @staticmethod
    def _off(check: Check, got: np.ndarray, truth: np.ndarray) -> np.ndarray:
        """Rows where `got` is outside the tolerance of `truth` (NaN and Inf are)."""
        got = np.nan_to_num(np.asarray(got, np.float64), nan=np.inf)
        return ~(np.abs(got - truth) <= check.atol + check.rtol * np.abs(truth))

    def verdicts(self, check: Check, values: np.ndarray, truth: np.ndarray) -> tuple[str, str]:
        """What values say of the model, judged on the rows where the grader's measurement is
        clear of the thresholds by twice the tolerance: energy and reciprocity, in words."""
        n = self.albedo_count(check)
        tol = 2.0 * (check.atol + check.rtol * np.abs(truth))
        values = np.nan_to_num(np.asarray(values, np.float64), nan=0.0)
        clear_a = np.abs(truth[:n] - 1.0) > tol[:n]
        gain = bool((values[:n][clear_a] > 1.0).any())
        clear_r = (truth[n:] > RECIPROCAL + tol[n:]) | (truth[n:] < RECIPROCAL - tol[n:])
        broken = bool((values[n:][clear_r] > RECIPROCAL).any())
        energy = WORDS["gains"] if gain else WORDS["conserves"]
        return energy, (WORDS["not_reciprocal"] if broken else WORDS["reciprocal"])

    def compare(self, check: Check, expected: np.ndarray, raw: np.ndarray) -> CheckResult:
        got, truth = raw[0], raw[1]
        n, rows = self.albedo_count(check), self.rows(check)
        off = self._off(check, got, truth)
        extra = {
            "extra": {
                "rows": rows.tolist(),
                "got": got.tolist(),
                "truth": truth.tolist(),
                "albedo_rows": n,
                "off": np.flatnonzero(off).tolist(),
            }
        }
        mine, real = self.verdicts(check, got, truth), self.verdicts(check, truth, truth)
        found = WORDS["found"].format(energy=real[0], reciprocity=real[1])
        if not off.any() and mine == real:
            largest = WORDS["largest"].format(albedo=truth[:n].max())
            if len(truth) > n:
                largest = WORDS["largest_error"].format(
                    albedo=truth[:n].max(), error=truth[n:].max()
                )
            return passed(check, WORDS["passes"].format(found=found, largest=largest), **extra)
        parts = []
        if off[:n].any():
            k = int(np.flatnonzero(off[:n])[0])
            said = {"theta": rows[k, 2], "got": got[k], "truth": truth[k]}
            parts.append(WORDS["albedo_off"].format(count=int(off[:n].sum()), n=n, **said))
        if off[n:].any():
            k = n + int(np.flatnonzero(off[n:])[0])
            said = dict(zip(("tl", "pl", "tv", "pv"), rows[k], strict=True))
            said.update(count=int(off[n:].sum()), n=len(truth) - n, got=got[k], truth=truth[k])
            parts.append(WORDS["pairs_off"].format(**said))
        if mine != real:
            parts.append(
                WORDS["verdicts_off"].format(energy=mine[0], reciprocity=mine[1], found=found)
            )
        return failed(check, "; ".join(parts), **extra)

    def differs(self, check: Check, values: np.ndarray, reference: np.ndarray) -> bool:
        values = np.asarray(values)
        if values.shape != reference.shape:
            return True
        truth = reference[1]
        return bool(self._off(check, values[0], truth).any()) or self.verdicts(
            check, values[0], truth
        ) != self.verdicts(check, truth, truth)

    def nearest(self, check: Check, got, expected, candidates: dict) -> str | None:
        """The known mistake whose values the student's match at every row (within the
        check's tolerance), the closest of them."""
        got = np.nan_to_num(np.asarray(got, np.float64), nan=np.inf)
        best, best_off = None, np.inf
        for key, other in candidates.items():
            if other.shape != got.shape:
                continue
            scale = check.atol + check.rtol * np.abs(other[0])
            off = float(np.max(np.abs(got[0] - other[0]) / scale)) if got.shape[1] else 0.0
            if off <= 1.0 and off < best_off:
                best, best_off = key, off
        return best

    def explain(self, explainer, exercise, check, model, expected, got, live: bool) -> str:
        """A test that gives one value whatever it measures (a test that always says
        "pass"): said when no known mistake matched."""
        if got is None or np.ndim(got) != 2 or got.shape[0] != 2:
            return ""
        n, (mine, truth) = self.albedo_count(check), np.asarray(got, np.float64)
        said = []
        for what, part, real in (
            ("directional_albedo", mine[:n], truth[:n]),
            ("reciprocity_error", mine[n:], truth[n:]),
        ):
            tol = check.atol + check.rtol * np.abs(real)
            if len(part) > 1 and np.ptp(part) == 0.0 and np.ptp(real) > tol.max():
                said.append(WORDS["same_value"].format(what=what, value=part[0]))
        if not said:  # values the definitions rule out: an error in [0, 1], an albedo >= 0
            errors = np.nan_to_num(mine[n:])
            if (errors < -1e-6).any():
                return WORDS["negative_error"]
            if (errors > 1.0 + 1e-4).any():
                return WORDS["error_above_one"].format(value=errors.max())
            if (np.nan_to_num(mine[:n]) < -1e-6).any():
                return WORDS["negative_albedo"]
            target = target_model(check.options["target"])
            channels = _TRUTHS.get(self._key(target, check))  # the render has just made it
            if channels is None and explainer is not None:
                channels = self.channels(explainer.grader.renderer, target, check)
            return "" if channels is None else reduction(check, n, mine, channels)
        return WORDS["constant"].format(said="; ".join(said))

    # -- report --------------------------------------------------------------------------
    SHOWN_PAIRS = 8  # reciprocity rows in the report: the failing ones, else the largest

    def figures(self, result: CheckResult) -> list[str]:
        """A table of the albedo rows and a few reciprocity pairs: yours, the grader's, and
        a mark on each row outside the tolerance (not colour alone)."""
        data = result.extra
        if not data.get("rows"):
            return []
        n, off = data["albedo_rows"], set(data.get("off", []))
        pairs = [k for k in sorted(off) if k >= n][: self.SHOWN_PAIRS]
        if not pairs and len(data["truth"]) > n:
            pairs = [n + int(np.argmax(data["truth"][n:]))]
        lines = []
        for k in [*range(n), *pairs]:
            row, got, truth = data["rows"][k], data["got"][k], data["truth"][k]
            angles = ", ".join(f"{a:.0f}°" for a in row)
            what = (
                f"directional_albedo, θV = {row[2]:.1f}°"
                if k < n
                else f"reciprocity_error, (θL, φL, θV, φV) = ({angles})"
            )
            mark = "✗ differs" if k in off else "✓"
            lines.append(
                f"<tr><td>{html.escape(what)}</td><td>{got:.4g}</td><td>{truth:.4g}</td>"
                f"<td>{mark}</td></tr>"
            )
        hidden = sum(1 for k in off if k >= n) - sum(1 for k in pairs if k in off)
        more = f" ({hidden} more pairs differ)" if hidden > 0 else ""
        return [
            # A region of its own that scrolls (by keyboard too) on a narrow screen.
            '<figure class="properties"><div style="overflow-x: auto" tabindex="0" role="region"'
            ' aria-label="your values and the grader\'s"><table><thead><tr><th scope="col">row</th>'
            '<th scope="col">yours</th><th scope="col">grader\'s</th>'
            '<th scope="col">within tolerance</th></tr></thead><tbody>'
            + "".join(lines)
            + "</tbody></table></div><figcaption>your tests' values beside the grader's "
            f"measurement of the same model{more}</figcaption></figure>"
        ]

    def practice(self, exercise, check: Check, values) -> dict:
        """What the page's properties.js needs to run the check as this kind does: the rows
        and frame, the model the tests are linked with (a library model by name, a file of
        the exercise by its text), and the grader's measurement of it (the committed
        reference's second row: the page never measures, so its verdicts follow from the
        same numbers)."""
        target = check.options["target"]
        if target.endswith(".glsl"):
            path = Path(target)
            inside = path.relative_to(exercise.folder.resolve()).as_posix()
            linked_with = {
                "name": path.stem,
                "path": f"exercises/{exercise.name}/{inside}",
                "source": path.read_text(encoding="utf-8"),
            }
        else:
            linked_with = {"name": target}
        return {
            "options": {**check.options, "target": linked_with["name"]},
            "rows": self.rows(check).tolist(),
            "frame": self.frame(check).tolist(),
            "truth": np.asarray(values[check.name], np.float64)[1].tolist(),
            # per channel (explain's reductions); none in references made before it was kept
            "channels": values[f"{check.name}{CHANNELS}"].tolist()
            if f"{check.name}{CHANNELS}" in values
            else None,
            "luma": LUMA,  # the luminance reduction's weights, written once (lab/constants.py)
            "linked_with": linked_with,
            "prototype": PROTOTYPE,
            "reciprocal": RECIPROCAL,
            "words": WORDS,  # lab/grading/words.py: the page fills the same sentences
        }


def reduction(check: Check, n: int, mine: np.ndarray, channels: np.ndarray) -> str:
    """A test that reduces the colour channels to one number otherwise than by the largest
    (the smallest, the mean, one channel, the luminance): its values are that reduction of
    the grader's measurement per channel at every row of the part, and not the largest's.
    Whatever code reduces so shows it: the values say which reduction, not the text."""
    said = []
    for what, part, per in (
        ("directional_albedo", mine[:n], channels[:n]),
        ("reciprocity_error", mine[n:], channels[n:]),
    ):
        if len(part) == 0 or not np.isfinite(part).all():
            continue
        largest = per.max(axis=1)
        if (np.abs(part - largest) <= check.atol + check.rtol * np.abs(largest)).all():
            continue
        alike = [
            WORDS[f"by_{name}"]
            for name, reduce in REDUCTIONS.items()
            if (np.abs(part - reduce(per)) <= check.atol + check.rtol * np.abs(reduce(per))).all()
        ]  # at these rows two may agree (red may be the smallest channel): both are said
        if alike:
            said.append(WORDS["reduced"].format(what=what, reduction=" or ".join(alike)))
    return WORDS["reduction"].format(said="; ".join(said)) if said else ""


@functools.lru_cache(maxsize=256)
def _rows(seed: int, n_albedo: int, n_grazing: int, n_pairs: int) -> np.ndarray:
    rng = np.random.default_rng(seed)
    spread = n_albedo - n_grazing
    edges = np.linspace(0.0, SPREAD, spread + 1)
    theta_v = list(rng.uniform(edges[:-1], edges[1:])) if spread else []
    g_edges = np.linspace(*GRAZING, n_grazing + 1)
    theta_v += list(rng.uniform(g_edges[:-1], g_edges[1:])) if n_grazing else []
    albedo = np.zeros((n_albedo, 4))
    albedo[:, 0] = -1.0
    albedo[:, 2] = theta_v
    albedo[:, 3] = rng.uniform(0.0, 360.0, n_albedo)
    theta = np.degrees(np.arccos(rng.uniform(0.1, 1.0, (n_pairs, 2))))
    phi = rng.uniform(0.0, 360.0, (n_pairs, 2))
    pairs = np.stack([theta[:, 0], phi[:, 0], theta[:, 1], phi[:, 1]], axis=1)
    table = np.concatenate([albedo, pairs])
    table.flags.writeable = False
    return table


KIND = PropertiesKind()

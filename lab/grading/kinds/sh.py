"""`kind = "sh"`: a student's real spherical harmonics and a lobe's projection (exercise 15).

The student's file defines `float sh_basis(int l, int m, vec3 w)`, the real orthonormal
harmonic Y_lm at the unit direction w, and `vec3 sh_coefficient(int l, int m, vec3 L)`, the
coefficient of the cosine-weighted lobe g(w) = f_r(L, w) cos(theta_w) of the `BRDF(L, V, N,
X, Y)` it calls but does not define. Both work in the shading frame's own coordinates (N = z,
X = x, Y = y). A check without a `target` runs sh_basis at `pairs` directions over the
whole sphere (a few near the poles and on the horizon among them), every (l, m) up to
`order`; a check with one links that library model after the file (as `properties` does)
and runs sh_coefficient for every (l, m) up to `order` at `incidences` light directions.

What the values should be is the lab's own, made apart from any student code: the basis is
lab/measured/sh.py's `real_sh` (numpy), the coefficients are its `Projector` on a fine
Gauss-Legendre grid of the target's lobe evaluated on the GPU (what the app's SH view shows).
Both travel with the render (row 1 of the raw values, the program's are row 0), so the
verdict never rests on the solution's numbers. Hidden mode draws the target's parameters in
the check's `ranges` and the directions and incidences from the drawn seed.
"""

from __future__ import annotations

import functools
import html

import numpy as np

from lab.glsl import ShaderCompileError
from lab.grading.kinds import CheckKind
from lab.grading.kinds.properties import PROTOTYPE, _from_target, linked, target_model
from lab.grading.result import CheckResult, failed, passed
from lab.grading.rowpass import row_at, run_rows
from lab.grading.spec import Check, ExerciseError
from lab.grading.words import SH as WORDS
from lab.models import Model, model_names

VIEW = "grade_sh"
LINKED_FOR_BASIS = "lambert"  # a basis check calls no BRDF; the file still needs one to link
GRID = (96, 192)  # the lab's quadrature of the truth: Gauss-Legendre cos(theta) x uniform phi
INCIDENCE = (10.0, 75.0)  # incidences are stratified over this range of theta_i, degrees
SPECIAL = ((0.5, 30.0), (179.5, 250.0), (90.0, 0.0), (90.0, 90.0), (90.0, 180.0), (90.0, 270.0))
_TRUTHS: dict[tuple, np.ndarray] = {}  # coefficients by target, parameters and incidences


def lm_pairs(order: int) -> np.ndarray:
    """(K, 2) rows (l, m), index l^2 + l + m, as lab.measured.sh orders them."""
    return np.array([(l, m) for l in range(order + 1) for m in range(-l, l + 1)], np.float64)  # noqa: E741


class SHKind(CheckKind):
    name = "sh"
    order = 72
    purpose_of = ""  # its directions and incidences are drawn from `seed`
    fields = {"target": "", "order": 4, "incidences": 2}

    # -- inputs ------------------------------------------------------------------------------
    def validate(self, check: Check, where: str) -> None:
        o, here = check.options, f"{where}: check {check.name}"
        if o["target"] and o["target"] not in model_names():
            raise ExerciseError(
                f"{here}: target {o['target']!r} is no library model ({', '.join(model_names())});"
                " leave it out to check sh_basis"
            )
        if not 0 <= o["order"] <= 8:
            raise ExerciseError(f"{here}: order must be 0 to 8")
        if not 1 <= o["incidences"] <= 16:
            raise ExerciseError(f"{here}: incidences must be 1 to 16")
        if not 1 <= check.pairs <= 1024:
            raise ExerciseError(f"{here}: pairs (basis directions) must be 1 to 1024")

    def projects(self, check: Check) -> bool:
        return bool(check.options["target"])

    def params_model(self, check: Check, model: Model) -> Model:
        """Hidden mode draws the target's parameters (its header, the check's ranges)."""
        return target_model(check.options["target"] or LINKED_FOR_BASIS)

    def rows(self, check: Check) -> np.ndarray:
        """(n, 4) rows l, m, theta, phi (degrees): the direction w of a basis check, the
        light L of a projection check; every (l, m) up to the order at each direction."""
        o = check.options
        return _rows(
            int(check.seed),
            int(o["order"]),
            self.projects(check),
            int(check.pairs),
            int(o["incidences"]),
        )

    # -- render --------------------------------------------------------------------------
    def render(self, renderer, model: Model, check: Check) -> np.ndarray:
        """(2, n, 3): the program's values at the rows, and the lab's there."""
        target = target_model(check.options["target"] or LINKED_FOR_BASIS)
        program = linked(model, target)
        rows = self.rows(check)
        # The lab's values first: the grader reads the loop guard of the last render.
        truth = self.truth(renderer, target, check)
        data = np.zeros((len(rows), 4), np.float32)
        data[:, :2] = rows[:, :2]
        data[:, 2:] = np.radians(rows[:, 2:])
        uniforms = {"u_rows": 0, "u_project": int(self.projects(check))}
        try:
            out = run_rows(renderer, program, VIEW, check.params, data, uniforms)
            got = out[:, :3].astype(np.float64)
        except ShaderCompileError as err:
            raise _from_target(err, model, target) from None
        return np.stack([got, truth])

    def truth(self, renderer, target: Model, check: Check) -> np.ndarray:
        """The lab's values at the check's rows (n, 3)."""
        from lab.measured import sh

        rows, order = self.rows(check), int(check.options["order"])
        index = (rows[:, 0] ** 2 + rows[:, 0] + rows[:, 1]).astype(int)
        if not self.projects(check):
            Y = sh.real_sh(order, np.radians(rows[:, 2]), np.radians(rows[:, 3]))
            return np.repeat(Y[np.arange(len(rows)), index][:, None], 3, axis=1)
        key = (target.name, target.code, repr(sorted(check.params.items())), rows.tobytes())
        found = _TRUTHS.get(key)
        if found is None:
            projector = _projector(order)
            V = projector.grid.directions
            out = np.empty((len(rows), 3))
            for start in range(0, len(rows), len(index) // int(check.options["incidences"])):
                theta, phi = np.radians(rows[start, 2:])
                light = [np.sin(theta) * np.cos(phi), np.sin(theta) * np.sin(phi), np.cos(theta)]
                L = np.repeat(np.array([light]), len(V), axis=0)
                f = renderer.probe(target, check.params, L, V).astype(np.float64)
                block = slice(start, start + sh.coefficient_count(order))
                out[block] = projector.project(f * V[:, 2:3])[index[block]]
            if len(_TRUTHS) >= 64:
                _TRUTHS.clear()
            found = _TRUTHS[key] = out
        return found.copy()

    def stored(self, raw: np.ndarray, check: Check) -> np.ndarray:
        """float32, as the GPU gives them: every stored mistake's values are kept per check."""
        return np.asarray(raw, np.float32)

    def where(self, check: Check, x: int, y: int) -> str:
        rows = self.rows(check)
        l, m, theta, phi = rows[min(row_at(x, y), len(rows) - 1)]  # noqa: E741
        said = {"l": int(l), "m": int(m), "theta": theta, "phi": phi}
        return WORDS["coefficient_at" if self.projects(check) else "basis_at"].format(**said)

    # -- compare -------------------------------------------------------------------------
    @staticmethod
    def _off(check: Check, got: np.ndarray, truth: np.ndarray) -> np.ndarray:
        """Rows where some channel of `got` is outside the tolerance of `truth`."""
        got = np.nan_to_num(np.asarray(got, np.float64), nan=np.inf)
        return ~(np.abs(got - truth) <= check.atol + check.rtol * np.abs(truth)).all(axis=-1)

    def lobe_error(self, check: Check, got: np.ndarray, truth: np.ndarray) -> float:
        """The largest relative L2 distance, over the incidences, between the lobe rebuilt
        from `got` and from `truth`: by Parseval, the coefficients' own distance."""
        if not self.projects(check):
            return 0.0
        got = np.nan_to_num(np.asarray(got, np.float64), nan=1e30, posinf=1e30, neginf=-1e30)
        count = (int(check.options["order"]) + 1) ** 2
        worst = 0.0
        for start in range(0, len(truth), count):
            a, b = got[start : start + count], truth[start : start + count]
            worst = max(worst, float(np.linalg.norm(a - b) / max(np.linalg.norm(b), 1e-30)))
        return min(worst, 10.0)  # past 1000 % the figure says nothing more

    def compare(self, check: Check, expected: np.ndarray, raw: np.ndarray) -> CheckResult:
        got, truth = raw[0], raw[1]
        rows, off = self.rows(check), self._off(check, raw[0], raw[1])
        error = self.lobe_error(check, got, truth)
        extra = {
            "extra": {
                "rows": rows.tolist(),
                "got": got.max(axis=1).tolist(),
                "truth": truth.max(axis=1).tolist(),
                "off": np.flatnonzero(off).tolist(),
            }
        }
        if not off.any():
            if self.projects(check):
                return passed(check, WORDS["coefficients_pass"].format(error=error), **extra)
            said = {"n": len(rows), "largest": float(np.abs(truth).max())}
            return passed(check, WORDS["basis_passes"].format(**said), **extra)
        k = int(np.flatnonzero(off)[0])
        c = int(np.argmax(np.abs(got[k] - truth[k])))
        said = {
            "count": int(off.sum()),
            "n": len(rows),
            "l": int(rows[k, 0]),
            "m": int(rows[k, 1]),
            "theta": rows[k, 2],
            "phi": rows[k, 3],
            "got": got[k, c],
            "truth": truth[k, c],
            "error": error,
        }
        words = WORDS["coefficients_off" if self.projects(check) else "basis_off"]
        return failed(check, words.format(**said), **extra)

    def differs(self, check: Check, values: np.ndarray, reference: np.ndarray) -> bool:
        values = np.asarray(values)
        if values.shape != reference.shape:
            return True
        return bool(self._off(check, values[0], reference[1]).any())

    def nearest(self, check: Check, got, expected, candidates: dict) -> str | None:
        """The known mistake whose values the student's match at every row (within the
        check's tolerance), the closest of them."""
        got = np.nan_to_num(np.asarray(got, np.float64), nan=np.inf)
        rows = self.rows(check)
        best, best_off = None, np.inf
        for key, other in candidates.items():
            if np.shape(other) != got.shape:
                continue
            # A mistake that moves one harmonic alone (a Lambert lobe has one) is told apart
            # from another only by that value's size: no evidence of which mistake it is.
            moved = self._off(check, other[0], other[1])
            if len({(int(l), int(m)) for l, m in rows[moved, :2]}) < 2:  # noqa: E741
                continue
            scale = check.atol + check.rtol * np.abs(other[0])
            off = float(np.max(np.abs(got[0] - other[0]) / scale)) if got.shape[1] else 0.0
            if off <= 1.0 and off < best_off:
                best, best_off = key, off
        return best

    def explain(self, explainer, exercise, check, model, expected, got, live: bool) -> str:
        """Values the lab's up to a sign on a family of (l, m), or up to one factor: said
        when no known mistake matched."""
        if got is None or np.ndim(got) != 3 or np.shape(got)[0] != 2:
            return ""
        mine, truth = np.nan_to_num(np.asarray(got, np.float64))
        rows, tol = self.rows(check), check.atol + check.rtol * np.abs(truth)
        bad = self._off(check, mine, truth)
        same_size = (np.abs(np.abs(mine) - np.abs(truth)) <= tol).all()
        if same_size and bad.any():
            l, m = rows[:, 0], rows[:, 1]  # noqa: E741
            families = {
                "m is odd": m % 2 != 0,
                "m < 0": m < 0,
                "m > 0": m > 0,
                "l is odd": l % 2 != 0,
                "l + |m| is odd": (l + np.abs(m)) % 2 != 0,
            }
            flipped = bad & (np.abs(truth) > tol).any(axis=1)
            for words, family in families.items():
                if flipped.any() and not (flipped & ~family).any():
                    return WORDS["sign_only"].format(where=words)
        big = np.abs(truth) > 10.0 * tol
        if big.sum() >= 3:
            ratio = mine[big] / truth[big]
            factor = float(np.median(ratio))
            # every value, the lab's zeros too, is the lab's times that factor
            close = np.abs(mine - factor * truth) <= 2.0 * tol * max(1.0, abs(factor))
            # a factor near 0 is values that are all but zero (a stub's): no factor to name
            if abs(factor - 1.0) > 0.01 and abs(factor) > 0.01 and close.all():
                return WORDS["scaled"].format(factor=factor)
        return ""

    # -- the page ------------------------------------------------------------------------
    def practice(self, exercise, check: Check, values) -> dict:
        """What the page's shcheck.js needs to run the check as this kind does: the
        directions (the page repeats every (l, m) up to the order at each, as `_rows`), the
        model linked after the file, and the lab's values (the committed reference's second
        row: the page never projects, so its verdicts follow from the same numbers)."""
        rows = self.rows(check)
        count = (int(check.options["order"]) + 1) ** 2
        return {
            "options": {**check.options, "target": check.options["target"] or LINKED_FOR_BASIS},
            "directions": rows[::count, 2:].tolist(),  # degrees, theta and phi
            # (n, 3) flat, float32's shortest digits (1e-14 stays); a basis check's one channel
            "truth": [float(str(v)) for v in self.shipped(check, values[check.name], 1, True)],
            "linked_with": {"name": check.options["target"] or LINKED_FOR_BASIS},
            "prototype": PROTOTYPE,
            "project": self.projects(check),
            "words": WORDS,  # lab/grading/words.py: the page fills the same sentences
        }

    def shipped(self, check: Check, raw: np.ndarray, row: int = 1, single=False) -> np.ndarray:
        """Row `row` of stored values as the page reads them, flat: a basis check's channels
        are one value (the view writes vec3(sh_basis)), so its first channel alone."""
        values = np.asarray(raw, np.float32 if single else np.float64)[row]
        return (values if self.projects(check) else values[:, :1]).ravel()

    # -- report --------------------------------------------------------------------------
    SHOWN = 12  # rows in the report's table: the failing ones first

    def figures(self, result: CheckResult) -> list[str]:
        """A table of a few rows: (l, m), the direction, yours, the lab's, and a mark on each
        row outside the tolerance (not colour alone)."""
        data = result.extra
        if not data.get("rows"):
            return []
        off = data.get("off", [])
        shown = (off or list(range(len(data["rows"]))))[: self.SHOWN]
        lines = []
        for k in shown:
            l, m, theta, phi = data["rows"][k]  # noqa: E741
            mark = "✗ differs" if k in off else "✓"
            lines.append(
                f"<tr><td>({int(l)}, {int(m)}) at ({theta:.1f}°, {phi:.1f}°)</td>"
                f"<td>{data['got'][k]:.4g}</td><td>{data['truth'][k]:.4g}</td><td>{mark}</td></tr>"
            )
        more = f" ({len(off) - len(shown)} more rows differ)" if len(off) > len(shown) else ""
        return [
            '<figure class="sh"><div style="overflow-x: auto" tabindex="0" role="region"'
            ' aria-label="your values and the lab\'s"><table><thead><tr><th scope="col">(l, m) at'
            ' (θ, φ)</th><th scope="col">yours</th><th scope="col">lab\'s</th>'
            '<th scope="col">within tolerance</th></tr></thead><tbody>'
            + "".join(lines)
            + "</tbody></table></div><figcaption>"
            + html.escape(f"your values beside the lab's (largest channel){more}")
            + "</figcaption></figure>"
        ]


@functools.lru_cache(maxsize=4)
def _projector(order: int):
    from lab.measured import sh

    return sh.Projector(order, sh.hemisphere_grid(*GRID))


@functools.lru_cache(maxsize=256)
def _rows(seed: int, order: int, project: bool, pairs: int, incidences: int) -> np.ndarray:
    rng = np.random.default_rng(seed)
    if project:
        edges = np.linspace(*INCIDENCE, incidences + 1)
        directions = np.stack([rng.uniform(edges[:-1], edges[1:]), rng.uniform(0, 360, incidences)])
    else:
        theta = np.degrees(np.arccos(rng.uniform(-1.0, 1.0, pairs)))
        directions = np.concatenate([np.array(SPECIAL).T, [theta, rng.uniform(0, 360, pairs)]], 1)
    lm = lm_pairs(order)
    table = np.concatenate(
        [np.concatenate([lm, np.repeat([d], len(lm), axis=0)], 1) for d in directions.T]
    )
    table.flags.writeable = False
    return table


KIND = SHKind()

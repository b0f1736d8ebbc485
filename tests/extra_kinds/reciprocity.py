"""`kind = "reciprocity"`: f_r(L, V) = f_r(V, L) on `samples` random pairs (Helmholtz), and
f_r(L, V) as the solution's. Its table adds `samples`; its report adds the worst pair."""

from __future__ import annotations

import html

import numpy as np

from lab.grading.kinds import CheckKind
from lab.grading.result import failed, passed
from lab.grading.spec import Check, ExerciseError


class ReciprocityKind(CheckKind):
    name = "reciprocity"
    fields = {"samples": 64}

    def validate(self, check: Check, where: str) -> None:
        if check.options["samples"] < 1:
            raise ExerciseError(f"{where}: check {check.name}: samples must be at least 1")

    def angles(self, check: Check) -> np.ndarray:
        rng = np.random.default_rng(check.seed)
        n = check.options["samples"]
        theta = np.degrees(np.arccos(rng.uniform(0.1, 1.0, (n, 2))))
        phi = rng.uniform(0.0, 360.0, (n, 2))
        return np.stack([theta[:, 0], phi[:, 0], theta[:, 1], phi[:, 1]], axis=1)

    def render(self, renderer, model, check: Check) -> np.ndarray:
        rows = self.angles(check)
        both = np.concatenate([rows, rows[:, [2, 3, 0, 1]]])
        return renderer.eval_angles(model, check.params, both).reshape(2, len(rows), 3)

    def compare(self, check: Check, expected: np.ndarray, raw: np.ndarray):
        forward, backward = raw
        tol = check.atol + check.rtol * np.abs(forward)
        broken = (np.abs(forward - backward) > tol).any(axis=-1)
        off = (np.abs(forward - expected[0]) > check.atol + check.rtol * np.abs(expected[0])).any(
            axis=-1
        )
        worst = int(np.argmax(np.abs(forward - backward).max(axis=-1)))
        extra = {"extra": {"worst": (float(forward[worst, 0]), float(backward[worst, 0]))}}
        n = len(forward)
        if broken.any():
            return failed(check, f"{int(broken.sum())} of {n} pairs break reciprocity", **extra)
        if off.any():
            return failed(check, f"{int(off.sum())} of {n} pairs differ from the solution", **extra)
        return passed(check, f"f(L, V) = f(V, L) on all {n} pairs", **extra)

    def figures(self, result) -> list[str]:
        forward, backward = result.extra.get("worst", (0.0, 0.0))
        text = f"worst pair: f(L, V) = {forward:.4g}, f(V, L) = {backward:.4g}"
        return [f'<figure class="reciprocity">{html.escape(text)}</figure>']


KIND = ReciprocityKind()

"""What the three sampling kinds (chi_square, pdf_integral, ibl_render) share: their
`views` option, checked, and the directions they test (lab.grading.sampling does the
numbers)."""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from lab.grading import diagnosis, sampling
from lab.grading.kinds import CheckKind
from lab.grading.spec import Check, ExerciseError
from lab.ibl import chisquare


class SampledKind(CheckKind):
    """A kind that runs the model's BRDF sampler and pdf (an exercise with sampler_for)."""

    order = 50

    def validate(self, check: Check, where: str) -> None:
        views = check.options.get("views")
        if views is None:
            return
        for view in views:
            ok = isinstance(view, list) and len(view) == 2
            ok = ok and all(isinstance(v, (int, float)) for v in view) and 0 <= view[0] < 90
            if not ok:
                raise ExerciseError(
                    f"{where}: check {check.name}: views = {views!r}: each view is "
                    "[theta, phi] in degrees with 0 <= theta < 90, e.g. views = [[10.0, 0.0]]"
                )
        if not 0.0 <= check.theta_i < 90.0:
            raise ExerciseError(f"{where}: check {check.name}: theta_i must lie in [0, 90)")

    def views(self, check: Check) -> list[tuple[float, float]]:
        """The declared views and the check's (theta_i, phi_i), random in hidden mode."""
        return sampling.views_of(check.options["views"], check.theta_i, check.phi_i)

    def where(self, check: Check, x: int, y: int) -> str:
        return f"sample {y * 1024 + x}"

    def practice_views(self, check: Check) -> dict:
        """The views as the page's practice mode runs them: angles, V in the local frame
        and each view's turned shading frame (rows X, Y, N), computed here so that the page
        samples and integrates exactly the grader's directions (web/static/sampling.js)."""
        views = self.views(check)
        return {
            "rules": page_rules(),
            "views": [list(v) for v in views],
            "V": [chisquare.view_direction(t, p).tolist() for t, p in views],
            "frames": [
                chisquare.random_frame(check.seed * 31 + i).tolist() for i in range(len(views))
            ],
        }

    # Hidden mode: a sampling check's own values cost a full run each (100,000 samples and
    # the pdf per bin, or a converged render); a likely wrong program is told apart by its
    # sampler, pdf and BRDF at a few hundred inputs instead, once per submission.
    by_program = True

    def live_values(self, renderer, model, check: Check) -> np.ndarray:
        return sampling.fingerprint(renderer, model, check.params, check.seed)

    def live_same(self, check: Check, values, other) -> bool:
        exact = replace(check, rtol=1e-3, atol=1e-4)
        return values.shape == other.shape and diagnosis.same(exact, values, other)

    def live_match(self, check: Check, mine, solution, candidates: dict) -> str | None:
        exact = replace(check, rtol=1e-3, atol=1e-4)
        wrong = ~diagnosis.within(exact, mine, solution, slack=1.0)
        if not wrong.any():
            return None  # the program behaves as the solution's here: nothing to name
        return diagnosis.nearest(exact, mine, candidates, wrong)


def page_rules() -> dict:
    """The sampling checks' words, bins and thresholds, as the page's sampling.js takes
    them (it carries the mechanisms: the quadrature, Pearson's test, the histograms)."""
    return {
        "words": sampling.WORDS,
        "bins": [chisquare.THETA_BINS, chisquare.PHI_BINS],
        "min_expected": chisquare.MIN_EXPECTED,
        "sub": chisquare.SUB,
        "tolerance": chisquare.TOLERANCE,
        "max_levels": chisquare.MAX_LEVELS,
        "max_cells": chisquare.MAX_CELLS,
        "redraw": sampling.REDRAW,
        "decisive": sampling.DECISIVE,
        "usable": sampling.USABLE,
        "z_integral": sampling.Z_INTEGRAL,
    }

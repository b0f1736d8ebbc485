"""`kind = "chi_square"`: the student's BRDF sampler against the student's own pdf.

`samples` directions per view (`views`, plus the check's theta_i / phi_i) in shading frames
turned away from the axes are binned over (cos theta, phi) and compared with the pdf
integrated over each bin: Pearson's test, low bins pooled, significance `alpha` for all
views together (Šidák), as pbrt-v4's BSDF tests do. A draw that fails by a margin chance
could give is drawn again, independently, and only the second counts: a correct sampler
fails with probability about alpha² (lab.grading.sampling.chi_square_raw). The reference
(the solution's numbers) only serves the report and the explanation of a failure.
"""

from __future__ import annotations

import numpy as np

from lab.grading import sampling
from lab.grading.compare import png
from lab.grading.kinds.sampled import SampledKind
from lab.grading.kinds.values import floats_b64
from lab.grading.result import CheckResult, failed, passed
from lab.grading.spec import Check, ExerciseError


class ChiSquareKind(SampledKind):
    name = "chi_square"
    order = 50
    fields = {"views": [[10.0, 0.0], [70.0, 130.0]], "samples": 100_000, "alpha": 0.002}
    captions = {
        "your pdf": "your pdf × samples over (cos θ, φ): θ down from the normal, φ across",
        "your samples": "your samples, counted in the same bins",
        "solution's pdf": "the solution's pdf, for comparison",
    }

    def validate(self, check: Check, where: str) -> None:
        super().validate(check, where)
        if not 1000 <= check.options["samples"] <= 4_000_000:
            raise ExerciseError(f"{where}: check {check.name}: samples must be 1000 to 4000000")
        if not 0.0 < check.options["alpha"] < 0.5:
            raise ExerciseError(f"{where}: check {check.name}: alpha must lie in (0, 0.5)")

    def render(self, renderer, model, check: Check) -> np.ndarray:
        o = check.options
        return sampling.chi_square_raw(
            renderer, model, check.params, self.views(check), o["samples"], check.seed, o["alpha"]
        )

    def compare(self, check: Check, expected: np.ndarray, raw: np.ndarray) -> CheckResult:
        samples, views = check.options["samples"], self.views(check)
        ok, message, worst = sampling.judge_chi_square(raw, views, samples, check.options["alpha"])
        view = max(worst, 0)
        _, mine_pdf, _ = sampling._split(raw[view])
        mine, _, _ = sampling._split(raw[view])
        solution = expected[view, 800:1600] if expected is not None else None
        if solution is not None and expected.shape != raw.shape:
            solution = None
        # One scale for the three pictures, so that none saturates (a pdf of 0 next to the
        # solution's would otherwise leave the solution's all white).
        shown = [mine_pdf, mine] + ([solution] if solution is not None else [])
        peak = max(max(float(h.max()) for h in shown), 1.0)
        images = {
            "your pdf": png(sampling.histogram_image(mine_pdf, peak)),
            "your samples": png(sampling.histogram_image(mine, peak)),
        }
        if solution is not None:
            images["solution's pdf"] = png(sampling.histogram_image(solution, peak))
        extra = {"images": images, "extra": {"view": list(views[view])}}
        return passed(check, message, **extra) if ok else failed(check, message, **extra)

    def practice(self, exercise, check: Check, values) -> dict:
        # The solution's numbers: the page's explanation compares with them (explain).
        return {
            **self.practice_views(check),
            "captions": self.captions,  # the histograms' titles
            "solution": floats_b64(values[check.name]),
        }

    def differs(self, check: Check, values: np.ndarray, reference: np.ndarray) -> bool:
        samples, views = check.options["samples"], self.views(check)
        if values.shape != (len(views), sampling.COLUMNS):
            return True
        return not sampling.judge_chi_square(values, views, samples, check.options["alpha"])[0]

    def nearest(self, check: Check, got, expected, candidates: dict) -> str | None:
        samples = check.options["samples"]
        for key, other in candidates.items():
            if sampling.same_chi_square(got, other, samples):
                return key
        return None

    def explain(self, explainer, exercise, check, model, expected, got, live: bool) -> str:
        """Which half is wrong: the pdf (it differs from the solution's) or the sampler (the
        samples differ from the solution's while the pdf agrees)."""
        samples = check.options["samples"]
        if expected is None or expected.shape != got.shape:
            return ""
        pdf_off = any(
            np.abs(g[800:1600] - e[800:1600]).sum() > 0.02 * samples
            for g, e in zip(got, expected, strict=True)
        )
        mine_only = got.copy()
        mine_only[:, 800:1600] = expected[:, 800:1600]
        samples_like = sampling.same_chi_square(mine_only, expected, samples)
        if pdf_off and samples_like:
            return sampling.WORDS["pdf_wrong"]
        if not pdf_off and not samples_like:
            return sampling.WORDS["sampler_wrong"]
        return ""


KIND = ChiSquareKind()

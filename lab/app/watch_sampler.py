"""`brdf-lab watch` on a sampling exercise's file (exercise 10): the student's sampler,
judged as the grader judges it.

On each save the exercise's chi-square and pdf-integral checks run with the grader's own
code and print their verdicts; the window shows where the samples land beside what the
student's pdf predicts (and the solution's pdf), over (cos θ, φ) bins, as the report does.
An estimator exercise's file (14: `estimator = true`) is judged by its ibl_render checks, a
fraction of a second each, and the window shows its render beside the reference.
"""

from __future__ import annotations

import io
from pathlib import Path

import numpy as np

from lab.app.student_file import StudentFile

SHOWN_KINDS = ("chi_square", "pdf_integral")  # quick enough to rerun on every save
PANELS = ("your samples", "your pdf", "solution's pdf")
RENDER_PANELS = ("yours, converged", "converged reference", "yours")  # an estimator's


class SamplerView(StudentFile):
    """The checks of a sampling exercise that run in a second, on the student's file."""

    def __init__(self, path: Path):
        super().__init__(path)
        shown = (*SHOWN_KINDS, "ibl_render") if self.exercise.estimator else SHOWN_KINDS
        self.checks = [c for c in self.exercise.checks if c.kind in shown]
        self.left_out = [c.name for c in self.exercise.checks if c.kind not in shown]

    def shows(self) -> bool:
        return bool(self.exercise.sampler_for and self.checks)

    def judge(self, renderer, model) -> tuple[list[str], list[np.ndarray]]:
        """Each check's verdict line, and the histograms of the first chi-square check
        (its worst view) as RGBA panels."""
        from lab.grading.kinds import kind_of

        lines: list[str] = []
        panels: list[np.ndarray] = []
        for check in self.checks:
            kind = kind_of(check)
            try:
                expected = kind.load_reference(self.exercise, check)
            except (OSError, KeyError):
                expected = None
            result = kind.compare(check, expected, kind.render(renderer, model, check))
            lines.append(
                f"  {check.name}: {'passed' if result.passed else 'FAILED'}: {result.message}"
            )
            if not panels and result.images and check.kind == "ibl_render":
                panels = [
                    captioned(result.images[label], label, note=check.name)
                    for label in RENDER_PANELS
                    if label in result.images
                ]
            elif not panels and result.images:
                view = result.extra.get("view", [0.0, 0.0])
                where = f"view θ {view[0]:.0f}°, φ {view[1]:.0f}°"
                panels = [
                    captioned(result.images[label], f"{label} ({where})")
                    for label in PANELS
                    if label in result.images
                ]
        if self.left_out:
            lines.append(f"  not run here (brdf-lab grade runs them): {', '.join(self.left_out)}")
        return lines, panels


def captioned(
    png: bytes, caption: str, size: int = 320, note: str = "θ down from the normal, φ across"
) -> np.ndarray:
    """A report histogram or render (PNG) scaled to the panel's width under its caption,
    with `note` below it, RGBA uint8."""
    from matplotlib import font_manager
    from PIL import Image, ImageDraw, ImageFont

    font_file = font_manager.findfont("DejaVu Sans")  # matplotlib's own: it has θ and φ

    histogram = Image.open(io.BytesIO(png)).convert("RGB")
    margin = 8  # the panels sit side by side: keep their pictures apart
    # As wide as the panel, or (a square render) as tall as leaves room for the words.
    scale = min((size - 2 * margin) / histogram.width, (size - 72) / histogram.height)
    width, height = round(histogram.width * scale), round(histogram.height * scale)
    histogram = histogram.resize((width, height), Image.NEAREST)
    panel = Image.new("RGB", (size, size), (41, 41, 43))
    draw = ImageDraw.Draw(panel)
    font = ImageFont.truetype(font_file, 15)
    draw.text((margin, 10), caption, fill=(235, 235, 235), font=font)
    top = (size - height) // 2
    panel.paste(histogram, ((size - width) // 2, top))
    small = ImageFont.truetype(font_file, 13)
    draw.text((8, top + height + 8), note, fill=(190, 190, 190), font=small)
    return np.dstack([np.asarray(panel), np.full((size, size), 255, np.uint8)])

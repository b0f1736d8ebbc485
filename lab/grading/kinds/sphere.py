"""`kind = "sphere"`: the lit sphere image (`size`, `lights`, `ambient`, grading template
`view`), tone-mapped to 8 bits and compared pixel by pixel with a threshold, a maximum
failing fraction and mean FLIP."""

from __future__ import annotations

import base64
import hashlib
import math

import numpy as np

from lab.geometry import direction
from lab.grading.compare import bad_values, image8, mean_flip, png, read_png, tonemap
from lab.grading.kinds import CheckKind
from lab.grading.result import CheckResult, failed, passed
from lab.grading.spec import Check
from lab.grading.visuals import failing_overlay, signed_difference
from lab.render import Light, light_uniforms


def share_off(check: Check, image: np.ndarray, other: np.ndarray) -> float:
    """Share of the covered pixels of two 8-bit images that differ by more than threshold."""
    covered = image[..., 3] > 127
    diff = np.abs(image[..., :3].astype(int) - other[..., :3].astype(int)).max(axis=-1)
    return float((diff[covered] > check.threshold).mean()) if covered.any() else 0.0


_PNGS: dict[tuple, bytes] = {}  # reference images as PNG: a class shares them


def _reference_png(reference: np.ndarray) -> bytes:
    key = (reference.shape, hashlib.blake2b(reference.tobytes(), digest_size=16).digest())
    if key not in _PNGS:
        if len(_PNGS) > 64:
            _PNGS.clear()
        _PNGS[key] = png(reference[..., :3])
    return _PNGS[key]


class SphereKind(CheckKind):
    name = "sphere"
    order = 20
    purpose_of = "lights"  # each light's angle from the view axis
    captions = {
        "reference": "solution",
        "student": "yours",
        "difference": "yours − solution",
        "failing pixels": "failing pixels (orange)",
    }
    alts = {  # what each image shows, for a screen reader
        "reference": "the solution's render of the lit sphere",
        "student": "your render of the lit sphere, from the same settings",
        "difference": "your render minus the solution's: red where yours is too bright, "
        "blue where too dark, pale where they agree",
        "failing pixels": "the solution's render in grey with the pixels that fail in orange",
    }

    # -- render --------------------------------------------------------------------------
    def render(self, renderer, model, check: Check) -> np.ndarray:
        lights = check.lights
        uniforms = {
            **light_uniforms(lights),
            "u_resolution": (float(check.size), float(check.size)),
            "u_ambient": tuple(check.ambient),
            "u_multiply_cos": True,
        }
        preamble = f"const int LIGHT_COUNT = {len(lights)};"
        # The sphere view's own plumbing, so grading templates (shaders/views/grade_*.glsl)
        # share it.
        return renderer.image(model, check.view, check.params, check.size, uniforms, preamble)

    def stored(self, raw: np.ndarray, check: Check) -> np.ndarray:
        """Tone-mapped to 8-bit RGBA: what the reference PNG holds."""
        return image8(raw)

    def where(self, check: Check, x: int, y: int) -> str:
        px, py = ((np.array([x, y]) + 0.5) / check.size) * 2.0 - 1.0
        normal = np.array([px, py, math.sqrt(max(1.0 - px * px - py * py, 0.0))])
        light = check.lights[0] if check.lights else Light(45.0)
        cos_i = np.clip(normal @ direction(light.theta, light.phi), -1, 1)
        theta_i = math.degrees(math.acos(cos_i))
        theta_o = math.degrees(math.acos(np.clip(normal[2], -1.0, 1.0)))
        angles = f"θi = {theta_i:.1f}°, θo = {theta_o:.1f}°"
        return f"pixel ({x}, {check.size - 1 - y}) of the sphere ({angles})"

    # -- compare -------------------------------------------------------------------------
    def compare(self, check: Check, expected: np.ndarray, raw: np.ndarray) -> CheckResult:
        """Per-channel threshold after tone mapping, a maximum failing fraction, mean FLIP."""
        reference = expected
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
        flip = (
            mean_flip(reference[..., :3], student8) if failing.any() or diff.max() >= 1.0 else 0.0
        )
        fails = bool(bad.any()) or fraction > check.max_fraction
        images = {"reference": _reference_png(reference), "student": png(shown)}
        if fails:  # the report shows the difference images of a failed check only
            # the channel that is off the most, with its sign: too bright or too dark
            pick = np.take_along_axis(delta, np.abs(delta).argmax(axis=-1)[..., None], axis=-1)
            signed = np.where(bad, 255.0, pick[..., 0])
            images["difference"] = png(signed_difference(signed, covered, check.threshold))
            images["failing pixels"] = png(failing_overlay(reference, failing))
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
        return passed(check, summary, **extra)

    def differs(self, check: Check, values: np.ndarray, reference: np.ndarray) -> bool:
        return share_off(check, reference, values) > check.max_fraction

    # -- reference -----------------------------------------------------------------------
    def save_reference(self, exercise, check: Check, reference: np.ndarray, values: dict) -> list:
        from PIL import Image

        path = exercise.references / f"{check.name}.png"
        Image.fromarray(reference, "RGBA").save(path)
        return [path]

    def load_reference(self, exercise, check: Check) -> np.ndarray:
        return read_png(exercise.references / f"{check.name}.png")

    # -- report --------------------------------------------------------------------------
    def nearest(self, check: Check, got, expected, candidates: dict) -> str | None:
        """The known mistake whose image the student's matches (nearly every pixel)."""
        best, best_share = None, 1.0
        for key, other in candidates.items():
            if other.shape != got.shape:
                continue
            share = share_off(check, other, got)
            if share <= max(check.max_fraction, 0.002) and share < best_share:
                best, best_share = key, share
        return best

    def practice(self, exercise, check: Check, values) -> dict:
        image = self.load_reference(exercise, check)
        return {"reference": base64.b64encode(np.ascontiguousarray(image).tobytes()).decode()}


KIND = SphereKind()

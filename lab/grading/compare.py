"""Comparisons the check kinds share: values within a tolerance, tone mapping, PNG files.

Plain numpy (and Pillow for PNG): no OpenGL, so the supervising process and the web
manifest can use it too.
"""

from __future__ import annotations

import io
import math
import os
import sys
from pathlib import Path

import numpy as np

from lab.constants import LUMA
from lab.grading.result import CheckResult, failed, passed
from lab.grading.spec import Check


def tonemap(rgb: np.ndarray) -> np.ndarray:
    """Radiance to display values in [0, 1) without clipping highlights (x/(1+x), gamma 2.2)."""
    x = np.maximum(np.nan_to_num(rgb, nan=0.0, posinf=1e30, neginf=0.0), 0.0)
    return (x / (1.0 + x)) ** (1.0 / 2.2)


def image8(raw: np.ndarray) -> np.ndarray:
    """A float RGBA render as the 8-bit RGBA image its reference is stored as."""
    rgb = (np.clip(tonemap(raw[..., :3]), 0, 1) * 255.0 + 0.5).astype(np.uint8)
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


def bad_values(values: np.ndarray) -> np.ndarray:
    """Mask of rows with NaN, Inf or negative output (no comparison may let these pass)."""
    return ~np.isfinite(values).all(axis=-1) | (np.nan_to_num(values) < 0.0).any(axis=-1)


def wrong_values(
    check: Check, expected: np.ndarray, got: np.ndarray, tolerance: np.ndarray | None = None
) -> np.ndarray:
    """Mask of rows that are broken or off by more than `tolerance` (per value; by default
    atol + rtol |expected|)."""
    if tolerance is None:
        tolerance = check.atol + check.rtol * np.abs(expected)
    error = np.abs(np.nan_to_num(got, nan=np.inf) - expected)
    return bad_values(got) | (error > tolerance).any(axis=-1)


def fmt_rgb(rgb) -> str:
    r, g, b = (float(c) for c in rgb)
    if r == g == b or (math.isnan(r) and math.isnan(g) and math.isnan(b)):
        return f"{r:.5g}"
    return f"({r:.4g}, {g:.4g}, {b:.4g})"


def compare_values(
    check: Check,
    angles: np.ndarray,
    expected: np.ndarray,
    got: np.ndarray,
    what: str,
    tolerance: np.ndarray | None = None,
) -> CheckResult:
    """Values within `tolerance` (by default atol + rtol |expected|); the six rows nearest
    (or beyond) it are kept with their directions: the failures, or for a pass the closest
    calls."""
    bad = bad_values(got)
    error = np.abs(np.nan_to_num(got, nan=np.inf) - expected)
    wrong = wrong_values(check, expected, got, tolerance)
    with np.errstate(over="ignore", invalid="ignore"):
        if tolerance is None:
            relative = (error / (check.atol + np.abs(expected))).max(-1)
        else:  # how far into its own tolerance each row is
            relative = (error / tolerance).max(-1)
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
    return passed(check, f"all {n} {what} match", rows=rows)


def mean_flip(reference8: np.ndarray, student8: np.ndarray) -> float:
    """Mean FLIP error (LDR) on 2x-downsampled images: FLIP's cost grows fast with size.

    One OpenMP thread: on images this small, threads cost more than they save (on a busy
    machine six times the CPU time); the grader runs one worker per core anyway."""
    if "flip_evaluator" not in sys.modules:
        os.environ.setdefault("OMP_NUM_THREADS", "1")  # read when libgomp loads
    import flip_evaluator

    def half(image: np.ndarray) -> np.ndarray:
        x = image.astype(np.float32) / 255.0
        h, w = x.shape[0] // 2 * 2, x.shape[1] // 2 * 2
        return x[:h, :w].reshape(h // 2, 2, w // 2, 2, 3).mean(axis=(1, 3))

    return float(flip_evaluator.evaluate(half(reference8), half(student8), "LDR")[1])


def luminance(values: np.ndarray) -> list[float]:
    lum = np.nan_to_num(values, nan=0.0) @ np.array(LUMA)
    return [round(float(v), 6) for v in lum]

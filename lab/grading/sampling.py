"""The numbers behind the sampling checks of exercise 10 (kinds chi_square, pdf_integral
and ibl_render): a student's sampler and pdf run on the GPU (lab.ibl), judged here.

- chi-square: samples binned over (cos theta, phi) against the student's own pdf
  integrated per bin, for several views in shading frames turned away from the axes,
  at one significance level for all views together (Šidák), as pbrt-v4's BSDF tests do;
- pdf integral: the pdf over the sphere is a density: it integrates to 1, less the share
  of samples that fail (a half vector facing away from V), as the solution's does;
- render: the lit sphere under the sky with the student's sampler alone, at equal samples,
  against the converged reference: no more error than the solution's, and no bias.

Each `*_raw` function returns one float array (what the references store); each
`judge_*` returns (passed, message, worst view) from the student's and reference arrays.
"""

from __future__ import annotations

import math

import numpy as np

from lab.constants import LUMA
from lab.ibl import chisquare
from lab.ibl.integrator import Environment, IBLRenderer, Progressive, local_view

BINS = chisquare.THETA_BINS * chisquare.PHI_BINS
EXTRA = 3  # per view after the two histograms: failed, not unit, not finite
_ENVIRONMENTS: dict[str, Environment] = {}


def views_of(views: list, theta: float, phi: float) -> list[tuple[float, float]]:
    """The check's declared views (theta, phi in degrees) and its own (theta_i, phi_i),
    which hidden mode draws at random."""
    out = [(float(t), float(p)) for t, p in views]
    if all(abs(t - theta) > 1e-6 or abs(p - phi) > 1e-6 for t, p in out):
        out.append((float(theta), float(phi)))
    return out


def ibl_renderer(renderer) -> IBLRenderer:
    """An IBLRenderer on the grader's context (the grader's own when it is one)."""
    if isinstance(renderer, IBLRenderer):
        return renderer
    cached = getattr(renderer, "_ibl_twin", None)
    if cached is None:
        cached = IBLRenderer(renderer.ctx)
        renderer._ibl_twin = cached
    return cached


# -- a program's fingerprint: what hidden mode's diagnosis compares ---------------------------
FINGERPRINT_ROWS = 256


def fingerprint(renderer, model, params, seed: int) -> np.ndarray:
    """(256, 5) rows: a sample (L and its pdf) for a view V, and the pdf at a pair (L, V),
    at random inputs fixed by `seed`. Samplers with the same rows sample and weigh alike
    (the BRDF is the library's): two texel passes, where a check's own values take a full
    chi-square test or render."""
    rng = np.random.default_rng([seed, 1])
    n = FINGERPRINT_ROWS
    theta = np.degrees(np.arccos(rng.uniform(0.05, 1.0, (2, n))))
    phi = rng.uniform(0.0, 360.0, (2, n))
    L = chisquare.view_direction(theta[0], phi[0]).T
    V = chisquare.view_direction(theta[1], phi[1]).T
    ibl = ibl_renderer(renderer)
    sampled = ibl.brdf_samples(model, params, V, seed)
    pdf = ibl.brdf_pdf(model, params, L, V)
    return np.concatenate([sampled, pdf[:, None]], axis=1)


# -- chi-square -------------------------------------------------------------------------------
def chi_square_raw(renderer, model, params, views, samples: int, seed: int) -> np.ndarray:
    """(views, 2 * BINS + EXTRA): observed counts, expected counts, failure counts."""
    ibl = ibl_renderer(renderer)
    rows = []
    for index, (theta, phi) in enumerate(views):
        frame = chisquare.random_frame(seed * 31 + index)
        V = chisquare.view_direction(theta, phi)
        out = ibl.brdf_samples(model, params, np.repeat(V[None], samples, 0), seed + index, frame)
        L, pdf = out[:, :3], out[:, 3]
        finite = np.isfinite(out).all(axis=1)
        length = np.linalg.norm(np.where(finite[:, None], L, 0.0), axis=1)
        unit = finite & (np.abs(length - 1.0) < 1e-3)
        valid = unit & (pdf > 0.0)
        observed = chisquare.histogram(L[valid] / length[valid, None])
        expected = chisquare.bin_probabilities(ibl, model, params, V, frame=frame) * samples
        counts = [samples - valid.sum(), samples - unit.sum(), samples - finite.sum()]
        rows.append(np.concatenate([observed.ravel(), expected.ravel(), counts]))
    return np.array(rows, dtype=np.float64)


def _split(row: np.ndarray):
    return row[:BINS], row[BINS : 2 * BINS], row[2 * BINS :]


def _bin_words(index: int) -> str:
    ti, pi = divmod(index, chisquare.PHI_BINS)
    c0 = -1.0 + 2.0 * ti / chisquare.THETA_BINS
    c1 = c0 + 2.0 / chisquare.THETA_BINS
    t0, t1 = math.degrees(math.acos(min(c1, 1.0))), math.degrees(math.acos(max(c0, -1.0)))
    p0 = 360.0 * pi / chisquare.PHI_BINS
    return f"θ {t0:.0f}–{t1:.0f}°, φ {p0:.0f}–{p0 + 360.0 / chisquare.PHI_BINS:.0f}°"


def judge_chi_square(raw, views, samples: int, alpha: float) -> tuple[bool, str, int]:
    """Pearson's test per view at Šidák's level; the first failing view's story."""
    level = chisquare.sidak(alpha, len(views))
    worst, lines = -1, []
    for index, ((theta, phi), row) in enumerate(zip(views, raw, strict=True)):
        observed, expected, (failed, not_unit, not_finite) = _split(row)
        where = f"view θ = {theta:.0f}°, φ = {phi:.0f}°"
        if not_finite:
            lines.append(f"{where}: {int(not_finite)} of {samples} samples are NaN or infinite")
        elif not_unit > 0.001 * samples:
            lines.append(
                f"{where}: {int(not_unit)} of {samples} sampled directions are not unit "
                "vectors (a direction built from sin and cos has length 1)"
            )
        elif expected.sum() < 0.5 * samples:
            lines.append(
                f"{where}: your pdf integrates to {expected.sum() / samples:.3f} over the sphere, "
                "so it cannot describe your samples (see the pdf_integral check)"
            )
        else:
            stat, dof, p = chisquare.pearson(observed, expected, failed, samples - expected.sum())
            if p >= level:
                continue
            off = np.argmax((observed - expected) ** 2 / np.maximum(expected, 1.0))
            lines.append(
                f"{where}: the samples do not follow your pdf (χ² = {stat:.0f} for {dof} "
                f"degrees of freedom, p = {p:.2g} < {level:.2g}); most off: "
                f"{_bin_words(int(off))} holds {int(observed[off])} samples where the pdf "
                f"expects {expected[off]:.0f}"
            )
        worst = index if worst < 0 else worst
    if lines:
        more = len(lines) - 1
        tail = f" (and {more} more view{'s' if more > 1 else ''} fail)" if more else ""
        return False, lines[0] + tail, worst
    tested = ", ".join(f"{t:.0f}°" for t, _ in views)
    return True, f"samples follow the pdf at every view (θ = {tested}; p ≥ {level:.2g})", -1


def same_chi_square(a: np.ndarray, b: np.ndarray, samples: int) -> bool:
    """Two samplers alike: pdfs within 2% per view and histograms from one distribution
    (a two-sample chi-square test, Press et al., Numerical Recipes 14.3)."""
    if a.shape != b.shape:
        return False
    for ra, rb in zip(a, b, strict=True):
        oa, ea, ca = _split(ra)
        ob, eb, cb = _split(rb)
        if np.abs(ea - eb).sum() > 0.02 * samples or abs(ca[1] - cb[1]) > 0.01 * samples:
            return False
        both = (oa + ob) > 0
        stat = float(np.sum((oa[both] - ob[both]) ** 2 / (oa[both] + ob[both])))
        if chisquare.chi2_sf(stat, max(int(both.sum()) - 1, 1)) < 1e-4:
            return False
    return True


def histogram_image(counts: np.ndarray, peak: float, scale: int = 6) -> np.ndarray:
    """A (cos theta, phi) histogram as an 8-bit picture: theta down, phi across."""
    grid = counts.reshape(chisquare.THETA_BINS, chisquare.PHI_BINS)[::-1]
    value = np.sqrt(np.clip(grid / max(peak, 1e-9), 0.0, 1.0))  # square root: tails show
    rgb = np.stack([value, value**0.7, value**0.4], axis=-1)
    image = (rgb * 255.0 + 0.5).astype(np.uint8)
    return np.kron(image, np.ones((scale, scale, 1), np.uint8))


# -- the pdf integral ------------------------------------------------------------------------------
def pdf_integral_raw(renderer, model, params, views, seed: int) -> np.ndarray:
    """(views,): the pdf integrated over the sphere, per view (frames as chi_square's)."""
    ibl = ibl_renderer(renderer)
    out = []
    for index, (theta, phi) in enumerate(views):
        frame = chisquare.random_frame(seed * 31 + index)
        V = chisquare.view_direction(theta, phi)
        out.append(chisquare.bin_probabilities(ibl, model, params, V, frame=frame).sum())
    return np.array(out, dtype=np.float64)


def judge_pdf_integral(raw, reference, views, tolerance: float) -> tuple[bool, str, int]:
    raw = np.nan_to_num(np.asarray(raw, np.float64), nan=np.inf)
    off = np.abs(raw - reference)
    if (off <= tolerance).all():
        values = ", ".join(f"{v:.4f}" for v in raw)
        return True, f"the pdf integrates to {values} over the sphere, as it should", -1
    worst = int(np.argmax(off))
    theta, phi = views[worst]
    return (
        False,
        f"at the view θ = {theta:.0f}°, φ = {phi:.0f}° your pdf integrates to "
        f"{raw[worst]:.4f} over the sphere, the solution's to {reference[worst]:.4f} (1 less "
        f"the samples whose half vector faces away from V); allowed ±{tolerance:g}",
        worst,
    )


# -- the render at equal samples ---------------------------------------------------------
def environment(name: str) -> Environment:
    if name not in _ENVIRONMENTS:
        _ENVIRONMENTS[name] = Environment.load(name)
    return _ENVIRONMENTS[name]


def render_raw(
    renderer, model, params, env: str, size: int, samples: int, converged: int, seed: int
) -> np.ndarray:
    """(2, size, size, 4): the sphere with the model's sampler alone at `samples` per pixel,
    and the same estimator run to `converged` samples (what it converges to)."""
    ibl = ibl_renderer(renderer)
    out = []
    for count, offset in ((samples, 0), (converged, 1000)):
        job = Progressive(ibl, model, params, environment(env), "brdf", size, 0.0, seed + offset)
        try:
            out.append(job.run(count, spp=min(count, 256)).image())
        finally:
            job.release()
    return np.stack(out).astype(np.float32)


def _sphere(size: int) -> np.ndarray:
    return local_view(size)[2]


def relative_rms(image: np.ndarray, reference: np.ndarray, mask: np.ndarray) -> float:
    """RMS of the luminance difference over the sphere, relative to the mean luminance."""
    lum = np.nan_to_num(image[..., :3], nan=1e9, posinf=1e9, neginf=-1e9) @ np.array(LUMA)
    ref = reference[..., :3] @ np.array(LUMA)
    scale = max(float(ref[mask].mean()), 1e-9)
    return float(np.sqrt(np.mean((lum[mask] - ref[mask]) ** 2)) / scale)


def judge_render(raw, reference, samples: int, factor: float, bias: float) -> tuple[bool, str]:
    """Error at equal samples no more than `factor` times the solution's (relative RMS over
    the sphere), and the estimator's limit within `bias` of the solution's in every ring of
    equal view angle (ring means: the noise of single pixels averages out)."""
    raw = raw.astype(np.float32)
    reference = reference.astype(np.float32)
    mask = _sphere(raw.shape[1])
    pixels = raw[:, mask, :3]
    if not np.isfinite(pixels).all() or (pixels < 0).any():
        n = int((~np.isfinite(pixels) | (pixels < 0)).any(axis=-1).any(axis=0).sum())
        return False, f"{n} pixels of the sphere are NaN, infinite or negative"
    mine = relative_rms(raw[0], reference[1], mask)
    theirs = relative_rms(reference[0], reference[1], mask)
    limit = ring_deviation(raw[1], reference[1])
    text = (
        f"at {samples} samples per pixel your render is {100 * mine:.1f}% RMS off the converged "
        f"reference, the solution's {100 * theirs:.1f}% (allowed {factor:g}×); your estimator "
        f"converges to within {100 * limit:.1f}% of it (allowed {100 * bias:g}%)"
    )
    if limit > bias:
        return False, text + ": it is biased — the pdf does not match what the sampler draws"
    if mine > factor * theirs:
        return False, text + ": more noise than the solution's sampler"
    return True, text


RINGS = 16


def ring_means(image: np.ndarray) -> np.ndarray:
    """Mean luminance in RINGS rings of equal view angle on the sphere: a fingerprint of an
    estimator that the noise of single pixels hardly moves."""
    image = image.astype(np.float64)
    theta, _, mask = local_view(image.shape[0])
    lum = np.nan_to_num(image[..., :3], nan=0.0, posinf=1e6, neginf=-1e6) @ np.array(LUMA)
    which = np.minimum((theta / 90.0 * RINGS).astype(int), RINGS - 1)
    return np.array(
        [
            lum[mask & (which == r)].mean() if (mask & (which == r)).any() else 0.0
            for r in range(RINGS)
        ]
    )


def ring_deviation(image: np.ndarray, reference: np.ndarray) -> float:
    """The largest relative difference of ring means (dim rings against a fifth of the mean)."""
    mine, theirs = ring_means(image), ring_means(reference)
    scale = np.maximum(np.abs(theirs), 0.2 * np.abs(theirs).mean() + 1e-12)
    return float(np.max(np.abs(mine - theirs) / scale))


SAME_RENDER = 0.05  # two estimators whose converged rings agree this well count as alike

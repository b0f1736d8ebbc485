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

import hashlib
import math
from statistics import NormalDist

import numpy as np

from lab.constants import LUMA
from lab.grading.words import SAMPLING as WORDS
from lab.ibl import chisquare
from lab.ibl.integrator import Environment, IBLRenderer, Progressive, local_view, sampler_text

BINS = chisquare.THETA_BINS * chisquare.PHI_BINS
EXTRA = 4  # per view after the two histograms: failed, not unit, not finite, draw
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
REDRAW = 1_000_003  # seed offset of the chi-square's second, independent draw
DECISIVE = 1e-7  # a first draw this improbable (per view) fails without a second one
COLUMNS = 2 * BINS + EXTRA  # per view: observed, expected, then failed, not unit, not
# finite, and which draw the row comes from (0 the first, 1 the second)


def chi_square_draw(renderer, model, params, views, samples: int, seed: int) -> np.ndarray:
    """(views, COLUMNS): observed counts, expected counts, failure counts of one draw."""
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
        counts = [samples - valid.sum(), samples - unit.sum(), samples - finite.sum(), 0]
        rows.append(np.concatenate([observed.ravel(), expected.ravel(), counts]))
    return np.array(rows, dtype=np.float64)


def chi_square_raw(
    renderer, model, params, views, samples: int, seed: int, alpha: float = 0.002
) -> np.ndarray:
    """The draw the verdict rests on: the first, unless it fails the test at `alpha`
    without being decisive (p < DECISIVE, or samples that are broken whatever the
    chance): then a second, independent draw of as many samples (its rows say draw 1).
    A correct sampler then fails only when two independent draws both fail, with
    probability about alpha squared."""
    first = chi_square_draw(renderer, model, params, views, samples, seed)
    verdicts = chi_square_views(first, views, samples, alpha)
    if all(v is None or v[1] for v in verdicts):
        return first  # passed, or failed beyond chance
    second = chi_square_draw(renderer, model, params, views, samples, seed + REDRAW)
    second[:, -1] = 1.0
    return second


def _split(row: np.ndarray):
    return row[:BINS], row[BINS : 2 * BINS], row[2 * BINS :]


def _bin_words(index: int) -> str:
    ti, pi = divmod(index, chisquare.PHI_BINS)
    c0 = -1.0 + 2.0 * ti / chisquare.THETA_BINS
    c1 = c0 + 2.0 / chisquare.THETA_BINS
    t0, t1 = math.degrees(math.acos(min(c1, 1.0))), math.degrees(math.acos(max(c0, -1.0)))
    p0 = 360.0 * pi / chisquare.PHI_BINS
    return WORDS["bin"].format(t0=t0, t1=t1, p0=p0, p1=p0 + 360.0 / chisquare.PHI_BINS)


def chi_square_views(raw, views, samples: int, alpha: float) -> list[tuple[str, bool] | None]:
    """Per view: None where it passes, else (what is wrong, decisive): decisive failures
    are broken samples or p < DECISIVE, which no second draw could undo."""
    level = chisquare.sidak(alpha, len(views))
    out: list[tuple[str, bool] | None] = []
    for (theta, phi), row in zip(views, raw, strict=True):
        observed, expected, (failed, not_unit, not_finite, _) = _split(row)
        where = WORDS["view"].format(theta=theta, phi=phi)
        said = {"where": where, "samples": samples}
        if not_finite:
            out.append((WORDS["not_finite"].format(**said, count=int(not_finite)), True))
        elif not_unit > 0.001 * samples:
            out.append((WORDS["not_unit"].format(**said, count=int(not_unit)), True))
        elif expected.sum() < 0.5 * samples:
            out.append((WORDS["no_mass"].format(where=where, mass=expected.sum() / samples), True))
        else:
            stat, dof, p = chisquare.pearson(observed, expected, failed, samples - expected.sum())
            if p >= level:
                out.append(None)
                continue
            off = np.argmax((observed - expected) ** 2 / np.maximum(expected, 1.0))
            text = WORDS["not_following"].format(
                where=where,
                statistic=stat,
                dof=dof,
                p=p,
                level=level,
                bin=_bin_words(int(off)),
                observed=int(observed[off]),
                expected=expected[off],
            )
            out.append((text, p < DECISIVE))
    return out


def judge_chi_square(raw, views, samples: int, alpha: float) -> tuple[bool, str, int]:
    """Pearson's test per view at Šidák's level, on the draw chi_square_raw kept; the
    first failing view's story."""
    verdicts = chi_square_views(raw, views, samples, alpha)
    lines = [v[0] for v in verdicts if v is not None]
    if lines:
        worst = next(i for i, v in enumerate(verdicts) if v is not None)
        more = len(lines) - 1
        text = lines[0]
        if more:
            text = WORDS["more" if more > 1 else "one_more"].format(text=text, more=more)
        if raw.shape[1] == COLUMNS and raw[:, -1].max() > 0:
            text = WORDS["again"].format(text=text)
        return False, text, worst
    level = chisquare.sidak(alpha, len(views))
    tested = ", ".join(WORDS["angle"].format(theta=t) for t, _ in views)
    return True, WORDS["follows"].format(tested=tested, level=level), -1


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
USABLE = 0.5  # a sampler must give a usable direction (pdf > 0) at least this often
Z_INTEGRAL = 5.0  # the failed share's noise allowed: P(|z| > 5) = 5.7e-7 per view


def pdf_integral_raw(renderer, model, params, views, seed: int, samples: int) -> np.ndarray:
    """(views, 2): the pdf integrated over the sphere (quadrature, frames as chi_square's)
    and the share of `samples` of the sampler's own draws that fail (pdf 0 where they
    land, not a unit vector, or not finite), per view."""
    ibl = ibl_renderer(renderer)
    out = []
    for index, (theta, phi) in enumerate(views):
        frame = chisquare.random_frame(seed * 31 + index)
        V = chisquare.view_direction(theta, phi)
        integral = chisquare.bin_probabilities(ibl, model, params, V, frame=frame).sum()
        drawn = ibl.brdf_samples(model, params, np.repeat(V[None], samples, 0), seed + index, frame)
        finite = np.isfinite(drawn).all(axis=1)
        length = np.linalg.norm(np.where(finite[:, None], drawn[:, :3], 0.0), axis=1)
        valid = finite & (np.abs(length - 1.0) < 1e-3) & (drawn[:, 3] > 0.0)
        out.append((integral, 1.0 - valid.mean()))
    return np.array(out, dtype=np.float64)


def integral_allowed(failed: float, samples: int, tolerance: float) -> float:
    """How far the integral may lie from 1 - failed: the quadrature's `tolerance` and
    Z_INTEGRAL standard errors of the failed share measured from `samples` draws."""
    share = min(max(failed, 1.0 / samples), 1.0 - 1.0 / samples)
    return tolerance + Z_INTEGRAL * math.sqrt(share * (1.0 - share) / samples)


def judge_pdf_integral(raw, views, samples: int, tolerance: float) -> tuple[bool, str, int]:
    """The pdf is the density of what the sampler draws: over the sphere it integrates to
    the share of draws that land somewhere (1 less those that fail), whatever that share
    is; the solution's share plays no part."""
    raw = np.nan_to_num(np.asarray(raw, np.float64).reshape(len(views), 2), nan=np.inf)
    integrals, failed = raw[:, 0], raw[:, 1]
    allowed = np.array([integral_allowed(f, samples, tolerance) for f in failed])
    off = np.abs(integrals - (1.0 - failed))
    usable = 1.0 - failed >= USABLE
    if (off <= allowed).all() and usable.all():
        values = ", ".join(WORDS["integral"].format(value=v) for v in integrals)
        wasted = ", ".join(WORDS["share"].format(percent=100 * f) for f in failed)
        return True, WORDS["integrates"].format(values=values, wasted=wasted), -1
    worst = int(np.argmin(usable)) if not usable.all() else int(np.argmax(off - allowed))
    theta, phi = views[worst]
    said = {"at": WORDS["at_view"].format(theta=theta, phi=phi), "percent": 100 * failed[worst]}
    if not usable[worst]:
        return False, WORDS["unusable"].format(**said, usable=100 * USABLE), worst
    text = WORDS["integral_off"].format(
        **said, value=integrals[worst], density=1.0 - failed[worst], allowed=allowed[worst]
    )
    return False, text, worst


# -- the render at equal samples ---------------------------------------------------------
Z_GROUPS = 8  # rings of equal view angle tested for bias, and the whole sphere besides


def environment(name: str) -> Environment:
    if name not in _ENVIRONMENTS:
        _ENVIRONMENTS[name] = Environment.load(name)
    return _ENVIRONMENTS[name]


def program_seed(model, seed: int) -> int:
    """The check's seed salted with the sampler's text: a program other than the
    solution never replays the random numbers of the reference (a sampler that maps them
    differently would be compared with a correlated copy of its own noise)."""
    text = sampler_text(model) or ""
    salt = int.from_bytes(hashlib.sha1(text.encode()).digest()[:3], "little")
    return (seed + salt) % (1 << 30)


def render_raw(
    renderer,
    model,
    params,
    env: str,
    size: int,
    samples: int,
    passes: int,
    seed: int,
    rotation: float = 0.0,
) -> np.ndarray:
    """(3, size, size, 3) float32: one pass of `samples` per pixel (RGB), the mean of
    `passes` independent such passes (RGB), and in channel 0 of the third the sample
    variance of the passes' luminance per pixel (the estimator's own noise). `rotation`
    turns the environment about the vertical (degrees)."""
    ibl = ibl_renderer(renderer)
    seed = program_seed(model, seed)
    job = Progressive(ibl, model, params, environment(env), "brdf", size, rotation, seed)
    luma = np.array(LUMA)
    try:
        total = first = np.zeros((size, size, 3))
        lum = []
        for _ in range(passes):
            job.add(samples)
            running = job.image()[..., :3].astype(np.float64) * job.samples
            one = (running - total) / samples
            total = running
            lum.append(one @ luma)
            first = one if len(lum) == 1 else first  # the picture of one pass
    finally:
        job.release()
    variance = np.zeros((size, size, 3))
    variance[..., 0] = np.var(np.array(lum), axis=0, ddof=1)
    return np.stack([first, total / (samples * passes), variance]).astype(np.float32)


def _sphere(size: int) -> np.ndarray:
    return local_view(size)[2]


def _luminance(image: np.ndarray) -> np.ndarray:
    return image[..., :3].astype(np.float64) @ np.array(LUMA)


def t_limit(alpha: float, tests: int, dof: float) -> float:
    """|t| beyond which one of `tests` two-sided tests fails a correct estimator with
    probability at most `alpha` in all (Bonferroni), for a statistic whose variance is
    estimated with `dof` degrees of freedom: Student's t quantile by the Cornish-Fisher
    expansion around the normal one (Abramowitz and Stegun 26.7.5; within 1% from 10 dof)."""
    z = NormalDist().inv_cdf(1.0 - alpha / (2.0 * tests))
    n = max(dof, 3.0)
    return (
        z
        + (z**3 + z) / (4 * n)
        + (5 * z**5 + 16 * z**3 + 3 * z) / (96 * n**2)
        + (3 * z**7 + 19 * z**5 + 17 * z**3 - 15 * z) / (384 * n**3)
    )


def bias_z(raw: np.ndarray, reference: np.ndarray, passes: int) -> tuple[np.ndarray, list]:
    """The difference of the two estimators' means over its standard error, per ring of
    equal view angle and over the whole sphere, with both estimators' own variances (from
    their passes); per group also its name, relative difference and degrees of freedom
    (Welch and Satterthwaite: each pixel's variance has passes - 1)."""
    theta, _, mask = local_view(raw.shape[1])
    d = _luminance(raw[1]) - _luminance(reference[1])
    v = (raw[2][..., 0].astype(np.float64) + reference[2][..., 0]) / passes
    ring = np.minimum((theta / 90.0 * Z_GROUPS).astype(int), Z_GROUPS - 1)
    groups = [
        (
            mask & (ring == r),
            WORDS["ring"].format(low=90 * r / Z_GROUPS, high=90 * (r + 1) / Z_GROUPS),
        )
        for r in range(Z_GROUPS)
    ] + [(mask, WORDS["whole_sphere"])]
    groups = [(g, name) for g, name in groups if g.any()]
    ref = _luminance(reference[1])
    z = np.array([d[g].sum() / math.sqrt(max(v[g].sum(), 1e-30)) for g, _ in groups])
    words = []
    for g, name in groups:
        dof = (passes - 1) * v[g].sum() ** 2 / max(float((v[g] ** 2).sum()), 1e-300)
        words.append((name, d[g].mean() / max(abs(ref[g].mean()), 1e-12), dof))
    return z, words


def render_errors(raw, reference, passes: int) -> tuple[float, float]:
    """Relative RMS error of one pass against the truth, the student's and the solution's:
    the student's from its squared distance to the reference's mean, less the reference's
    own noise (an unbiased estimate); the solution's from its variance (it is unbiased)."""
    mask = _sphere(raw.shape[1])
    d = (_luminance(raw[1]) - _luminance(reference[1]))[mask]
    mine_var = raw[2][..., 0][mask].astype(np.float64)
    ref_var = reference[2][..., 0][mask].astype(np.float64)
    mine = np.mean(mine_var * (1.0 - 1.0 / passes) + d * d - ref_var / passes)
    scale = max(float(_luminance(reference[1])[mask].mean()), 1e-12)
    return math.sqrt(max(mine, 0.0)) / scale, math.sqrt(float(ref_var.mean())) / scale


def judge_render(
    raw, reference, samples: int, passes: int, factor: float, alpha: float
) -> tuple[bool, str, dict]:
    """No bias (a z-test per ring and over the sphere against the reference, with both
    estimators' own noise, at `alpha` for all tests together) and, at `samples` per pixel,
    no more than `factor` times the solution's RMS error: importance sampling is what
    buys that. Also returns the figures: noise ratio, largest |z| and its limit."""
    if reference is None or np.shape(reference) != np.shape(raw) or raw.shape[0] != 3:
        return False, "the reference does not fit this check (instructor: --make-references)", {}
    raw = raw.astype(np.float32)
    pixels = raw[:, _sphere(raw.shape[1])]
    bad = (~np.isfinite(pixels) | (pixels < 0)).any(axis=-1).any(axis=0)
    if bad.any():
        return False, WORDS["render_bad"].format(count=int(bad.sum())), {}
    mine, theirs = render_errors(raw, reference, passes)
    z, words = bias_z(raw, reference, passes)
    limits = np.array([t_limit(alpha, len(z), dof) for _, _, dof in words])
    worst = int(np.argmax(np.abs(z) / limits))
    limit = float(limits[worst])
    noise = WORDS["render_noise"].format(
        samples=samples, mine=100 * mine, theirs=100 * theirs, factor=factor
    )
    name, rel, _ = words[worst]
    ratio = mine / max(theirs, 1e-12)
    stats = {"noise_ratio": ratio, "largest_z": float(abs(z[worst])), "z_limit": limit}
    if abs(z[worst]) > limit:
        said = {"total": samples * passes, "group": name, "rel": 100 * rel, "z": z[worst]}
        text = WORDS["render_biased"].format(**said, limit=limit, noise=noise)
        return False, text, stats
    if mine > factor * theirs:
        return False, WORDS["render_noisy"].format(noise=noise, ratio=ratio), stats
    text = WORDS["render_passes"].format(noise=noise, z=abs(z[worst]), limit=limit)
    return True, text, stats


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

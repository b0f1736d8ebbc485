"""What the grader says of a failed (or passed) check, as str.format templates: one source
for the grader and the web page's practice mode, which gets them as data in exercises.json
(lab/web/exercises.py) and fills them with web/static/header.js fill(), Python's format for
the specs used here ({name}, {name:g}, {name:.2g}, {name:.0f}, {name:+.1f}).

The logic that picks a sentence lives in lab.grading.diagnosis and lab.grading.sampling
(and, for the page, diagnosis.js and sampling.js); here are only the words.
"""

from __future__ import annotations

# The diagnosis of values against the solution's (lab.grading.diagnosis, explain).
DIAGNOSIS = {
    "likely": "Likely: {text}.",
    # the grader's and the page's sentence for a loop the guard stopped ({limit}: "10,000")
    "loop_stopped": (
        "{file}:{line}: the loop at line {line} did not end within {limit} iterations at "
        "{where} (counted over every pass of the loops around it); check its exit condition, "
        "or take fewer steps (on a GPU such a loop freezes the screen)"
    ),
    # ... and for loops that together reached the guard's total ({total}: "65,000")
    "loops_total": (
        "{file}:{line}: your loops ran {total} passes in all by the loop at line {line}, at "
        "{where} (every pass of every loop counts, a nested loop's at each pass of the loops "
        "around it); the grader's software renderer (Mesa llvmpipe) ends them all there "
        "without a word, so the lab stops them and the values are wrong: take fewer steps "
        "(a coarser grid, fewer samples)"
    ),
    "not_finite": (
        "some values are NaN or infinite — a division by zero or the pow/sqrt of a "
        "negative number; guard them with max(..., EPS)"
    ),
    "negative": (
        "{count} values are negative {where} — a dot product is not clamped (max(..., 0.0)) "
        "or the below-the-surface test is missing"
    ),
    "negative_at_zero": "where the solution is 0",
    "negative_in_places": "in places",
    "wrong_below": (
        "the values are wrong only where the solution is 0 (light or view below the "
        "surface) — return vec3(0.0) when N·L ≤ 0 or N·V ≤ 0"
    ),
    "wrong_above": (
        "the values are wrong only where the solution is 0, with light and view above "
        "the surface — a dot product that the solution clamps (max(..., 0.0)) is not"
    ),
    "zero": (
        "it is 0 {where} while the solution's is not — a part is missing, or never added "
        "to what is returned"
    ),
    "zero_everywhere": "everywhere",
    "zero_where_wrong": "wherever it is wrong",
    "named_large": "every value is {name} times too large — {cause}",
    "named_small": "every value is {name} times too small — {cause}",
    "large": "every value is {times:.3g} times too large: a constant factor is off",
    "small": "every value is {times:.3g} times too small: a constant factor is off",
    "off_by": "the values are off by {factor}",
    "off_by_scaled": "the values are off by {factor} (and a constant factor {scale:.3g})",
    # The factors a ratio is tested for, in this order (diagnosis._ratio).
    "factor_cos_i": "an extra factor cos θi (N·L) — the renderer multiplies by N·L itself",
    "factor_cos_o": "an extra factor cos θo (N·V)",
    "factor_over_cos_i": "divided by cos θi (N·L) once too often",
    "factor_over_cos_o": "divided by cos θo (N·V) once too often",
    "factor_sqrt": "an extra factor √(cos θi cos θo)",
    "factor_over_sqrt": "divided by √(cos θi cos θo) once too often",
    "grey": (
        "the result is grey where the solution is coloured — a float is used where a "
        "colour (vec3) belongs, e.g. one channel of a colour parameter"
    ),
    "one_channel": "only the {channel} channel is wrong",
    "grazing": (
        "the values are right except near grazing (θ above {grazing:g}°) — check the "
        "terms that matter there: Fresnel, G and the N·L·N·V denominator"
    ),
    "grazing_table": (
        "the values are right except near grazing (θ above {grazing:g}°) — check what "
        "the lookup does with the large angles there: the difference angle θd's bins "
        "(radians over π/2) and the clamp at the table's last bin"
    ),
    "seam": (
        "the values are right except where φd crosses the table's end (within half a bin "
        "of 0° or 180°) — φd is periodic, not clamped: the neighbour of the last bin is "
        "bin 0 and the one below bin 0 is the last, so wrap the index around (modulo the "
        "bin count) instead of clamping it or leaving it outside the table"
    ),
    "peak_fit": (
        "the lobe peaks at θo = {got:.0f}° instead of {want:.0f}°, as it does with {what} "
        "of about {value:g} instead of {actual:g}"
    ),
    "peak": (
        "the lobe peaks at θo = {got:.0f}° instead of {want:.0f}° — check the reflected "
        "direction (or the half vector) and which vectors enter it"
    ),
    "too_wide": "the lobe is {ratio:.2g} times too wide",
    "too_narrow": "the lobe is {ratio:.2g} times too narrow",
    "and_peaks": "{text} and peaks at θo = {got:.0f}° instead of {want:.0f}°",
    "as_wide": "{text} — as wide as {what} of about {value:g} instead of {actual:g}",
    "listed": "{most} and {last}",  # the most joined by ", "
    "term_wrong": "the {names} term is wrong",
    "terms_wrong": "the {names} terms are wrong",
    "term_right": "{text} (the {names} term is right)",
    "terms_right": "{text} (the {names} terms are right)",
    "detail": "{text}: {detail}",
    "swapped_lv": (
        "your BRDF(L, V) gives the solution's BRDF(V, L) — L and V are swapped somewhere "
        "(the solution is not symmetric in them)"
    ),
    "swapped_xy": "the X and Y axes are swapped — alpha_x belongs with X, alpha_y with Y",
}

# The sampling checks of exercise 10 (lab.grading.sampling, kinds chi_square, pdf_integral).
SAMPLING = {
    "view": "view θ = {theta:.0f}°, φ = {phi:.0f}°",
    "not_finite": "{where}: {count} of {samples} samples are NaN or infinite",
    "not_unit": (
        "{where}: {count} of {samples} sampled directions are not unit vectors (a direction "
        "built from sin and cos has length 1)"
    ),
    "no_mass": (
        "{where}: your pdf integrates to {mass:.3f} over the sphere, so it cannot describe "
        "your samples (see the pdf_integral check)"
    ),
    "not_following": (
        "{where}: the samples do not follow your pdf (χ² = {statistic:.0f} for {dof} degrees "
        "of freedom, p = {p:.2g} < {level:.2g}); most off: {bin} holds {observed} samples "
        "where the pdf expects {expected:.0f}"
    ),
    "bin": "θ {t0:.0f}–{t1:.0f}°, φ {p0:.0f}–{p1:.0f}°",
    "one_more": "{text} (and 1 more view fail)",
    "more": "{text} (and {more} more views fail)",
    "again": "{text}; a second, independent draw failed as the first did",
    "angle": "{theta:.0f}°",  # joined by ", " in "follows"
    "follows": "samples follow the pdf at every view (θ = {tested}; p ≥ {level:.2g})",
    "pdf_wrong": "your samples are drawn like the solution's: the pdf is what is wrong",
    "sampler_wrong": "your pdf agrees with the solution's: the sampler is what is wrong",
    "integral": "{value:.4f}",  # joined by ", " in "integrates"
    "share": "{percent:.1f}%",  # joined by ", " in "integrates"
    "integrates": (
        "the pdf integrates to {values} over the sphere: 1 less the samples that fail "
        "({wasted}), as a density of what your sampler draws should"
    ),
    "at_view": "at the view θ = {theta:.0f}°, φ = {phi:.0f}°",
    "unusable": (
        "{at} {percent:.1f}% of your samples fail (pdf 0 where they land, or not a unit "
        "vector): a sampler must give a usable direction at least {usable:.0f}% of the time"
    ),
    "integral_off": (
        "{at} your pdf integrates to {value:.4f} over the sphere, but {percent:.1f}% of your "
        "samples fail, so the density of what your sampler draws integrates to "
        "{density:.4f} (allowed ±{allowed:.3f}): the pdf does not describe the sampler"
    ),
    # The IBL render (sampling.judge_render; the page's iblcheck.js fills the same).
    "ring": "ring θ {low:.0f}–{high:.0f}°",
    "whole_sphere": "whole sphere",
    "render_bad": "{count} pixels of the sphere are NaN, infinite or negative",
    "render_noise": (
        "at {samples} samples per pixel your render is {mine:.1f}% RMS off the converged "
        "reference, the solution's {theirs:.1f}% (allowed {factor:g}×)"
    ),
    "render_biased": (
        "over {total} samples per pixel your estimator converges to another image: in the "
        "{group} its mean is {rel:+.1f}% off the reference's (z = {z:.1f}, allowed |z| ≤ "
        "{limit:.1f} for noise like yours); {noise}: it is biased — a sample's weight "
        "f_r L_i cos θ / p does not fit the density p its direction is drawn with"
    ),
    "render_noisy": (
        "{noise}: {ratio:.1f}× the solution's noise; it converges to the right image, but "
        "needs far more samples to get there (samples drawn like the lobe, each from its own "
        "random numbers, need fewer)"
    ),
    "render_passes": (
        "{noise}; no bias (every ring within its limit; closest |z| {z:.1f} of {limit:.1f})"
    ),
}


# A `properties` check (exercise 11: kinds/properties.py; the page's properties.js).
PROPERTIES = {
    "gains": "gains energy",
    "conserves": "conserves energy",
    "not_reciprocal": "not reciprocal",
    "reciprocal": "reciprocal",
    "found": "the model {energy} and is {reciprocity}",
    "largest": "largest albedo {albedo:.3f}",
    "largest_error": "largest albedo {albedo:.3f}, largest reciprocity error {error:.3g}",
    "passes": "your tests find that {found} ({largest})",
    "albedo_off": (
        "{count} of {n} albedo values differ from the grader's (at θV = {theta:.1f}° your "
        "directional_albedo gives {got:.4g}, the grader measures {truth:.4g})"
    ),
    "pairs_off": (
        "{count} of {n} reciprocity errors differ (at (θL, φL, θV, φV) = ({tl:.0f}°, "
        "{pl:.0f}°, {tv:.0f}°, {pv:.0f}°) yours is {got:.4g}, the grader's {truth:.4g})"
    ),
    "verdicts_off": "your values say the model {energy} and is {reciprocity}; in fact {found}",
    "same_value": "your {what} gives the same value, {value:.4g}, for every input",
    "constant": (
        "{said}: a test must measure the BRDF linked with it (call BRDF(L, V, N, X, Y)), "
        "whose values change with the directions and the model"
    ),
    "negative_error": (
        "your reciprocity_error is negative at some pairs: the difference |f(L, V) − f(V, L)| "
        "needs its absolute value"
    ),
    "error_above_one": (
        "your reciprocity_error reaches {value:.3g}, above 1: relative to the larger of "
        "f(L, V) and f(V, L) the difference is at most 1"
    ),
    "negative_albedo": "your directional_albedo is negative at some views: f_r cos θL is not",
    "reduced": "your {what} returns {reduction}",
    "reduction": (
        "{said}, where the largest channel belongs, max(r, g, b): a model conserves energy, "
        "and is reciprocal, only where every colour channel does, so the worst one decides"
    ),
    "by_smallest": "the smallest channel, min(r, g, b)",
    "by_mean": "the mean of the channels",
    "by_red": "the red channel alone",
    "by_green": "the green channel alone",
    "by_blue": "the blue channel alone",
    "by_luminance": "the luminance of the channels",
    "albedo_at": "directional_albedo at θV = {theta:.1f}°",
    "pair_at": (
        "reciprocity_error at (θL, φL, θV, φV) = ({tl:.1f}°, {pl:.1f}°, {tv:.1f}°, {pv:.1f}°)"
    ),
}


def joined(names: list[str]) -> str:
    """'D', 'D and G', 'diffuse, D and G'."""
    if len(names) == 1:
        return names[0]
    return DIAGNOSIS["listed"].format(most=", ".join(names[:-1]), last=names[-1])


# An `sh` check (exercise 15: kinds/sh.py).
SH = {
    "basis_at": "sh_basis({l}, {m}, w) at (θ, φ) = ({theta:.1f}°, {phi:.1f}°)",
    "coefficient_at": "sh_coefficient({l}, {m}, L) for L at (θi, φi) = ({theta:.1f}°, {phi:.1f}°)",
    "basis_passes": (
        "your sh_basis matches the lab's real harmonics at {n} values (largest {largest:.3g})"
    ),
    "coefficients_pass": (
        "your coefficients match the lab's projection of the lobe; the lobe rebuilt from "
        "them is {error:.2%} away from the lab's (L2 over the sphere)"
    ),
    "basis_off": (
        "{count} of {n} harmonic values differ from the lab's (sh_basis({l}, {m}, w) at "
        "(θ, φ) = ({theta:.1f}°, {phi:.1f}°) gives {got:.4g}, the lab's Y is {truth:.4g})"
    ),
    "coefficients_off": (
        "{count} of {n} coefficients differ from the lab's projection (sh_coefficient({l}, "
        "{m}, L) at θi = {theta:.1f}° gives {got:.4g}, the lab's is {truth:.4g}); the lobe "
        "rebuilt from yours is {error:.1%} away from the lab's (L2 over the sphere)"
    ),
    "sign_only": (
        "your values have the lab's sizes but the opposite sign wherever {where}: "
        "look at the sign convention there"
    ),
    "scaled": "your values are the lab's times {factor:.4g} throughout: a constant factor is off",
}

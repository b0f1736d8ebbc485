"""Low-discrepancy samples (lab/ibl/sobol.py, lab_sobol3 in terms/sampling.glsl): the
generator is Sobol's, the scrambling keeps the nets, the pixels are decorrelated, and in
the furnace every prefix of a render is at least as good as random numbers' and 1% comes
at least twice as soon."""

from __future__ import annotations

import numpy as np
import pytest

from lab.ibl import sobol
from lab.ibl.convergence import converge, reference_image
from lab.ibl.furnace import furnace
from lab.ibl.integrator import SAMPLING_TERMS, Environment, IBLRenderer, Progressive


@pytest.fixture(scope="module")
def ibl(ctx):
    return IBLRenderer(ctx)


def test_generator_is_sobols():
    """The first 256 points in dimensions 0-2 are scipy's (unscrambled) as a set."""
    from scipy.stats import qmc

    n = np.arange(256)
    mine = np.stack([sobol.sobol(n, d) for d in range(3)], axis=1) / 2.0**32
    theirs = qmc.Sobol(3, scramble=False).random(256)
    key = lambda p: sorted(map(tuple, np.round(p * 2**12).astype(int)))  # noqa: E731
    assert key(mine) == key(theirs)


def test_glsl_carries_the_same_direction_numbers():
    assert sobol.glsl_constants() in SAMPLING_TERMS.read_text()


@pytest.mark.parametrize("seed", [1, 77, 123456])
def test_scrambled_prefixes_stay_nets(seed):
    """Owen scrambling (per dimension) of the first 2^m points of dimensions 0 and 1: every
    elementary box of area 2^-m holds exactly one point, as for the unscrambled net."""
    m = 8
    n = np.arange(2**m)
    x = sobol.owen(sobol.sobol(n, 0), seed).astype(np.float64) / 2.0**32
    y = sobol.owen(sobol.sobol(n, 1), seed + 1).astype(np.float64) / 2.0**32
    for a in range(m + 1):
        cells = (x * 2**a).astype(int) * 2 ** (m - a) + (y * 2 ** (m - a)).astype(int)
        assert np.bincount(cells, minlength=2**m).max() == 1, a


@pytest.fixture(scope="module")
def furnace_env():
    return Environment(np.ones((16, 32, 3), np.float32), "furnace")


def test_pixels_are_decorrelated(ibl, furnace_env):
    """Each pixel scrambles its own sequence: the errors of neighbouring pixels at 4 spp are
    uncorrelated (a shared sequence would make them nearly equal)."""
    job = Progressive(ibl, "ggx", {"alpha": 0.5}, furnace_env, "brdf", 64, sequence="sobol")
    reference = Progressive(ibl, "ggx", {"alpha": 0.5}, furnace_env, "brdf", 64, seed=9)
    try:
        error = job.run(4).image()[..., 1] - reference.run(4096, spp=256).image()[..., 1]
    finally:
        job.release()
        reference.release()
    inner = error[8:-8, 8:-8]
    for a, b in ((inner[:, 1:], inner[:, :-1]), (inner[1:], inner[:-1])):
        assert abs(np.corrcoef(a.ravel(), b.ravel())[0, 1]) < 0.15


def test_sobol_furnace_is_unbiased(ibl):
    result = furnace("ggx", {"alpha": 0.3}, samples=256, renderer=ibl, sequence="sobol")
    assert result.max_relative_error < 0.01


@pytest.mark.parametrize("alpha", [0.1, 0.5])
def test_every_prefix_beats_random_and_one_percent_comes_twice_as_soon(ibl, furnace_env, alpha):
    """GGX under the furnace, BRDF sampling: at every checkpoint (1, 2, 3, 4, 6, 8, ...
    samples per pixel) Sobol's error is at most random's (5% slack for the noise of one
    run), and it reaches 1% with at most half the samples."""
    values = {"alpha": alpha}
    reference, own = reference_image(ibl, "ggx", values, furnace_env, 32, 4096)
    runs = {
        sequence: converge(
            ibl, "ggx", values, furnace_env, "brdf", reference, 32, 30.0, 0.01, own, sequence,
            max_samples=4096,
        )
        for sequence in ("random", "sobol")
    }  # fmt: skip
    random, ld = runs["random"], runs["sobol"]
    for n in ld.samples:
        assert ld.error_at(n) <= 1.05 * random.error_at(n), (n, ld.errors, random.errors)
    assert random.samples_to()[0] >= 2.0 * ld.samples_to()[0]

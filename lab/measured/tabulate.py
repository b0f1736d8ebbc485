"""Tabulate an analytic model in the MERL layout, on the GPU through its own shader."""

from __future__ import annotations

import functools

import numpy as np

from lab.measured.merl import MERL_DIMS, MerlTable, bin_grid
from lab.models import Model, Value


def tabulate(
    model: Model | str,
    values: dict[str, Value] | None = None,
    dims: tuple[int, int, int] = MERL_DIMS,
    noise: float = 0.0,
    seed: int = 0,
    renderer=None,
) -> MerlTable:
    """f_r of `model` at every bin centre; `noise` is a relative error (sigma).

    Noise multiplies each value by (1 + sigma * z), clipped at 0, as a stand-in for a
    gonioreflectometer's error, which grows with the signal; z is noise_normal's (mean 0,
    standard deviation 1), a function of the bin, the channel and `seed` alone.
    """
    if noise < 0 or not np.isfinite(noise):
        raise ValueError(f"noise must be a finite sigma >= 0, not {noise}")
    return measure(bin_values(model, values, dims, renderer), dims, noise, seed)


def bin_values(
    model: Model | str, values: dict[str, Value] | None, dims=MERL_DIMS, renderer=None
) -> np.ndarray:
    """tabulate's first step: f_r (n, 3) at the bin centres in file order, noise-free."""
    from lab.render import Renderer

    L, V = _grid(tuple(dims))
    return (renderer or Renderer()).probe(model, values, L, V).astype(np.float64)


def measure(f: np.ndarray, dims, noise: float = 0.0, seed: int = 0) -> MerlTable:
    """tabulate's second step: the table of noise-free values `f`, with its noise."""
    if noise > 0:
        f = f * noise_factor(len(f), noise, seed)
    return MerlTable.from_rgb(f.reshape(*dims, 3))


# The noise is counter-based: the value of bin i, channel c is a hash of (3 i + c, seed), so
# the web page's practice mode makes the grader's table on its own GPU from the same hash in
# GLSL (shaders/views/tabulate.glsl; tests/test_web_tables.py holds the two equal) instead
# of downloading 1.46 M bins. z sums four 16-bit pieces of two hashes (Irwin-Hall, nearly
# Gaussian, |z| < 3.47): integer arithmetic up to one float32 product, so it is the same
# float on every GPU and here.
PIECES_MEAN = 131070  # 4 * 65535 / 2
PIECES_INV_STD = np.float32(2.6428997e-05)  # 1 / sqrt((65536^2 - 1) / 3), their std's inverse
SEED_SALT = 0x9E3779B9


def hash32(x: np.ndarray) -> np.ndarray:
    """A 32-bit integer mixer (xor-shift and multiply rounds), as lab_hash32 in GLSL."""
    x = np.array(x, dtype=np.uint32, ndmin=1)
    with np.errstate(over="ignore"):  # products wrap modulo 2^32, as GLSL's uint
        x ^= x >> np.uint32(16)
        x *= np.uint32(0x7FEB352D)
        x ^= x >> np.uint32(15)
        x *= np.uint32(0x846CA68B)
        x ^= x >> np.uint32(16)
    return x


def noise_normal(count: int, seed: int = 0) -> np.ndarray:
    """z (count, 3) float32 of bins 0 to count - 1 (file order), channels R, G, B."""
    salt = hash32((seed + SEED_SALT) % 2**32)[0]
    key = (np.arange(3 * count, dtype=np.uint32) << np.uint32(1)) ^ salt
    first, second = hash32(key), hash32(key ^ np.uint32(1))
    low = np.uint32(0xFFFF)
    pieces = (first & low) + (first >> np.uint32(16)) + (second & low) + (second >> np.uint32(16))
    centred = (pieces.astype(np.int64) - PIECES_MEAN).astype(np.float32)
    return (centred * PIECES_INV_STD).reshape(count, 3)


def noise_factor(count: int, noise: float, seed: int = 0) -> np.ndarray:
    """(count, 3) float32 factors max(1 + noise * z, 0): float32 steps, as the GLSL's."""
    z = noise_normal(count, seed)
    return np.maximum(np.float32(1.0) + np.float32(noise) * z, np.float32(0.0))


@functools.lru_cache(maxsize=2)
def _grid(dims: tuple[int, int, int]) -> tuple[np.ndarray, np.ndarray]:
    """The bin centres' directions as float32, made once per grid (half of a table's time)."""
    L, V = (np.ascontiguousarray(d, dtype=np.float32) for d in bin_grid(dims))
    L.flags.writeable = V.flags.writeable = False
    return L, V

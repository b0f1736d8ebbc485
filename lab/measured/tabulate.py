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
    """f_r of `model` at every bin centre; `noise` is a relative Gaussian error (sigma).

    Noise multiplies each value by (1 + sigma * N(0, 1)), clipped at 0, as a stand-in for
    a gonioreflectometer's error, which grows with the signal.
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
        rng = np.random.default_rng(seed)
        f = np.maximum(f * (1.0 + noise * rng.standard_normal(f.shape)), 0.0)
    return MerlTable.from_rgb(f.reshape(*dims, 3))


@functools.lru_cache(maxsize=2)
def _grid(dims: tuple[int, int, int]) -> tuple[np.ndarray, np.ndarray]:
    """The bin centres' directions as float32, made once per grid (half of a table's time)."""
    L, V = (np.ascontiguousarray(d, dtype=np.float32) for d in bin_grid(dims))
    L.flags.writeable = V.flags.writeable = False
    return L, V

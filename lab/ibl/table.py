"""Data-driven importance sampling for any BRDF (shaders/terms/sampling_table.glsl).

For a model without an analytic sampler, `build` renders the mass of f_r cos in every cell
of a half-vector table on the GPU (views/ibl_table.glsl, the model's own BRDF), and turns
it into one piecewise-constant distribution per view angle: a density per cell and its
CDFs, uploaded as textures. The sampler draws from them with its exact pdf, so the
estimates and MIS weights stay unbiased however well or badly the table fits the lobe.
A table is rebuilt when the model or a parameter changes (`TableCache`).
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field

import moderngl
import numpy as np

from lab.gl import table_texture
from lab.models import SHADER_DIR

GLSL = SHADER_DIR / "terms" / "sampling_table.glsl"
UNIT = 12  # texture units 12..14 (the environment holds 8..11, a measured table 7)


def _constant(name: str) -> int:
    """A table size as sampling_table.glsl declares it (the one place it is written)."""
    match = re.search(rf"const int {name} = (\d+);", GLSL.read_text(encoding="utf-8"))
    if match is None:
        raise RuntimeError(f"{GLSL}: no 'const int {name} = N;'")
    return int(match.group(1))


VIEWS, ROWS, COLUMNS = _constant("TABLE_VIEWS"), _constant("TABLE_U"), _constant("TABLE_PHI")
GUIDES = _constant("TABLE_GUIDES")  # guide texels per cell of a row (`inversion_tables`)
DEFENSIVE = 0.05  # share of the table's probability spread uniformly over the half vectors


def cell_solid_angles() -> np.ndarray:
    """(ROWS,) solid angle of one cell of each row: 1 - cos(theta_h) = u^4."""
    versine = (np.arange(ROWS + 1) / ROWS) ** 4
    return np.diff(versine) * (2.0 * math.pi / COLUMNS)


@dataclass
class Table:
    """One model's sampling table: density (VIEWS * ROWS, COLUMNS) per half-vector solid
    angle, and the inverse CDFs (`inversion_tables`) of the rows of each view
    (VIEWS, 5 ROWS, 4) and of the cells of each row (VIEWS * ROWS, 5 COLUMNS, 4)."""

    density: np.ndarray
    marginal: np.ndarray
    conditional: np.ndarray
    seconds: float = 0.0  # time to build (GPU pass, readback, CDFs, upload)
    _textures: list = field(default_factory=list, repr=False)

    @classmethod
    def from_masses(cls, masses: np.ndarray) -> Table:
        """The distributions from the masses (VIEWS, ROWS, COLUMNS) of f_r cos per cell
        (a view angle with no mass at all is sampled uniformly over the cells)."""
        m = np.nan_to_num(np.asarray(masses, np.float64), nan=0.0, posinf=0.0, neginf=0.0)
        m = np.maximum(m, 0.0).reshape(VIEWS, ROWS, COLUMNS)
        totals = m.sum(axis=(1, 2), keepdims=True)
        uniform = np.broadcast_to(cell_solid_angles()[None, :, None], m.shape)
        m = np.where(totals > 0.0, m, uniform)
        # A share DEFENSIVE of the draws uniform over the half vectors (a defensive mixture,
        # Hesterberg 1995): every direction L above the horizon keeps p > 0, whatever the
        # table's samples of each cell missed, so the estimate stays unbiased.
        m = m / m.sum(axis=(1, 2), keepdims=True)
        m = (1.0 - DEFENSIVE) * m + DEFENSIVE * uniform / (2.0 * math.pi)
        marginal = inversion_tables(m.sum(axis=2)).astype(np.float32)
        conditional = inversion_tables(m.reshape(VIEWS * ROWS, COLUMNS)).astype(np.float32)
        # The probability the shader draws each cell with: its float32 CDF steps (a cell of
        # probability 1e-6 next to CDF 1 would be 6% off its float64 value)
        p = cell_probabilities(marginal).reshape(VIEWS * ROWS, 1)
        p = p * cell_probabilities(conditional)
        density = p / np.tile(cell_solid_angles(), VIEWS)[:, None]
        return cls(density.astype(np.float32), marginal, conditional)

    def bind(self, ctx: moderngl.Context) -> dict:
        """Upload (once) and bind the three textures; the uniforms that name their units."""
        if not self._textures:
            tables = (self.density, self.marginal, self.conditional)
            self._textures = [table_texture(ctx, array) for array in tables]
        for unit, texture in enumerate(self._textures):
            texture.use(UNIT + unit)
        return {
            "u_table_density": UNIT,
            "u_table_marginal": UNIT + 1,
            "u_table_conditional": UNIT + 2,
        }

    def release(self) -> None:
        for texture in self._textures:
            texture.release()
        self._textures.clear()


def inversion_tables(weights: np.ndarray) -> np.ndarray:
    """(..., GUIDES * n + n, 4) for each row of `weights` (..., n): the inverse of its CDF
    as the shader reads it. Texel g < GUIDES * n guides x in [g, g + 1) / (GUIDES * n): it
    holds the cell i that g's start falls in (Chen and Asau 1974), i's CDF at its lower and
    upper edge, and the upper edge of cell i + 1; x is in i or i + 1 but where many small
    cells share a guide's span, where the search goes on over texels GUIDES * n + k, cell
    k's edges (0, 1). Inverting in order keeps a stratified x stratified over the cells
    (an alias table, one fetch too, shuffles them). A row with no weight is uniform."""
    w = np.asarray(weights, np.float64)
    flat = w.reshape(-1, w.shape[-1])
    n = flat.shape[1]
    totals = flat.sum(axis=1, keepdims=True)
    flat = np.where(totals > 0.0, flat, 1.0)
    # float32 as the shader reads them: a guide past x's own cell would skip it
    upper = (np.cumsum(flat, axis=1) / flat.sum(axis=1, keepdims=True)).astype(np.float32)
    upper[:, -1] = 1.0
    lower = np.concatenate([np.zeros((len(flat), 1), np.float32), upper[:, :-1]], axis=1)
    starts = (np.arange(GUIDES * n) / (GUIDES * n)).astype(np.float32)
    # One search for all rows: row i's edges and starts lifted by i * 2^31 as the integers
    # of their float32 bits (which order non-negative floats as their values do)
    lift = np.arange(len(flat), dtype=np.int64)[:, None]
    keys = upper.view(np.int32).astype(np.int64) + (lift << 31)
    wanted = starts.view(np.int32).astype(np.int64)[None, :] + (lift << 31)
    found = np.searchsorted(keys.ravel(), wanted.ravel(), "right")
    cell = np.minimum(found.reshape(len(flat), -1) - lift * n, n - 1)
    following = np.take_along_axis(upper, np.minimum(cell + 1, n - 1), axis=1)
    out = np.zeros((len(flat), GUIDES * n + n, 4))
    out[:, : GUIDES * n, 0] = cell
    out[:, : GUIDES * n, 1] = np.take_along_axis(lower, cell, axis=1)
    out[:, : GUIDES * n, 2] = np.take_along_axis(upper, cell, axis=1)
    out[:, : GUIDES * n, 3] = following
    out[:, GUIDES * n :, 0], out[:, GUIDES * n :, 1] = lower, upper
    return out.reshape(*w.shape[:-1], GUIDES * n + n, 4)


def cell_probabilities(inverse: np.ndarray) -> np.ndarray:
    """(..., n): each cell's probability as the shader draws it, from `inversion_tables`."""
    cells = inverse[..., -(inverse.shape[-2] // (GUIDES + 1)) :, :2].astype(np.float64)
    return cells[..., 1] - cells[..., 0]


def masses(renderer, model, values) -> np.ndarray:
    """(VIEWS, ROWS, COLUMNS): f_r cos integrated over each cell, on the GPU."""
    uniforms = {"u_views": VIEWS, "u_rows": ROWS, "u_columns": COLUMNS}
    fbo = renderer._run(model, "ibl_table", values, (COLUMNS, VIEWS * ROWS), uniforms)
    return renderer._read(fbo)[..., 0].astype(np.float64).reshape(VIEWS, ROWS, COLUMNS)


def values_key(model, values) -> tuple:
    """What a table depends on: the model's code and its resolved parameter values."""
    resolved = model.resolve(values)
    items = tuple(sorted((k, repr(v)) for k, v in resolved.items()))
    return (str(model.path), model.code, id(getattr(model, "table", None)), items)


class TableCache:
    """The tables of one renderer, keyed by model and values; the last few are kept, so
    a slider moved back and forth does not rebuild."""

    KEEP = 8

    def __init__(self):
        self._tables: dict[tuple, Table] = {}

    def get(self, renderer, model, values) -> Table:
        import time

        key = values_key(model, values)
        table = self._tables.pop(key, None)
        if table is None:
            start = time.perf_counter()
            table = Table.from_masses(masses(renderer, model, values))
            table.bind(renderer.ctx)
            table.seconds = time.perf_counter() - start
            while len(self._tables) >= self.KEEP:
                oldest = next(iter(self._tables))
                self._tables.pop(oldest).release()
        self._tables[key] = table  # most recent last
        return table

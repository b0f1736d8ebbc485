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


def cell_solid_angles() -> np.ndarray:
    """(ROWS,) solid angle of one cell of each row: 1 - cos(theta_h) = u^4."""
    versine = (np.arange(ROWS + 1) / ROWS) ** 4
    return np.diff(versine) * (2.0 * math.pi / COLUMNS)


@dataclass
class Table:
    """One model's sampling table: density (VIEWS * ROWS, COLUMNS) per half-vector solid
    angle, and alias tables (probability, alias) for the rows of each view (VIEWS, ROWS, 2)
    and the cells of each row (VIEWS * ROWS, COLUMNS, 2)."""

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
        p = m / m.sum(axis=(1, 2), keepdims=True)
        density = p / cell_solid_angles()[None, :, None]
        rows = p.sum(axis=2)
        within = np.where(rows[..., None] > 0.0, p / np.maximum(rows[..., None], 1e-300), 1.0)
        return cls(
            density.reshape(VIEWS * ROWS, COLUMNS).astype(np.float32),
            alias_tables(rows).astype(np.float32),
            alias_tables(within.reshape(VIEWS * ROWS, COLUMNS)).astype(np.float32),
        )

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


def alias_tables(weights: np.ndarray) -> np.ndarray:
    """(..., n, 2): for each row of `weights` (..., n), Walker's alias table by Vose's
    method (Vose 1991): bin i keeps its own cell with probability [i, 0] and gives the rest
    to cell [i, 1], so that cell k is drawn with probability weights[k] / sum. A row with
    no weight is uniform."""
    w = np.asarray(weights, np.float64)
    flat = w.reshape(-1, w.shape[-1])
    n = flat.shape[1]
    out = np.zeros((flat.shape[0], n, 2))
    for index, row in enumerate(flat):
        total = row.sum()
        scaled = row * (n / total) if total > 0.0 else np.ones(n)
        prob, alias = np.ones(n), np.arange(n, dtype=np.float64)
        small = [i for i in range(n) if scaled[i] < 1.0]
        large = [i for i in range(n) if scaled[i] >= 1.0]
        while small and large:
            s, g = small.pop(), large.pop()
            prob[s], alias[s] = scaled[s], g
            scaled[g] -= 1.0 - scaled[s]
            (small if scaled[g] < 1.0 else large).append(g)
        out[index, :, 0], out[index, :, 1] = prob, alias  # leftovers keep prob 1 (rounding)
    return out.reshape(*w.shape, 2)


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

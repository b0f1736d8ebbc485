"""Tabulated BRDFs in the MERL layout (Matusik et al. 2003): read, write, index, look up.

A table holds f_r over the half/difference angles of Rusinkiewicz (1998) for an isotropic
material: theta_h (non-linear bins, dense near the specular peak), theta_d (linear over
90 deg) and phi_d (linear over 180 deg; phi_d and phi_d + 180 deg are the same
configuration with L and V swapped, so half the circle suffices).

File layout (.binary, little-endian): three int32 (n_theta_h, n_theta_d, n_phi_d) =
(90, 90, 180), then three blocks of n float64 values, one per channel (R, G, B), index
phi_d + n_phi_d * (theta_d + n_theta_d * theta_h). A stored value times the channel's
scale (1/1500, 1.15/1500, 1.66/1500) is f_r in 1/sr; negative values mean "not measured".

The real MERL database (100 isotropic materials) is distributed by MERL at
https://www.merl.com/brdf/ under its own terms; this project ships none of its files.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from lab.models import ModelError

MERL_DIMS = (90, 90, 180)
TABLE_UNIFORM = "u_table"  # the sampler a model file declares to read a table (exercise 12)
SCALE = np.array([1.0 / 1500.0, 1.15 / 1500.0, 1.66 / 1500.0])
HEADER_BYTES = 12
MAX_DIM = 4096  # a header larger than this is not a BRDF table but a misread file


class MerlFormatError(ModelError):
    """A .binary file that is not a valid table; the message says what and what to do."""


@dataclass
class MerlTable:
    """f_r samples on the (theta_h, theta_d, phi_d) grid.

    `raw` holds the values exactly as stored in the file, shape (3, n_h, n_d, n_p), so
    that reading and writing a file again gives the same bytes.
    """

    raw: np.ndarray
    path: Path | None = None

    @property
    def dims(self) -> tuple[int, int, int]:
        return tuple(int(n) for n in self.raw.shape[1:])  # type: ignore[return-value]

    @property
    def rgb(self) -> np.ndarray:
        """f_r in 1/sr, shape (n_h, n_d, n_p, 3); unmeasured entries stay negative."""
        return np.moveaxis(self.raw, 0, -1) * SCALE

    @classmethod
    def from_rgb(cls, rgb: np.ndarray) -> MerlTable:
        """A table from f_r values (n_h, n_d, n_p, 3) in 1/sr."""
        rgb = np.asarray(rgb, dtype=np.float64)
        if rgb.ndim != 4 or rgb.shape[-1] != 3:
            raise ValueError(f"expected f_r of shape (n_h, n_d, n_p, 3), got {rgb.shape}")
        return cls(np.ascontiguousarray(np.moveaxis(rgb / SCALE, -1, 0)))

    def measured(self) -> np.ndarray:
        """Boolean mask (n_h, n_d, n_p): every channel was measured."""
        return (self.raw >= 0.0).all(axis=0)


# -- file format -----------------------------------------------------------------------------
def read_merl(path: str | Path) -> MerlTable:
    """Read a .binary table; any defect raises MerlFormatError naming the file."""
    path = Path(path)
    try:
        data = path.read_bytes()
    except OSError as err:
        raise MerlFormatError(f"cannot read the table: {err.strerror}", path) from None
    if len(data) < HEADER_BYTES:
        raise MerlFormatError(
            f"file has {len(data)} bytes, too short for the 12-byte header: not a MERL .binary",
            path,
        )
    dims = tuple(int(n) for n in np.frombuffer(data, "<i4", 3))
    if any(n < 1 or n > MAX_DIM for n in dims):
        raise MerlFormatError(
            f"header gives dimensions {dims}, expected {MERL_DIMS} (theta_h, theta_d, phi_d): "
            "not a MERL .binary file (or a big-endian one)",
            path,
        )
    count = dims[0] * dims[1] * dims[2]
    expected = HEADER_BYTES + 3 * 8 * count
    if len(data) != expected:
        what = "truncated" if len(data) < expected else "has extra bytes"
        raise MerlFormatError(
            f"file {what}: the header's dimensions {dims} need {expected} bytes, the file has "
            f"{len(data)}; download it again or regenerate it with 'brdf-lab tabulate'",
            path,
        )
    raw = np.frombuffer(data, "<f8", 3 * count, HEADER_BYTES).reshape(3, *dims)
    bad = ~np.isfinite(raw)
    if bad.any():
        c, h, d, p = (int(i) for i in np.argwhere(bad)[0])
        raise MerlFormatError(
            f"{int(bad.sum())} value(s) are NaN or infinite, the first in channel "
            f"{'RGB'[c]} at bin (theta_h {h}, theta_d {d}, phi_d {p}); mark missing "
            "samples with a negative value instead",
            path,
        )
    return MerlTable(raw.astype(np.float64), path)


def merl_bytes(table: MerlTable) -> bytes:
    """The .binary file contents of `table`."""
    raw = np.asarray(table.raw, dtype=np.float64)
    if raw.ndim != 4 or raw.shape[0] != 3:
        raise ValueError(f"table data must have shape (3, n_h, n_d, n_p), not {raw.shape}")
    if not np.isfinite(raw).all():
        raise ValueError("table holds NaN or infinite values; mark missing samples negative")
    header = np.asarray(raw.shape[1:], dtype="<i4").tobytes()
    return header + raw.astype("<f8").tobytes(order="C")


def write_merl(table: MerlTable, path: str | Path) -> Path:
    path = Path(path)
    try:
        path.write_bytes(merl_bytes(table))
    except OSError as err:
        raise MerlFormatError(f"cannot write the table: {err.strerror}", path) from None
    return path


# -- angles and indices ------------------------------------------------------------------------
def _rotate(v: np.ndarray, axis: str, angle: np.ndarray) -> np.ndarray:
    """Rotate vectors v (..., 3) about the z or y axis by `angle` (right-handed)."""
    c, s = np.cos(angle), np.sin(angle)
    x, y, z = v[..., 0], v[..., 1], v[..., 2]
    if axis == "z":
        return np.stack([c * x - s * y, s * x + c * y, z], axis=-1)
    return np.stack([c * x + s * z, y, -s * x + c * z], axis=-1)


def half_diff(L: np.ndarray, V: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(theta_h, theta_d, phi_d) in radians for directions L, V (n, 3) in the frame N = z.

    The difference vector is L seen from a frame in which H is the pole: rotate L by
    -phi_h about N, then by -theta_h about the bitangent (Rusinkiewicz 1998).
    """
    L = np.asarray(L, dtype=np.float64).reshape(-1, 3)
    V = np.asarray(V, dtype=np.float64).reshape(-1, 3)
    H = L + V
    H /= np.maximum(np.linalg.norm(H, axis=1, keepdims=True), 1e-300)
    theta_h = np.arccos(np.clip(H[:, 2], -1.0, 1.0))
    phi_h = np.arctan2(H[:, 1], H[:, 0])
    d = _rotate(_rotate(L, "z", -phi_h), "y", -theta_h)
    theta_d = np.arccos(np.clip(d[:, 2], -1.0, 1.0))
    phi_d = np.arctan2(d[:, 1], d[:, 0])
    return theta_h, theta_d, phi_d


def directions(theta_h, theta_d, phi_d) -> tuple[np.ndarray, np.ndarray]:
    """L and V (n, 3) for half/difference angles in radians (phi_h = 0)."""
    theta_h, theta_d, phi_d = (
        np.asarray(a, dtype=np.float64).ravel() for a in (theta_h, theta_d, phi_d)
    )
    d = np.stack(
        [np.sin(theta_d) * np.cos(phi_d), np.sin(theta_d) * np.sin(phi_d), np.cos(theta_d)], axis=-1
    )
    mirrored = d * np.array([-1.0, -1.0, 1.0])  # V is L reflected about H
    return _rotate(d, "y", theta_h), _rotate(mirrored, "y", theta_h)


def continuous_index(theta_h, theta_d, phi_d, dims=MERL_DIMS) -> tuple[np.ndarray, ...]:
    """Position in bin units: bin i spans [i, i + 1), so floor() is the MERL index.

    theta_h is binned by sqrt(theta_h / 90 deg) (denser near the peak), theta_d linearly
    over 90 deg, phi_d linearly over 180 deg after folding phi_d < 0 by +180 deg.
    """
    n_h, n_d, n_p = dims
    theta_h = np.maximum(np.asarray(theta_h, dtype=np.float64), 0.0)
    phi_d = np.asarray(phi_d, dtype=np.float64)
    phi_d = np.where(phi_d < 0.0, phi_d + math.pi, phi_d)
    return (
        np.sqrt(theta_h / (math.pi / 2)) * n_h,
        np.asarray(theta_d, dtype=np.float64) / (math.pi / 2) * n_d,
        phi_d / math.pi * n_p,
    )


def bin_index(theta_h, theta_d, phi_d, dims=MERL_DIMS) -> tuple[np.ndarray, ...]:
    """The MERL indices (integer arrays), each clamped to its range."""
    return tuple(
        np.clip(np.floor(c), 0, n - 1).astype(np.int64)
        for c, n in zip(continuous_index(theta_h, theta_d, phi_d, dims), dims, strict=True)
    )


def bin_centres(dims=MERL_DIMS) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Angles (radians) at the centre of each bin along theta_h, theta_d and phi_d."""
    n_h, n_d, n_p = dims
    return (
        ((np.arange(n_h) + 0.5) / n_h) ** 2 * (math.pi / 2),
        (np.arange(n_d) + 0.5) / n_d * (math.pi / 2),
        (np.arange(n_p) + 0.5) / n_p * math.pi,
    )


def bin_grid(dims=MERL_DIMS) -> tuple[np.ndarray, np.ndarray]:
    """L and V (n, 3) at every bin centre, in file order."""
    th, td, pd = np.meshgrid(*bin_centres(dims), indexing="ij")
    return directions(th, td, pd)


def bin_weights(dims=MERL_DIMS) -> np.ndarray:
    """Measure of each bin in (omega_i, omega_o) space, shape dims, up to a constant.

    d omega_i d omega_o = 4 cos(theta_d) sin(theta_d) sin(theta_h) d theta_h d theta_d d phi_d
    d phi_h (Rusinkiewicz 1998); theta_h = (u / n_h)^2 pi / 2 adds d theta_h / du.
    """
    n_h, n_d, n_p = dims
    th, td, _ = bin_centres(dims)
    u = (np.arange(n_h) + 0.5) / n_h
    dth_du = math.pi * u / n_h
    wh = np.sin(th) * dth_du
    wd = np.cos(td) * np.sin(td)
    return np.broadcast_to((wh[:, None] * wd[None, :])[:, :, None], dims).copy()


# -- lookup -----------------------------------------------------------------------------------
def lookup(table: MerlTable, L: np.ndarray, V: np.ndarray, filter: str = "nearest") -> np.ndarray:
    """f_r (n, 3) from the table for direction pairs, as the `measured` shader does it.

    `nearest` returns the bin's value; `linear` interpolates trilinearly between bin
    centres (clamped in theta, periodic in phi_d). Unmeasured values count as 0, and so
    does any pair with L or V below the horizon.
    """
    L = np.asarray(L, dtype=np.float64).reshape(-1, 3)
    V = np.asarray(V, dtype=np.float64).reshape(-1, 3)
    rgb = np.maximum(table.rgb, 0.0)
    dims = table.dims
    angles = half_diff(L, V)
    if filter == "nearest":
        h, d, p = bin_index(*angles, dims)
        out = rgb[h, d, p]
    elif filter == "linear":
        out = interpolate(rgb, continuous_index(*angles, dims), dims)
    else:
        raise ValueError(f"filter must be nearest or linear, not {filter!r}")
    above = (L[:, 2] > 0.0) & (V[:, 2] > 0.0)
    return np.where(above[:, None], out, 0.0)


def interpolate(rgb: np.ndarray, coords, dims) -> np.ndarray:
    """(n, 3) trilinear values between bin centres at positions `coords` (bin units, as
    continuous_index gives them): clamped in theta, periodic in phi_d."""
    lower, frac = [], []
    for axis, (c, n) in enumerate(zip(coords, dims, strict=True)):
        c = np.asarray(c, dtype=np.float64) - 0.5
        if axis < 2:
            c = np.clip(c, 0.0, n - 1)
        base = np.floor(c)
        lower.append(base.astype(np.int64))
        frac.append(c - base)
    out = np.zeros((len(lower[0]), 3))
    for corner in range(8):
        bits = [(corner >> k) & 1 for k in range(3)]
        index = []
        weight = np.ones(len(lower[0]))
        for axis, n in enumerate(dims):
            i = lower[axis] + bits[axis]
            i = np.minimum(i, n - 1) if axis < 2 else np.mod(i, n)
            index.append(i)
            weight *= frac[axis] if bits[axis] else 1.0 - frac[axis]
        out += weight[:, None] * rgb[index[0], index[1], index[2]]
    return out

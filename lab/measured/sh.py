"""Real spherical harmonics for BRDF lobes: projection, reconstruction, error vs order.

The lobe for a fixed incident direction is the cosine-weighted BRDF g(w_o) =
f_r(w_i, w_o) cos(theta_o) on the upper hemisphere. It is extended to the whole sphere
as an odd function of z (g(x, y, -z) = -g(x, y, z)): the extension is continuous at the
horizon, so no coefficients are spent on a jump there, and a Lambertian lobe (a constant
times z) is exactly the degree-1 harmonic Y_1^0.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np


def coefficient_count(order: int) -> int:
    """Number of real harmonics up to degree `order`."""
    return (order + 1) ** 2


def associated_legendre(order: int, x: np.ndarray) -> np.ndarray:
    """P_l^m(x) for 0 <= m <= l <= order, shape (order + 1, order + 1, n), with the
    Condon-Shortley phase (as scipy.special.lpmv), by the standard three-term recurrence
    in l from P_m^m = (-1)^m (2m - 1)!! (1 - x^2)^(m/2) (no scipy: the app starts faster).
    """
    x = np.asarray(x, dtype=np.float64)
    sine = np.sqrt(np.maximum(1.0 - x * x, 0.0))
    table = np.zeros((order + 1, order + 1, *x.shape))
    diagonal = np.ones_like(x)
    for m in range(order + 1):
        if m:
            diagonal = -(2 * m - 1) * sine * diagonal
        table[m, m] = diagonal
        if m < order:
            table[m + 1, m] = (2 * m + 1) * x * diagonal
        for l in range(m + 2, order + 1):  # noqa: E741 (the usual name of the degree)
            table[l, m] = ((2 * l - 1) * x * table[l - 1, m] - (l + m - 1) * table[l - 2, m]) / (
                l - m
            )
    return table


def real_sh(order: int, theta: np.ndarray, phi: np.ndarray) -> np.ndarray:
    """Real orthonormal harmonics Y_lm (n, (order + 1)^2), index l^2 + l + m."""
    theta = np.asarray(theta, dtype=np.float64).ravel()
    phi = np.asarray(phi, dtype=np.float64).ravel()
    x = np.cos(theta)
    out = np.empty((len(theta), coefficient_count(order)))
    legendre = associated_legendre(order, x)
    for l in range(order + 1):  # noqa: E741 (the usual name of the degree)
        for m in range(l + 1):
            # P_l^m includes the Condon-Shortley phase (-1)^m; it cancels in the real basis
            # up to a sign per (l, m), which is harmless for projections.
            ratio = math.exp(math.lgamma(l - m + 1) - math.lgamma(l + m + 1))  # (l-m)!/(l+m)!
            norm = math.sqrt((2 * l + 1) / (4 * math.pi) * ratio)
            p = norm * legendre[l, m]
            if m == 0:
                out[:, l * l + l] = p
            else:
                out[:, l * l + l + m] = math.sqrt(2.0) * p * np.cos(m * phi)
                out[:, l * l + l - m] = math.sqrt(2.0) * p * np.sin(m * phi)
    return out


@dataclass
class Grid:
    """Quadrature on the upper hemisphere: Gauss-Legendre in cos(theta), uniform in phi."""

    theta: np.ndarray  # (n,)
    phi: np.ndarray
    weight: np.ndarray  # solid angle of each node

    @property
    def directions(self) -> np.ndarray:
        s = np.sin(self.theta)
        return np.stack([s * np.cos(self.phi), s * np.sin(self.phi), np.cos(self.theta)], -1)


def hemisphere_grid(n_theta: int = 96, n_phi: int = 192) -> Grid:
    x, w = np.polynomial.legendre.leggauss(2 * n_theta)
    x, w = x[n_theta:], w[n_theta:]  # the nodes with cos(theta) > 0
    phi = (np.arange(n_phi) + 0.5) * (2 * math.pi / n_phi)
    tt, pp = np.meshgrid(np.arccos(x), phi, indexing="ij")
    ww = np.repeat(w[:, None] * (2 * math.pi / n_phi), n_phi, axis=1)
    return Grid(tt.ravel(), pp.ravel(), ww.ravel())


def odd_in_z(order: int) -> np.ndarray:
    """1 for the harmonics that are odd in z (l + |m| odd), 0 for the others."""
    index = np.arange(coefficient_count(order))
    degree = np.floor(np.sqrt(index)).astype(int)
    m = index - degree * degree - degree
    return ((degree + np.abs(m)) % 2 == 1).astype(np.float64)


def project(
    lobe: np.ndarray, grid: Grid, order: int, basis: np.ndarray | None = None
) -> np.ndarray:
    """Coefficients ((order + 1)^2, channels) of the odd extension of `lobe` (n, channels).

    The lower hemisphere contributes as much as the upper one for harmonics that are odd
    in z (l + m odd) and cancels it for the others. `basis` may hold real_sh(order) on
    the grid already (it is the same for every lobe).
    """
    Y = (
        basis[:, : coefficient_count(order)]
        if basis is not None
        else real_sh(order, grid.theta, grid.phi)
    )
    return 2.0 * odd_in_z(order)[:, None] * (Y * grid.weight[:, None]).T @ lobe


class Projector:
    """Projection on one grid up to one order, with the harmonics computed once.

    For many lobes on the same grid (the app's view, as the light moves): projecting is
    then one matrix product.
    """

    def __init__(self, order: int, grid: Grid):
        self.order, self.grid = order, grid
        self.basis = real_sh(order, grid.theta, grid.phi)  # (n, (order + 1)^2)
        weighted = self.basis * grid.weight[:, None]
        self.analysis = np.ascontiguousarray(2.0 * odd_in_z(order)[:, None] * weighted.T)

    def project(self, lobe: np.ndarray) -> np.ndarray:
        """As project(lobe, grid, order): coefficients ((order + 1)^2, channels)."""
        return self.analysis @ lobe

    def errors(self, lobe: np.ndarray, coefficients: np.ndarray) -> np.ndarray:
        """Relative L2 error over the hemisphere of the series of every order 0..order."""
        w = self.grid.weight[:, None]
        norm = float(np.sqrt((w * lobe**2).sum()))
        approx = np.zeros_like(lobe, dtype=np.float64)
        out = np.empty(self.order + 1)
        for order in range(self.order + 1):  # add one degree's block at a time
            block = slice(order * order, (order + 1) ** 2)
            approx += self.basis[:, block] @ coefficients[block]
            out[order] = float(np.sqrt((w * (approx - lobe) ** 2).sum())) / max(norm, 1e-300)
        return out


def reconstruct(coefficients: np.ndarray, theta: np.ndarray, phi: np.ndarray) -> np.ndarray:
    order = int(round(math.sqrt(coefficients.shape[0]))) - 1
    return real_sh(order, theta, phi) @ coefficients


def relative_error(lobe: np.ndarray, approx: np.ndarray, grid: Grid) -> float:
    """L2 error over the hemisphere relative to the lobe's L2 norm."""
    w = grid.weight[:, None]
    norm = float(np.sqrt((w * lobe**2).sum()))
    return float(np.sqrt((w * (approx - lobe) ** 2).sum())) / max(norm, 1e-300)


def cosine_lobe(
    f: Callable[[np.ndarray, np.ndarray], np.ndarray], theta_i_deg: float, grid: Grid
) -> np.ndarray:
    """g = f_r(w_i, w_o) cos(theta_o) (n, 3) at the grid's directions, for w_i at theta_i."""
    V = grid.directions
    t = math.radians(theta_i_deg)
    L = np.repeat(np.array([[math.sin(t), 0.0, math.cos(t)]]), len(V), axis=0)
    return np.asarray(f(L, V), dtype=np.float64) * V[:, 2:3]


def error_by_order(lobe: np.ndarray, grid: Grid, orders) -> list[tuple[int, int, float]]:
    """(order, coefficient count, relative error) for each order."""
    top = max(orders)
    coefficients = project(lobe, grid, top)
    Y = real_sh(top, grid.theta, grid.phi)
    rows = []
    for order in orders:
        n = coefficient_count(order)
        approx = Y[:, :n] @ coefficients[:n]
        rows.append((order, n, relative_error(lobe, approx, grid)))
    return rows

"""Checks of a BRDF sampler against its own pdf (pbrt-v4's BSDF tests, Pharr et al.).

`chi_square` bins many GPU samples over the sphere in (cos theta, phi) and compares the
counts with the pdf integrated over each bin; `pdf_integral` integrates the pdf over the
sphere (it must be 1). Both run the model's sampler on the GPU (IBLRenderer).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy import stats

from lab.ibl.integrator import IBLRenderer

THETA_BINS, PHI_BINS, SUB = 20, 40, 16
MIN_EXPECTED = 5.0


@dataclass
class ChiSquare:
    statistic: float
    dof: int
    p_value: float
    invalid: int  # samples that are not unit vectors, or carry pdf <= 0


def view_direction(theta_deg: float) -> np.ndarray:
    t = np.radians(theta_deg)
    return np.array([np.sin(t), 0.0, np.cos(t)])


def _grid(n_theta: int, n_phi: int, sub: int):
    """Sub-bin centres (cos theta, phi) and their solid angle, shaped for bin sums."""
    cos_t = -1.0 + (np.arange(n_theta * sub) + 0.5) * 2.0 / (n_theta * sub)
    phi = (np.arange(n_phi * sub) + 0.5) * 2.0 * np.pi / (n_phi * sub)
    c, p = np.meshgrid(cos_t, phi, indexing="ij")
    s = np.sqrt(1.0 - c * c)
    L = np.stack([s * np.cos(p), s * np.sin(p), c], axis=-1).reshape(-1, 3)
    d_omega = (2.0 / (n_theta * sub)) * (2.0 * np.pi / (n_phi * sub))
    return L, d_omega


def bin_probabilities(renderer: IBLRenderer, model, values, V, n_theta, n_phi, sub):
    L, d_omega = _grid(n_theta, n_phi, sub)
    pdf = renderer.brdf_pdf(model, values, L, V).reshape(n_theta * sub, n_phi * sub)
    return pdf.reshape(n_theta, sub, n_phi, sub).sum(axis=(1, 3)) * d_omega


def pdf_integral(renderer: IBLRenderer, model, values, theta_v: float = 30.0) -> float:
    """The pdf integrated over the whole sphere (fine midpoint rule): 1 for a correct pdf,
    less by the share of failed samples for half-vector samplers (H facing away from V)."""
    return float(
        bin_probabilities(renderer, model, values, view_direction(theta_v), 90, 180, 4).sum()
    )


def chi_square(
    renderer: IBLRenderer, model, values, theta_v: float = 30.0, n: int = 200_000, seed: int = 7
) -> ChiSquare:
    """Pearson's test of the samples' histogram against the pdf's bin probabilities."""
    V = view_direction(theta_v)
    out = renderer.brdf_samples(model, values, np.repeat(V[None], n, axis=0), seed)
    L, pdf = out[:, :3], out[:, 3]
    length = np.linalg.norm(L, axis=1)
    valid = (np.abs(length - 1.0) < 1e-3) & (pdf > 0.0) & np.isfinite(pdf)
    L = L[valid] / length[valid, None]
    cos_t = np.clip(L[:, 2], -1.0, 1.0)
    phi = np.arctan2(L[:, 1], L[:, 0]) % (2.0 * np.pi)
    ti = np.clip(((cos_t + 1.0) / 2.0 * THETA_BINS).astype(int), 0, THETA_BINS - 1)
    pi = np.clip((phi / (2.0 * np.pi) * PHI_BINS).astype(int), 0, PHI_BINS - 1)
    observed = np.bincount(ti * PHI_BINS + pi, minlength=THETA_BINS * PHI_BINS).astype(float)
    expected = bin_probabilities(renderer, model, values, V, THETA_BINS, PHI_BINS, SUB).ravel()
    expected *= n
    # Bins expected to hold few samples are pooled into one (the test needs >= 5 each).
    order = np.argsort(expected)
    obs, exp = [], []
    pool_o = pool_e = 0.0
    for i in order:
        if expected[i] < MIN_EXPECTED:
            pool_o += observed[i]
            pool_e += expected[i]
        else:
            obs.append(observed[i])
            exp.append(expected[i])
    # Failed samples (a half vector facing away from V) are the pdf's missing mass.
    pool_o += n - valid.sum()
    pool_e += max(n - expected.sum(), 0.0)
    if pool_e > 0.0 or pool_o > 0.0:
        obs.append(pool_o)
        exp.append(max(pool_e, 1e-9))
    obs, exp = np.array(obs), np.array(exp)
    statistic = float(np.sum((obs - exp) ** 2 / exp))
    dof = len(obs) - 1
    return ChiSquare(statistic, dof, float(stats.chi2.sf(statistic, dof)), int(n - valid.sum()))

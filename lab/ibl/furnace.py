"""The white furnace test: under a uniform environment of radiance 1, the reflected radiance
toward V equals the directional albedo at V (for a reciprocal BRDF), so an IBL render must
reproduce the albedo view; a value above 1 is energy created from nothing.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from lab.ibl.integrator import Environment, IBLRenderer, local_view, render, ring_peak
from lab.models import Model
from lab.render import as_model

THETA_MAX = 80.0  # beyond it a pixel's footprint spans many view angles
BINS = 16


@dataclass
class FurnaceResult:
    theta: np.ndarray  # (BINS,) bin centres in degrees
    rendered: np.ndarray  # (BINS, 3) mean radiance of the pixels in each bin
    albedo: np.ndarray  # (BINS, 3) mean albedo (the albedo view) of the same pixels
    peak: float  # the largest mean luminance of a ring of equal view angle (ring_peak)

    @property
    def max_relative_error(self) -> float:
        return float(np.max(np.abs(self.rendered - self.albedo) / np.maximum(self.albedo, 1e-4)))

    @property
    def energy_gain(self) -> bool:
        """Reflects more than it receives somewhere (beyond the Monte Carlo noise)."""
        return self.peak > 1.01


def albedo_table(renderer: IBLRenderer, model: Model, values, thetas, phis) -> np.ndarray:
    """The albedo view's a(theta, phi) on a grid: (len(phis), len(thetas), 3)."""
    return np.stack([renderer.albedo(model, values, thetas, phi, 512, 128) for phi in phis])


def furnace(
    model: Model | str,
    values: dict | None = None,
    samples: int = 1024,
    size: int = 64,
    strategy: str = "brdf",
    renderer: IBLRenderer | None = None,
    sequence: str = "random",
) -> FurnaceResult:
    """Render `model` in the white furnace and compare with its albedo view, bin by bin."""
    renderer = renderer or IBLRenderer()
    model = as_model(model)
    env = Environment(np.ones((16, 32, 3), np.float32), "furnace")
    image = render(
        model, values, env, strategy, samples, size, renderer=renderer, sequence=sequence
    )
    return against_albedo(image, model, values, renderer)


def against_albedo(
    image: np.ndarray, model: Model | str, values: dict | None, renderer: IBLRenderer
) -> FurnaceResult:
    """Compare a furnace render (size, size, 4), row 0 at the top (any renderer's: the
    web lab's too), with the albedo view, bin by bin of the view angle."""
    model = as_model(model)
    size = image.shape[0]
    theta, phi, mask = local_view(size)
    thetas = np.linspace(0.0, THETA_MAX, 41)
    isotropic = "isotropic" in model.properties
    phis = np.array([0.0]) if isotropic else np.arange(0.0, 361.0, 15.0)
    table = albedo_table(renderer, model, values, thetas, phis)
    keep = mask & (theta <= THETA_MAX)
    t, p = theta[keep], phi[keep]
    rgb = image[..., :3][keep].astype(np.float64)
    # bilinear interpolation of the table at each pixel's (theta, phi)
    ti = np.clip(t / (thetas[1] - thetas[0]), 0, len(thetas) - 1.001)
    t0, tf = ti.astype(int), (ti - ti.astype(int))[:, None]
    if isotropic:
        a = table[0, t0] * (1 - tf) + table[0, t0 + 1] * tf
    else:
        pi = np.clip(p / 15.0, 0, len(phis) - 1.001)
        p0, pf = pi.astype(int), (pi - pi.astype(int))[:, None]
        a = (table[p0, t0] * (1 - tf) + table[p0, t0 + 1] * tf) * (1 - pf) + (
            table[p0 + 1, t0] * (1 - tf) + table[p0 + 1, t0 + 1] * tf
        ) * pf
    edges = np.linspace(0.0, THETA_MAX, BINS + 1)
    which = np.clip(np.digitize(t, edges) - 1, 0, BINS - 1)
    rendered = np.stack([rgb[which == b].mean(axis=0) for b in range(BINS)])
    albedo = np.stack([a[which == b].mean(axis=0) for b in range(BINS)])
    peak = ring_peak(image)
    return FurnaceResult(0.5 * (edges[1:] + edges[:-1]), rendered, albedo, peak)

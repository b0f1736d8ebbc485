"""Directions from angles: the lab's conventions for θ, φ and the plane of incidence."""

from __future__ import annotations

import numpy as np


def direction(theta_deg, phi_deg) -> np.ndarray:
    """Unit vectors for angles in degrees (theta from N = z, phi from X = x)."""
    theta = np.radians(np.asarray(theta_deg, dtype=np.float64))
    phi = np.radians(np.asarray(phi_deg, dtype=np.float64))
    d = np.stack([np.sin(theta) * np.cos(phi), np.sin(theta) * np.sin(phi), np.cos(theta)], axis=-1)
    # cos(90 deg) is 6e-17 in floating point: snap it so that theta = 90 lies on the horizon
    # (f_r = 0 there) rather than 6e-17 above it.
    d[np.abs(d) < 1e-12] = 0.0
    return d


def plane_of_incidence(theta_i: float, phi_i: float = 0.0, step: float = 1.0):
    """theta_o (deg) and viewing directions V in the plane of incidence.

    Positive theta_o lies on the far side from the light, so theta_o = theta_i is the
    mirror direction and negative angles look back toward the light.
    """
    theta_o = np.arange(-90.0, 90.0 + step / 2, step)
    V = direction(np.abs(theta_o), np.where(theta_o >= 0, phi_i + 180.0, phi_i))
    return theta_o, V

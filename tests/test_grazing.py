"""Every model's GLSL against the numpy reference up to the horizon: 89.9999 deg and 90 deg.

float32 keeps the forms of the shaders accurate to the horizon (GGX's visibility without
tan^2, Cook-Torrance's V.H from |L + V|): relative 1e-3 up to 89.9 deg, 5% beyond it, where
float32 direction vectors lose digits, and 0 on both sides at exactly 90 deg.
"""

from __future__ import annotations

import itertools

import numpy as np
import pytest

from lab import reference
from lab.models import load_model, model_names
from lab.render import direction

THETA = [0, 10, 30, 45, 60, 75, 85, 89, 89.5, 89.9, 89.99, 89.999, 89.9999, 90]
DPHI = [0, 45, 90, 135, 180]  # 180: the plane of incidence, mirror pairs included
PHI_I = [0, 37]  # 37: off the axes of Ward's anisotropy

SHARP = {"kd": (0.01, 0.01, 0.01)}  # a small floor keeps "relative" meaningful off the lobe
SETTINGS: dict[str, list[dict]] = {
    "ggx": [{}, {"alpha": 0.01, **SHARP}, {"alpha": 1.0, "kd": (0, 0, 0)}],
    "cook_torrance": [{}]
    + [
        {"m": m, "distribution": d, "fresnel": f, **SHARP}
        for d in ("beckmann", "blinn", "gaussian")
        for f in ("schlick", "dielectric", "none")
        for m in (0.05, 1.0)
    ],
    "ward": [{}, {"alpha_x": 0.02, "alpha_y": 0.5, **SHARP}],
    "phong": [{}, {"ke": 1000.0, **SHARP}],
    "blinn_phong": [{}, {"ke": 1000.0, **SHARP}],
    "oren_nayar": [{}, {"sigma": 1.0}],
}
CASES = [
    (name, settings)
    for name in model_names()
    if not load_model(name).delta
    for settings in SETTINGS.get(name, [{}])
]


def grid() -> np.ndarray:
    """Rows (theta_i, phi_i, theta_o, phi_o) in degrees over the dense grazing grid."""
    rows = [
        (ti, pi, to, pi + dp)
        for ti, to in itertools.product(THETA, THETA)
        for dp in DPHI
        for pi in PHI_I
    ]
    return np.array(rows, dtype=np.float64)


def bands(rows: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Masks: both angles <= 89.9; one beyond 89.9 but below 90; one exactly 90."""
    top = np.maximum(rows[:, 0], rows[:, 2])
    return top <= 89.9, (top > 89.9) & (top < 90.0), top >= 90.0


def mismatch(gpu: np.ndarray, cpu: np.ndarray, rtol: float, mask: np.ndarray) -> np.ndarray:
    """Rows of `mask` where some channel differs by more than rtol relative."""
    bad = np.abs(gpu - cpu) > rtol * np.abs(cpu) + 1e-9
    return mask & bad.any(axis=1)


IDS = [f"{n}-{i}" for i, (n, _) in enumerate(CASES)]


@pytest.mark.parametrize(("name", "settings"), CASES, ids=IDS)
def test_gpu_matches_reference_up_to_the_horizon(renderer, name, settings):
    """The plots' path: directions made in float64 on the host, f_r on the GPU."""
    model = load_model(name)
    values = model.resolve(settings)
    rows = grid()
    L, V = direction(rows[:, 0], rows[:, 1]), direction(rows[:, 2], rows[:, 3])
    gpu = renderer.probe(model, values, L, V).astype(np.float64)
    cpu = reference.brdf(name, values, L, V)
    assert np.isfinite(gpu).all(), f"{name}: not finite at {rows[~np.isfinite(gpu).all(1)][0]}"
    inside, grazing, horizon = bands(rows)
    for rtol, mask in ((1e-3, inside), (0.05, grazing)):
        bad = mismatch(gpu, cpu, rtol, mask)
        assert not bad.any(), (
            f"{name} {settings}: {bad.sum()} rows beyond {rtol:g}, e.g. {rows[bad][0]} "
            f"gpu {gpu[bad][0]} cpu {cpu[bad][0]}"
        )
    assert (gpu[horizon] == 0).all() and (cpu[horizon] == 0).all()
    # The grid reaches the values the plots would scale to: large, but finite and right.
    assert cpu[grazing].max() > 0


@pytest.mark.parametrize("name", [n for n in model_names() if not load_model(n).delta])
def test_angles_path_up_to_the_horizon(renderer, name):
    """`eval` makes directions on the GPU from float32 radians: compared at those angles."""
    model = load_model(name)
    values = model.defaults()
    rows = grid()
    exact = np.degrees(np.radians(rows).astype(np.float32).astype(np.float64))
    exact[rows == 90.0] = 90.0  # float32(pi/2) lies past the horizon; the reference snaps 90
    gpu = renderer.eval_angles(model, values, rows).astype(np.float64)
    cpu = reference.brdf_angles(name, values, exact)
    assert np.isfinite(gpu).all()
    inside, grazing, horizon = bands(rows)
    for rtol, mask in ((1e-3, inside), (0.05, grazing)):
        bad = mismatch(gpu, cpu, rtol, mask)
        assert not bad.any(), f"{name}: {rows[bad][0]} gpu {gpu[bad][0]} cpu {cpu[bad][0]}"
    assert (gpu[horizon] == 0).all()


def test_ggx_issue_values_at_45_deg(renderer):
    """The values once reported wrong: GGX at theta_i = 45 deg toward the horizon (0.171)."""
    theta_o = np.array([89.99, 89.999, 89.9999, 90.0])
    L = direction(np.full(4, 45.0), np.zeros(4))
    V = direction(theta_o, np.full(4, 180.0))
    gpu = renderer.probe("ggx", load_model("ggx").defaults(), L, V)[:, 0]
    cpu = reference.brdf("ggx", {}, L, V)[:, 0]
    np.testing.assert_allclose(gpu[:3], cpu[:3], rtol=1e-3)
    np.testing.assert_allclose(cpu[:3], 0.171, atol=0.001)
    assert gpu[3] == 0.0

"""Spherical-harmonic projection of BRDF lobes."""

from __future__ import annotations

import numpy as np

from lab import reference
from lab.cli import main
from lab.measured import sh


def test_real_harmonics_are_orthonormal():
    x, w = np.polynomial.legendre.leggauss(24)
    phi = (np.arange(48) + 0.5) * (2 * np.pi / 48)
    tt, pp = np.meshgrid(np.arccos(x), phi, indexing="ij")
    weight = np.repeat(w[:, None] * (2 * np.pi / 48), 48, axis=1).ravel()
    Y = sh.real_sh(6, tt.ravel(), pp.ravel())
    assert np.allclose((Y * weight[:, None]).T @ Y, np.eye(49), atol=1e-10)


def test_lambertian_lobe_is_exact_at_order_one():
    grid = sh.hemisphere_grid(32, 64)
    lobe = sh.cosine_lobe(lambda L, V: reference.brdf("lambert", {}, L, V), 40.0, grid)
    rows = sh.error_by_order(lobe, grid, [0, 1, 2, 4])
    assert rows[0][2] > 0.99  # a constant cannot be odd in z
    assert all(error < 1e-10 for _, _, error in rows[1:])


def test_error_falls_with_order_for_a_glossy_lobe():
    grid = sh.hemisphere_grid()
    lobe = sh.cosine_lobe(lambda L, V: reference.brdf("ggx", {"alpha": 0.3}, L, V), 45.0, grid)
    rows = sh.error_by_order(lobe, grid, [1, 2, 4, 8, 12, 16])
    errors = [e for _, _, e in rows]
    assert all(b <= a + 1e-12 for a, b in zip(errors, errors[1:], strict=False))
    assert errors[-1] < 0.1 * errors[1]
    assert [n for _, n, _ in rows] == [4, 9, 25, 81, 169, 289]


def test_sh_command(tmp_path, capsys):
    out = tmp_path / "sh.png"
    assert main(["sh", "blinn_phong", "--set", "ke=20", "--orders", "0,2,8", "-o", str(out)]) == 0
    text = capsys.readouterr().out
    assert "coefficients" in text and " 81 " in text and out.stat().st_size > 10000
    assert main(["sh", "--orders", "x", "-o", str(out)]) == 2


def test_legendre_recurrence_matches_scipy():
    """The app's own P_l^m (no scipy at start-up) equals scipy's lpmv, phase included."""
    from scipy.special import lpmv

    from lab.measured.sh import associated_legendre

    x = np.linspace(-1.0, 1.0, 101)
    table = associated_legendre(16, x)
    for l in range(17):  # noqa: E741
        for m in range(l + 1):
            np.testing.assert_allclose(
                table[l, m],
                lpmv(m, l, x),
                rtol=1e-10,
                atol=1e-12 * abs(lpmv(m, l, x)).max(),
                err_msg=f"l={l} m={m}",
            )

"""The numpy oracle (lab/reference.py) against hand-computed values and physics."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import integrate

from lab import reference as ref

PI = math.pi


def dirs(theta_deg: float, phi_deg: float) -> np.ndarray:
    """One direction (1, 3) from degrees, written out here rather than via ref.direction."""
    t, p = math.radians(theta_deg), math.radians(phi_deg)
    return np.array([[math.sin(t) * math.cos(p), math.sin(t) * math.sin(p), math.cos(t)]])


def f1(model: str, params: dict, light: tuple[float, float], view: tuple[float, float]):
    """f_r (3,) for one (theta, phi) light and view, in degrees."""
    return ref.brdf(model, params, dirs(*light), dirs(*view))[0]


def hemisphere_integral(fn, points=()) -> float:
    """2 pi int_0^{pi/2} fn(a) cos a sin a da (an isotropic function of the angle to N)."""
    edges = [0.0, *sorted(p for p in points if 0.0 < p < PI / 2), PI / 2]
    total = 0.0
    for lo, hi in zip(edges[:-1], edges[1:], strict=True):
        total += integrate.quad(
            lambda a: fn(a) * math.cos(a) * math.sin(a), lo, hi, epsabs=0, epsrel=1e-11, limit=200
        )[0]
    return 2.0 * PI * total


@pytest.fixture(scope="module")
def pairs() -> tuple[np.ndarray, np.ndarray]:
    rng = np.random.default_rng(7)
    n = 400
    theta = np.arccos(rng.uniform(0.02, 1.0, size=(2, n)))
    phi = rng.uniform(-PI, PI, size=(2, n))
    return ref.direction(theta[0], phi[0]), ref.direction(theta[1], phi[1])


# Every enum combination of Cook-Torrance plus anisotropic Ward: the reciprocal set.
RECIPROCAL = [
    ("lambert", {"albedo": (0.2, 0.5, 0.9)}),
    ("phong", {"ke": 20.0}),
    ("blinn_phong", {"ke": 20.0}),
    ("ward", {"alpha_x": 0.1, "alpha_y": 0.4}),
    *[
        ("cook_torrance", {"distribution": d, "fresnel": f, "m": 0.4})
        for d in ("beckmann", "blinn", "gaussian")
        for f in ("schlick", "dielectric", "none")
    ],
    ("ggx", {"alpha": 0.3}),
    ("oren_nayar", {"sigma": 0.8}),
    ("lommel_seeliger", {}),
]


# --- point values -------------------------------------------------------------------


def test_models_and_defaults():
    assert set(ref.MODELS) == {
        "lambert", "mirror", "phong", "blinn_phong", "ward", "cook_torrance", "ggx",
        "oren_nayar", "lommel_seeliger", "phong_illumination",
    }  # fmt: skip
    # Missing keys fall back to the header default albedo 0.8.
    np.testing.assert_allclose(f1("lambert", {}, (10, 0), (50, 70)), 0.8 / PI, rtol=1e-14)
    with pytest.raises(ValueError):
        ref.brdf("lambert", {"albedoo": 0.5}, dirs(0, 0), dirs(0, 0))


def test_lambert_is_albedo_over_pi(pairs):
    L, V = pairs
    f = ref.brdf("lambert", {"albedo": (0.2, 0.5, 0.9)}, L, V)
    np.testing.assert_allclose(f, np.tile([0.2 / PI, 0.5 / PI, 0.9 / PI], (len(L), 1)))


@pytest.mark.parametrize("model", [m for m in ref.MODELS])
def test_zero_below_horizon(model):
    up, down, grazing = dirs(30, 40), dirs(100, 10), np.array([[1.0, 0.0, 0.0]])
    for L, V in [(up, down), (down, up), (down, down), (up, grazing), (grazing, up)]:
        assert np.all(ref.brdf(model, {}, L, V) == 0.0)
    angles = np.array([[90.0, 0.0, 30.0, 180.0], [30.0, 0.0, 90.0, 180.0]])
    assert np.all(ref.brdf_angles(model, {}, angles) == 0.0)


def test_blinn_phong_at_h_equals_n():
    params = {"kd": (0.3, 0.1, 0.0), "ks": (0.5, 0.25, 1.0), "ke": 80.0}
    f = f1("blinn_phong", params, (35, 20), (35, 200))
    np.testing.assert_allclose(f, [0.3 / PI + 0.5, 0.1 / PI + 0.25, 1.0], rtol=1e-12)
    # 10 deg off the normal in H: the lobe is cos(5 deg)^80.
    f = f1("blinn_phong", params, (40, 0), (30, 180))
    np.testing.assert_allclose(f[2], math.cos(math.radians(5)) ** 80, rtol=1e-12)


def test_phong_at_and_near_the_mirror_direction():
    params = {"kd": (0.3, 0.3, 0.3), "ks": (0.5, 0.5, 0.5), "ke": 50.0}
    np.testing.assert_allclose(f1("phong", params, (30, 0), (30, 180)), 0.3 / PI + 0.5)
    # 10 deg beyond the mirror direction in the plane of incidence.
    expected = 0.3 / PI + 0.5 * math.cos(math.radians(10)) ** 50
    np.testing.assert_allclose(f1("phong", params, (30, 0), (40, 180)), expected, rtol=1e-12)
    # 90 deg or more away from R: diffuse only.
    np.testing.assert_allclose(f1("phong", params, (30, 0), (60, 0)), 0.3 / PI, rtol=1e-12)


def test_phong_illumination_divides_the_lobe_by_cos_theta_i_and_is_not_reciprocal():
    params = {"kd": (0.3, 0.3, 0.3), "ks": (0.5, 0.5, 0.5), "ke": 50.0}
    lobe = math.cos(math.radians(5)) ** 50
    forward = f1("phong_illumination", params, (20, 0), (25, 180))
    backward = f1("phong_illumination", params, (25, 180), (20, 0))
    # The slide's kd multiplies N.L directly: as a BRDF it is kd itself, without 1/pi.
    np.testing.assert_allclose(forward, 0.3 + 0.5 * lobe / math.cos(math.radians(20)))
    np.testing.assert_allclose(backward, 0.3 + 0.5 * lobe / math.cos(math.radians(25)))
    assert abs(forward[0] - backward[0]) > 0.01


def test_ward_isotropic_at_h_equals_n():
    sigma, theta = 0.2, 50.0
    params = {"kd": (0.2,) * 3, "ks": (0.3,) * 3, "alpha_x": sigma, "alpha_y": sigma}
    expected = 0.2 / PI + 0.3 / (4 * PI * sigma**2 * math.cos(math.radians(theta)))
    np.testing.assert_allclose(f1("ward", params, (theta, 77), (theta, 257)), expected)


@pytest.mark.parametrize("phi, alpha_name", [(0.0, "alpha_x"), (90.0, "alpha_y")])
def test_ward_anisotropic_along_each_axis(phi, alpha_name):
    # L at +0.5 rad and V at -0.1 rad in one plane through N: H is tilted by 0.2 rad.
    params = {"kd": (0.0,) * 3, "ks": (1.0,) * 3, "alpha_x": 0.1, "alpha_y": 0.4}
    L = dirs(math.degrees(0.5), phi)
    V = dirs(math.degrees(0.1), phi + 180)
    a = params[alpha_name]
    expected = math.exp(-(math.tan(0.2) ** 2) / a**2) / (
        4 * PI * 0.1 * 0.4 * math.sqrt(math.cos(0.5) * math.cos(0.1))
    )
    np.testing.assert_allclose(ref.brdf("ward", params, L, V)[0], expected, rtol=1e-12)


def test_oren_nayar_hand_values_and_sigma_zero_is_lambert(pairs):
    s2 = 0.5**2
    A = 1 - 0.5 * s2 / (s2 + 0.33)
    B = 0.45 * s2 / (s2 + 0.09)
    params = {"albedo": (0.8,) * 3, "sigma": 0.5}
    # Same azimuth, 60 deg each: sin(60) tan(60) = 3/2.
    np.testing.assert_allclose(f1("oren_nayar", params, (60, 0), (60, 0)), 0.8 / PI * (A + 1.5 * B))
    np.testing.assert_allclose(f1("oren_nayar", params, (60, 0), (60, 90)), 0.8 / PI * A)
    np.testing.assert_allclose(f1("oren_nayar", params, (60, 0), (60, 180)), 0.8 / PI * A)
    # Along N the azimuth term vanishes.
    np.testing.assert_allclose(f1("oren_nayar", params, (0, 0), (70, 0)), 0.8 / PI * A)
    L, V = pairs
    albedo = {"albedo": (0.1, 0.4, 0.7)}
    np.testing.assert_allclose(
        ref.brdf("oren_nayar", {**albedo, "sigma": 0.0}, L, V),
        ref.brdf("lambert", albedo, L, V),
        rtol=1e-14,
    )


def test_lommel_seeliger_hand_value():
    expected = 0.8 / (4 * PI * (math.cos(math.radians(30)) + math.cos(math.radians(60))))
    np.testing.assert_allclose(f1("lommel_seeliger", {}, (30, 0), (60, 123)), expected)


def test_cook_torrance_and_ggx_at_normal_incidence():
    # L = V = N: H = N, V.H = 1, so G = 1 and F = f0.
    m, f0 = 0.3, 0.04
    ct = f1("cook_torrance", {"kd": (0,) * 3, "m": m}, (0, 0), (0, 0))
    np.testing.assert_allclose(ct, f0 * (1 / (4 * m * m)) / PI, rtol=1e-12)
    a = 0.25
    ggx = f1("ggx", {"kd": (0,) * 3, "alpha": a}, (0, 0), (0, 0))
    np.testing.assert_allclose(ggx, f0 * (1 / (PI * a * a)) / 4, rtol=1e-12)


def test_mirror_is_a_delta():
    L, V = dirs(30, 0), dirs(30, 180)
    assert np.all(ref.brdf("mirror", {}, L, V) == 0.0)
    rho = (0.9, 0.5, 0.1)
    np.testing.assert_array_equal(ref.delta_reflectance("mirror", {"rho_s": rho}, L)[0], rho)
    assert np.all(ref.delta_reflectance("mirror", {}, dirs(120, 0)) == 0.0)
    np.testing.assert_array_equal(ref.directional_albedo("mirror", {"rho_s": rho}, 40.0), rho)


def test_brdf_angles_matches_brdf():
    angles = np.array([[30.0, 10.0, 45.0, 200.0], [70.0, -40.0, 5.0, 33.0]])
    L = np.vstack([dirs(30, 10), dirs(70, -40)])
    V = np.vstack([dirs(45, 200), dirs(5, 33)])
    params = {"alpha_x": 0.1, "alpha_y": 0.3}
    np.testing.assert_allclose(
        ref.brdf_angles("ward", params, angles), ref.brdf("ward", params, L, V)
    )


# --- terms ----------------------------------------------------------------------------


@pytest.mark.parametrize("m", [0.05, 0.3, 1.0])
def test_distributions_integrate_to_pi_over_4(m):
    beta = math.atan(m)
    D = {
        "beckmann": lambda a: float(ref.d_beckmann(np.array(a), m)),
        "blinn": lambda a: float(ref.d_blinn(np.array(a), beta)),
        "gaussian": lambda a: float(ref.d_gaussian(np.array(a), beta)),
    }
    for name, fn in D.items():
        value = hemisphere_integral(fn, points=[beta, 3 * beta, 10 * beta])
        assert value == pytest.approx(PI / 4, rel=1e-7), name


@pytest.mark.parametrize("alpha", [0.01, 0.25, 1.0])
def test_ggx_d_integrates_to_one(alpha):
    fn = lambda a: float(ref.d_ggx(np.array(a), alpha))  # noqa: E731
    value = hemisphere_integral(fn, points=[alpha, 10 * alpha, 100 * alpha])
    assert value == pytest.approx(1.0, rel=1e-7)


@pytest.mark.parametrize("m", [0.01, 0.3, 1.0])
def test_blinn_and_gaussian_halve_at_beta(m):
    beta = math.atan(m)
    for D in (ref.d_blinn, ref.d_gaussian):
        ratio = float(D(np.array(beta), beta) / D(np.array(0.0), beta))
        assert ratio == pytest.approx(0.5, rel=1e-12)


def test_beckmann_peak_and_gaussian_norm_small_angle_limit():
    assert float(ref.d_beckmann(np.array(0.0), 0.2)) == pytest.approx(1 / (4 * 0.04))
    # For a narrow lobe the normaliser tends to 2 pi int exp(-ln2 a^2/b^2) a da = pi b^2/ln2.
    beta = 0.01
    assert ref.gaussian_norm(beta) == pytest.approx(PI * beta**2 / math.log(2), rel=1e-3)


@pytest.mark.parametrize("n", [1.33, 1.5, 2.4])
def test_dielectric_fresnel_at_normal_incidence(n):
    assert float(ref.fresnel_dielectric(np.array(1.0), n)) == pytest.approx(
        ((n - 1) / (n + 1)) ** 2
    )


def test_dielectric_fresnel_matches_s_and_p_equations():
    n, theta = 1.5, math.radians(45)
    ci = math.cos(theta)
    ct = math.sqrt(1 - (math.sin(theta) / n) ** 2)
    rs = (ci - n * ct) / (ci + n * ct)
    rp = (n * ci - ct) / (n * ci + ct)
    assert float(ref.fresnel_dielectric(np.array(ci), n)) == pytest.approx((rs**2 + rp**2) / 2)
    # Grazing incidence reflects everything; so does total internal reflection (n < 1).
    assert float(ref.fresnel_dielectric(np.array(0.0), n)) == pytest.approx(1.0)
    assert float(ref.fresnel_dielectric(np.array(0.3), 0.8)) == 1.0


def test_schlick_fresnel():
    f0 = np.array([0.04, 0.5, 0.9])
    c = np.array([1.0, 0.5, 0.0])
    F = ref.fresnel_schlick(f0, c)
    np.testing.assert_allclose(F[0], f0)
    np.testing.assert_allclose(F[1], f0 + (1 - f0) / 32)
    np.testing.assert_allclose(F[2], 1.0)


# --- reciprocity ---------------------------------------------------------------------


@pytest.mark.parametrize("model, params", RECIPROCAL, ids=lambda x: str(x))
def test_reciprocity(model, params, pairs):
    L, V = pairs
    forward = ref.brdf(model, params, L, V)
    assert np.all(forward > 0)
    np.testing.assert_allclose(forward, ref.brdf(model, params, V, L), rtol=1e-10)


def test_phong_illumination_is_not_reciprocal(pairs):
    L, V = pairs
    params = {"ke": 5.0}
    forward = ref.brdf("phong_illumination", params, L, V)
    backward = ref.brdf("phong_illumination", params, V, L)
    assert np.max(np.abs(forward - backward) / backward) > 0.5


# --- directional albedo --------------------------------------------------------------


@pytest.mark.parametrize("theta_i", [0.0, 30.0, 60.0, 85.0])
def test_lambert_albedo_is_albedo(theta_i):
    rho = ref.directional_albedo("lambert", {"albedo": (0.2, 0.5, 0.9)}, theta_i)
    np.testing.assert_allclose(rho, [0.2, 0.5, 0.9], rtol=1e-7)


def test_lommel_seeliger_albedo_closed_form():
    # int A / (4 pi (mu0 + mu)) mu d omega = A/2 (1 - mu0 ln(1 + 1/mu0)).
    mu0 = math.cos(math.radians(50))
    expected = 0.8 / 2 * (1 - mu0 * math.log(1 + 1 / mu0))
    rho = ref.directional_albedo("lommel_seeliger", {}, 50.0)
    np.testing.assert_allclose(rho, expected, rtol=1e-6)


def test_sharp_phong_albedo_at_normal_incidence():
    # The lobe cos^ke about N integrates (with the cosine) to 2 pi / (ke + 2).
    params = {"kd": (0.3,) * 3, "ks": (0.5,) * 3, "ke": 1000.0}
    rho = ref.directional_albedo("phong", params, 0.0)
    np.testing.assert_allclose(rho, 0.3 + 0.5 * 2 * PI / 1002, rtol=1e-5)


def test_sharp_ggx_albedo_at_normal_incidence():
    # L = N: V is at 2 theta_h, d omega_o = 4 cos(theta_h) d omega_h, F = 1 (f0 = 1),
    # so the albedo is int D(h) G2(2h) cos(h) d omega_h over theta_h < 45 deg.
    alpha = 0.01
    params = {"kd": (0,) * 3, "ks": (1,) * 3, "alpha": alpha, "f0": (1,) * 3}

    def integrand(h: float) -> float:
        d = alpha**2 / (PI * (math.cos(h) ** 2 * (alpha**2 - 1) + 1) ** 2)
        lam = 0.5 * (-1 + math.sqrt(1 + (alpha * math.tan(2 * h)) ** 2))
        return 2 * PI * d / (1 + lam) * math.cos(h) * math.sin(h)

    edges = [0, alpha, 10 * alpha, 100 * alpha, PI / 4]
    expected = sum(
        integrate.quad(integrand, a, b, epsabs=0, epsrel=1e-11, limit=200)[0]
        for a, b in zip(edges[:-1], edges[1:], strict=True)
    )
    assert 0.99 < expected < 1.0
    np.testing.assert_allclose(ref.directional_albedo("ggx", params, 0.0), expected, rtol=1e-5)


PLAUSIBLE = [
    ("phong", {"ke": 20.0}),
    ("blinn_phong", {"ke": 20.0}),
    ("ward", {"alpha_x": 0.1, "alpha_y": 0.4}),
    ("cook_torrance", {"m": 0.4, "fresnel": "dielectric"}),
    ("ggx", {"alpha": 0.5}),
    ("oren_nayar", {"sigma": 0.8}),
]


@pytest.mark.parametrize("model, params", PLAUSIBLE, ids=lambda x: str(x))
def test_albedo_between_zero_and_one(model, params):
    # Not a law for heuristic models in general, but these settings must stay below 1.
    for theta_i in (0.0, 45.0, 80.0):
        rho = ref.directional_albedo(model, params, theta_i)
        assert np.all(rho > 0) and np.all(rho < 1.0), (theta_i, rho)

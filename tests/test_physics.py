"""The GLSL models against the numpy reference, and the physics the lecture states."""

from __future__ import annotations

import numpy as np
import pytest

from lab import reference
from lab.models import load_model, model_names
from lab.render import direction

FINITE_MODELS = [n for n in model_names() if not load_model(n).delta]


def claiming(prop: str) -> list[str]:
    """The finite library models whose header claims `@property prop`."""
    return [n for n in FINITE_MODELS if prop in load_model(n).properties]


PHYSICAL = claiming("energy-conserving")
ISOTROPIC = claiming("isotropic")
RECIPROCAL = claiming("reciprocal")


# float32 limits how sharp a lobe can be evaluated to 1e-4: an error of 6e-8 in a cosine
# becomes ke * 6e-8 in cos^ke. The strict comparison stays where that is below 3e-5; the
# sharpest settings are compared separately at 1e-3.
MODERATE = {
    "ke": (1.0, 300.0),
    "m": (0.08, 1.0),
    "alpha": (0.05, 1.0),
    "alpha_x": (0.05, 1.0),
    "alpha_y": (0.05, 1.0),
}


def random_values(model, rng, limits: dict | None = None) -> dict:
    """A random parameter set inside the header's ranges (log-uniform for log sliders)."""
    values = {}
    for p in model.params.values():
        low, high = (limits or {}).get(p.name, (p.minimum, p.maximum))
        if p.kind == "color":
            values[p.name] = tuple(rng.uniform(0.0, 1.0, 3))
        elif p.kind == "float" and p.scale == "log":
            values[p.name] = float(np.exp(rng.uniform(np.log(low), np.log(high))))
        elif p.kind == "float":
            values[p.name] = float(rng.uniform(p.minimum, p.maximum))
        elif p.kind == "enum":
            values[p.name] = str(rng.choice(p.choices))
        else:
            values[p.name] = bool(rng.integers(2))
    return values


def random_pairs(rng, n: int, max_theta: float = 85.0) -> np.ndarray:
    """(n, 4) angles in degrees, uniform in solid angle up to max_theta.

    The angles are exactly representable as float32 radians (what the GPU receives), so the
    comparison measures the shader, not the rounding of its input.
    """
    cos_max = np.cos(np.radians(max_theta))
    theta = np.degrees(np.arccos(rng.uniform(cos_max, 1.0, (n, 2))))
    phi = rng.uniform(0.0, 360.0, (n, 2))
    angles = np.column_stack([theta[:, 0], phi[:, 0], theta[:, 1], phi[:, 1]])
    return np.degrees(np.radians(angles).astype(np.float32).astype(np.float64))


@pytest.mark.parametrize("sharp", [False, True], ids=["moderate", "sharp"])
@pytest.mark.parametrize("name", FINITE_MODELS)
def test_gpu_matches_numpy_reference(renderer, name, sharp):
    """GLSL f_r = numpy f_r to 1e-4 relative (1e-3 for the sharpest lobes), random pairs/params."""
    rng = np.random.default_rng(sum(map(ord, name)) + sharp)
    model = load_model(name)
    for trial in range(6):
        limits = None if sharp else MODERATE
        values = model.resolve(random_values(model, rng, limits)) if trial else model.defaults()
        angles = random_pairs(rng, 2000)
        gpu = renderer.eval_angles(model, values, angles).astype(np.float64)
        cpu = reference.brdf_angles(name, values, angles)
        assert np.isfinite(gpu).all() and (gpu >= 0).all()
        scale = np.abs(cpu).max()
        rows = ~np.isclose(gpu, cpu, rtol=1e-3 if sharp else 1e-4, atol=1e-6 * scale).all(axis=1)
        assert not rows.any(), (
            f"{name} {values}: {rows.sum()} rows differ, e.g. angles "
            f"{angles[rows][0]} gpu {gpu[rows][0]} cpu {cpu[rows][0]}"
        )


@pytest.mark.parametrize("name", model_names())
def test_zero_below_the_horizon(renderer, name):
    L = direction([30.0, 100.0, 120.0], [0.0, 0.0, 90.0])
    V = direction([100.0, 30.0, 45.0], [180.0, 180.0, 0.0])
    assert (renderer.probe(name, None, L, V) == 0).all()


@pytest.mark.parametrize("name", FINITE_MODELS)
def test_helmholtz_reciprocity(renderer, name):
    """Swapping L and V leaves f_r unchanged exactly for the models claiming `reciprocal`."""
    rng = np.random.default_rng(7)
    model = load_model(name)
    values = model.resolve(random_values(model, rng))
    angles = random_pairs(rng, 1000)
    L, V = direction(angles[:, 0], angles[:, 1]), direction(angles[:, 2], angles[:, 3])
    same = np.allclose(
        renderer.probe(model, values, L, V),
        renderer.probe(model, values, V, L),
        rtol=2e-4,
        atol=1e-6,
    )
    assert same == (name in RECIPROCAL), f"{name}: header and behaviour disagree on reciprocity"


def test_phong_illumination_model_is_not_reciprocal(renderer):
    """The slide's form equals a BRDF divided by cos(theta_i): swapping L and V changes it."""
    L, V = direction([20.0], [0.0]), direction([70.0], [180.0])
    values = {"kd": (0.0,) * 3, "ks": (1.0,) * 3, "ke": 2.0}
    forward = renderer.probe("phong_illumination", values, L, V)[0, 0]
    backward = renderer.probe("phong_illumination", values, V, L)[0, 0]
    # (R.V)^ke is symmetric, so the ratio is exactly cos(70)/cos(20).
    assert forward / backward == pytest.approx(
        np.cos(np.radians(70)) / np.cos(np.radians(20)), rel=1e-4
    )
    phong = renderer.probe("phong", values, L, V)[0, 0]
    assert forward == pytest.approx(phong / np.cos(np.radians(20)), rel=1e-4)


@pytest.mark.parametrize("name", FINITE_MODELS)
def test_isotropy(renderer, name):
    """Rotating both directions about N leaves f_r unchanged for the models claiming
    `isotropic`; anisotropic Ward changes."""
    rng = np.random.default_rng(3)
    angles = random_pairs(rng, 500, 80.0)
    rotated = angles + np.array([0.0, 37.0, 0.0, 37.0])
    values = {"alpha_x": 0.08, "alpha_y": 0.4} if name == "ward" else None
    a = renderer.eval_angles(name, values, angles)
    b = renderer.eval_angles(name, values, rotated)
    same = np.allclose(a, b, rtol=2e-4, atol=1e-6)
    assert same == (name in ISOTROPIC), f"{name}: header and behaviour disagree on isotropy"
    if name == "ward":  # alpha_x = alpha_y makes Ward isotropic again
        iso = {"alpha_x": 0.2, "alpha_y": 0.2}
        np.testing.assert_allclose(
            renderer.eval_angles(name, iso, angles),
            renderer.eval_angles(name, iso, rotated),
            rtol=2e-4,
            atol=1e-6,
        )


THETAS = np.arange(0.0, 90.0, 1.0)


def extreme_values(model):
    """Corners of the parameter space that stress energy: full albedos, smooth and rough."""
    sets = []
    floats = [p for p in model.params.values() if p.kind == "float"]
    for pick in ("minimum", "maximum"):
        values = {p.name: (1.0, 1.0, 1.0) for p in model.params.values() if p.kind == "color"}
        values.update({p.name: getattr(p, pick) for p in floats})
        sets.append(values)
    return sets


@pytest.mark.parametrize("name", PHYSICAL)
def test_energy_conservation(renderer, name):
    """Directional albedo <= 1 for the physically based models at stressing settings."""
    model = load_model(name)
    for values in extreme_values(model):
        if name in ("ward", "cook_torrance", "ggx"):  # diffuse + specular must share the energy
            values["kd"] = (0.0,) * 3
        if name == "cook_torrance":
            values["f0"] = (1.0,) * 3
        a = renderer.albedo(model, values, THETAS[:86])
        assert a.max() <= 1.0 + 0.01, (name, values, a.max(), THETAS[a.max(axis=1).argmax()])


def test_property_lists_match_the_lecture():
    """The headers' claims, read back: the lecture's physical models and its heuristics."""
    assert set(PHYSICAL) == {
        "lambert",
        "ward",
        "cook_torrance",
        "ggx",
        "oren_nayar",
        "lommel_seeliger",
    }
    assert set(FINITE_MODELS) - set(RECIPROCAL) == {"phong_illumination"}
    assert set(FINITE_MODELS) - set(ISOTROPIC) == {"ward"}


@pytest.mark.parametrize(
    "name", sorted(set(FINITE_MODELS) - set(PHYSICAL) - {"phong_illumination"})
)
def test_unnormalised_phong_gains_energy(renderer, name):
    """The lecture's point: ks (R.V)^ke, ks = 1, a low exponent reflects more than it gets."""
    a = renderer.albedo(name, {"kd": (0.5,) * 3, "ks": (1.0,) * 3, "ke": 1.0}, THETAS)
    assert a.max() > 1.2


@pytest.mark.parametrize(
    "name, values",
    [
        ("lambert", None),
        ("phong", {"ke": 1000.0}),
        ("ggx", {"alpha": 0.01, "kd": (0.0,) * 3}),
        ("cook_torrance", {"m": 0.05}),
        ("ward", {"alpha_x": 0.05, "alpha_y": 0.3}),
        ("oren_nayar", {"sigma": 1.0}),
        ("blinn_phong", {"ke": 300.0}),
        ("mirror", None),
    ],
)
def test_albedo_integration_is_accurate(renderer, name, values):
    """GPU albedo within 1% of the reference's independent quadrature, sharp lobes included."""
    thetas = np.array([0.0, 30.0, 60.0, 80.0])
    gpu = renderer.albedo(name, values, thetas)
    for theta, row in zip(thetas, gpu, strict=True):
        expected = reference.directional_albedo(name, load_model(name).resolve(values), theta)
        np.testing.assert_allclose(row, expected, rtol=0.01, atol=1e-4, err_msg=f"theta_i={theta}")

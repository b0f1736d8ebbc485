"""The microfacet terms on their own: D against θh, G against θo in the plane of incidence,
F against θd, from the model's own GLSL (shaders/views/terms.glsl).

A model shows here when it defines `void MICROFACET_TERMS(vec3 L, vec3 V, vec3 N, vec3 X,
vec3 Y, out float D, out float G, out vec3 F)` (shaders/README.md); the library's
cook_torrance and ggx do.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

import numpy as np

from lab.geometry import direction, plane_of_incidence
from lab.models import Model, ModelError
from lab.sources import as_model
from lab.views import PlotJob, ViewSpec

TERMS_FUNCTION = re.compile(r"\bvoid\s+MICROFACET_TERMS\s*\(")
ANGLES = np.arange(0.0, 90.5, 1.0)  # theta_h for D, theta_d for F (degrees)


def has_terms(model: Model) -> bool:
    """Whether the model's GLSL defines its microfacet terms for this view."""
    return bool(TERMS_FUNCTION.search(model.code))


def no_terms_message(model: Model) -> str:
    return (
        f"{model.name} is not written as a microfacet model: define MICROFACET_TERMS (see "
        "shaders/README.md) to plot its D, G and F on their own"
    )


@dataclass
class Terms:
    """D (1/sr) against θh, G against θo (-90..90, light 1's plane of incidence), F (RGB)
    against θd; the light is (theta_i, phi_i)."""

    theta: np.ndarray
    D: np.ndarray
    theta_o: np.ndarray
    G: np.ndarray
    F: np.ndarray
    theta_i: float


def term_pairs(theta_i: float, phi_i: float) -> tuple[np.ndarray, np.ndarray]:
    """L and V of the three families, concatenated: L = V at θh (so H is there); L = light
    and V in its plane of incidence; L and V mirrored about N at θd (so V.H = cos θd)."""
    n = len(ANGLES)
    d_dirs = direction(ANGLES, np.full(n, phi_i))
    theta_o, V = plane_of_incidence(theta_i, phi_i)
    L_light = np.repeat(direction(theta_i, phi_i)[None], len(V), axis=0)
    f_L = direction(ANGLES, np.full(n, phi_i))
    f_V = direction(ANGLES, np.full(n, phi_i + 180.0))
    return np.concatenate([d_dirs, L_light, f_L]), np.concatenate([d_dirs, V, f_V])


def microfacet_terms(renderer, model: Model, values, theta_i: float, phi_i: float = 0.0) -> Terms:
    """The terms of `model` on the GPU; ModelError for a model that does not define them."""
    import moderngl

    model = as_model(model)
    if not has_terms(model):
        # A kind of model with its own advice (a measured table) names its own file.
        reason = getattr(model, "no_terms_reason", "")
        raise ModelError(reason or no_terms_message(model), None if reason else model.path)
    L, V = term_pairs(theta_i, phi_i)
    n = len(L)
    textures = []
    try:
        for unit, data in enumerate((L, V)):
            texels = np.zeros((n, 4), np.float32)
            texels[:, :3] = data
            texture = renderer.ctx.texture((n, 1), 4, texels.tobytes(), dtype="f4")
            texture.filter = (moderngl.NEAREST, moderngl.NEAREST)
            texture.use(unit)
            textures.append(texture)
        parts = []
        for part in (0, 1):
            uniforms = {"u_L": 0, "u_V": 1, "u_part": part}
            fbo = renderer._run(model, "terms", values, (n, 1), uniforms)
            parts.append(renderer._read(fbo).reshape(n, 4).astype(np.float64))
    finally:
        for texture in textures:
            texture.release()
    k, m = len(ANGLES), len(ANGLES) + 181
    return Terms(
        ANGLES.copy(),
        parts[0][:k, 0],
        np.arange(-90.0, 90.5, 1.0),
        parts[0][k:m, 1],
        parts[1][m:, :3],
        theta_i,
    )


def save_terms(renderer, model: Model, values, theta_i: float, phi_i: float, out, width=900):
    """`brdf-lab render --view terms`: the three plots side by side."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    t = microfacet_terms(renderer, model, values, theta_i, phi_i)
    dpi = 100
    fig, axes = plt.subplots(1, 3, figsize=(width / dpi, width / dpi * 0.36), dpi=dpi)
    ax_d, ax_g, ax_f = axes
    finite = np.isfinite(t.D) & (t.D > 0)
    ax_d.semilogy(t.theta[finite], t.D[finite], color="C0")
    ax_d.set(title="D (1/sr)", xlabel="θh: N to H (°)", xlim=(0, 90))
    ax_g.plot(t.theta_o, t.G, color="C2")
    ax_g.axvline(theta_i, color="0.6", ls="--", lw=1)
    ax_g.set(
        title=f"G, light at θi = {theta_i:g}°",
        xlabel="θo (°), R dashed",
        xlim=(-90, 90),
        ylim=(0, 1.05),
    )
    for c, name in enumerate("rgb"):
        ax_f.plot(
            t.theta, t.F[:, c], color=name, lw=1.5, ls=("-", "--", ":")[c], label=name.upper()
        )
    ax_f.set(title="F", xlabel="θd: V to H (°)", xlim=(0, 90), ylim=(0, 1.05))
    ax_f.legend(loc="upper left", fontsize=8)
    for ax in axes:
        ax.grid(alpha=0.3)
    fig.suptitle(f"{model.name}: microfacet terms on their own", fontsize=11)
    fig.tight_layout()
    fig.savefig(out, dpi=dpi)
    plt.close(fig)


def plot(job: PlotJob) -> None:
    save_terms(job.renderer, job.model, job.values, job.theta_i, job.phi_i, job.out)


VIEW = ViewSpec(
    name="terms",
    title="Microfacet terms D, G, F",
    dock=("right", 1),
    tab_of="sh",  # behind the spherical harmonics: the default layout keeps its sizes
    widget="lab.app.views.terms:TermsView",
    plot=plot,
    order=45,
)

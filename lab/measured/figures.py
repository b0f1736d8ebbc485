"""Figures of the measured-BRDF tools (matplotlib, written as PNG)."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from lab import constants
from lab.measured import merl, sh
from lab.measured.fit import FitResult, cpu_evaluate, evaluate_lobes
from lab.measured.model import measured_model

LUMA = np.array(constants.LUMA)


def _pyplot():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def _tone(image: np.ndarray, peak: float) -> np.ndarray:
    """Radiance -> displayable sRGB-ish floats, scaled so that `peak` is white."""
    x = np.clip(image[..., :3] / max(peak, 1e-12), 0.0, 1.0)
    return np.where(x <= 0.0031308, 12.92 * x, 1.055 * x ** (1 / 2.4) - 0.055)


def plane_lobe(f, theta_i: float) -> tuple[np.ndarray, np.ndarray]:
    """theta_o (deg, -89..89; positive = mirror side) and luminance of f_r there."""
    theta_o = np.arange(-89.0, 90.0, 1.0)
    t = np.radians(np.abs(theta_o))
    sign = np.where(theta_o >= 0, -1.0, 1.0)  # the mirror side has azimuth pi
    V = np.stack([sign * np.sin(t), np.zeros_like(t), np.cos(t)], -1)
    ti = math.radians(theta_i)
    L = np.repeat([[math.sin(ti), 0.0, math.cos(ti)]], len(V), axis=0)
    return theta_o, np.asarray(f(L, V)) @ LUMA


def fit_figure(
    table: merl.MerlTable,
    result: FitResult,
    out: str | Path,
    renderer=None,
    thetas=(20.0, 45.0, 70.0),
) -> Path:
    """Measured vs fitted: lobes in the plane of incidence and lit spheres."""
    from lab.render import Renderer

    plt = _pyplot()
    renderer = renderer or Renderer()
    fig = plt.figure(figsize=(11, 7), dpi=100)
    for k, theta_i in enumerate(thetas):
        ax = fig.add_subplot(2, len(thetas), k + 1, projection="polar")
        t, measured = plane_lobe(lambda L, V: merl.lookup(table, L, V, "linear"), theta_i)
        _, fitted = plane_lobe(
            lambda L, V: evaluate_lobes(cpu_evaluate, result.model, result.lobes, L, V), theta_i
        )
        ax.plot(np.radians(t), measured, label="measured", color="black")
        ax.plot(np.radians(t), fitted, "--", label=f"{result.model} fit", color="tab:red")
        ax.set_theta_zero_location("N")
        ax.set_theta_direction(-1)
        ax.set_thetamin(-90)
        ax.set_thetamax(90)
        ax.set_yticklabels([])  # radial values crowd the half disc; the shapes matter
        ax.set_title(f"f_r (luminance), θi = {theta_i:g}°", fontsize=9)
        if k == 0:
            ax.legend(loc="lower left", fontsize=8)
    model = measured_model(table)
    spheres = [renderer.sphere(model, {}, (45.0, 0.0), size=256)]
    fitted = sum(renderer.sphere(result.model, v, (45.0, 0.0), size=256) for v in result.lobes)
    spheres.append(fitted)
    peak = float(np.percentile(spheres[0][..., :3], 99.5))
    n = len(thetas)
    for k, (image, title) in enumerate(zip(spheres, ("measured (table)", "fitted"), strict=True)):
        ax = fig.add_subplot(2, n, n + 1 + k)
        ax.imshow(_tone(image, peak))
        ax.set_title(f"{title}, light at 45°", fontsize=9)
        ax.axis("off")
    if n > 2:
        ax = fig.add_subplot(2, n, 2 * n)
        ax.axis("off")
        lines = []
        for k, values in enumerate(result.lobes, start=1):
            lines.append(f"lobe {k}")
            for name, value in values.items():
                shown = (
                    ", ".join(f"{c:.3g}" for c in value)
                    if isinstance(value, tuple)
                    else f"{value:.4g}"
                )
                lines.append(f"  {name} = {shown}")
        ax.text(0.0, 1.0, "\n".join(lines), va="top", family="monospace", fontsize=8)
    fig.suptitle(
        f"{result.model} ({len(result.lobes)} lobe(s)) fitted to "
        f"{table.path.name if table.path else 'table'}: error {result.error:.4g} "
        f"({result.metric})",
        fontsize=11,
    )
    fig.tight_layout()
    fig.savefig(out)
    plt.close(fig)
    return Path(out)


def sh_figure(lobe_fn, theta_i: float, orders, out: str | Path, title: str) -> tuple[Path, list]:
    """Lobe vs its SH reconstructions in the plane of incidence, and error vs order."""
    plt = _pyplot()
    grid = sh.hemisphere_grid()
    lobe = sh.cosine_lobe(lobe_fn, theta_i, grid)
    rows = sh.error_by_order(lobe, grid, orders)
    coefficients = sh.project(lobe, grid, max(orders))
    fig, (ax, ax2) = plt.subplots(1, 2, figsize=(11, 4.5), dpi=100)
    t, exact = plane_lobe(lobe_fn, theta_i)
    cos_o = np.cos(np.radians(t))
    ax.plot(t, exact * cos_o, color="black", lw=2, label="lobe f_r cos θo")
    theta = np.radians(np.abs(t))
    phi = np.where(t >= 0, math.pi, 0.0)
    for order in orders:
        n = sh.coefficient_count(order)
        approx = sh.reconstruct(coefficients[:n], theta, phi) @ LUMA
        ax.plot(t, approx, lw=1, label=f"order {order} ({n} coeff.)")
    ax.set_xlabel("θo in the plane of incidence (deg; + = mirror side)")
    ax.set_title(f"{title}, θi = {theta_i:g}°", fontsize=10)
    ax.legend(fontsize=7)
    ax2.semilogy([r[1] for r in rows], [max(r[2], 1e-16) for r in rows], "o-")
    ax2.set_xlabel("coefficients (order + 1)²")
    ax2.set_ylabel("relative L2 error over the hemisphere")
    ax2.set_title("reconstruction error vs coefficient count", fontsize=10)
    fig.tight_layout()
    fig.savefig(out)
    plt.close(fig)
    return Path(out), rows


def filter_figure(
    table: merl.MerlTable, out: str | Path, renderer=None, size: int = 384, light=(45.0, 0.0)
) -> Path:
    """The measured sphere with nearest and linear lookup side by side, plus a zoom."""
    from lab.render import Renderer

    plt = _pyplot()
    renderer = renderer or Renderer()
    model = measured_model(table)
    images = [
        renderer.sphere(model, {"interpolation": f}, light, size=size)
        for f in ("nearest", "linear")
    ]
    peak = float(np.percentile(images[1][..., :3], 99.5))
    fig, axes = plt.subplots(1, 2, figsize=(9, 4.6), dpi=100)
    for ax, image, name in zip(axes, images, ("nearest", "linear"), strict=True):
        ax.imshow(_tone(image, peak))
        ax.set_title(f"{name} lookup", fontsize=10)
        ax.axis("off")
    fig.tight_layout()
    fig.savefig(out)
    plt.close(fig)
    return Path(out)

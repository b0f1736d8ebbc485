"""PNG output: tone-mapped renders and labelled plots of the views (matplotlib)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from lab.constants import LUMA
from lab.models import Model


def to_srgb8(rgb: np.ndarray, exposure: float = 0.0, gamma: float | None = None) -> np.ndarray:
    """Linear radiance -> 8-bit: scale by 2^exposure, clamp, sRGB curve (or 1/gamma power)."""
    x = np.clip(np.nan_to_num(rgb, nan=0.0) * 2.0**exposure, 0.0, 1.0)
    if gamma:
        encoded = x ** (1.0 / gamma)
    else:
        encoded = np.where(x <= 0.0031308, 12.92 * x, 1.055 * np.power(x, 1 / 2.4) - 0.055)
    return (encoded * 255.0 + 0.5).astype(np.uint8)


def save_image(image: np.ndarray, path: str | Path, exposure: float = 0.0) -> None:
    """Save an RGBA float render (alpha 0 = background) as PNG."""
    from PIL import Image

    rgb = to_srgb8(image[..., :3], exposure)
    if image.shape[-1] == 4:
        alpha = (np.clip(image[..., 3], 0, 1) * 255 + 0.5).astype(np.uint8)
        Image.fromarray(np.dstack([rgb, alpha]), "RGBA").save(path)
    else:
        Image.fromarray(rgb, "RGB").save(path)


def luminance(rgb: np.ndarray) -> np.ndarray:
    return rgb @ np.array(LUMA, dtype=rgb.dtype)


def _figure(polar: bool = False, three_d: bool = False):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig = plt.figure(figsize=(6, 4.5), dpi=110)
    projection = "polar" if polar else ("3d" if three_d else None)
    return fig, fig.add_subplot(projection=projection)


def polar_axes(ax, polar_data, label: str, color=None, normalize: bool = False) -> None:
    """Draw one lobe (luminance of f_r) on a half-disc polar axes: 0 deg = the normal."""
    theta = np.radians(polar_data.theta_o)
    r = luminance(polar_data.values.astype(np.float64))
    if normalize and r.max() > 0:
        r = r / r.max()
    ax.plot(theta, r, label=label, color=color)
    if polar_data.spike is not None:
        height = float(luminance(np.asarray(polar_data.spike)))
        mirror = np.radians(polar_data.theta_i)
        ax.plot([mirror, mirror], [0, height], lw=3, color=color, label=f"{label} (delta spike)")


def style_polar(ax, theta_i: float, what: str) -> None:
    ax.set_theta_zero_location("N")
    ax.set_theta_direction(-1)
    ax.set_thetamin(-90)
    ax.set_thetamax(90)
    top = ax.get_ylim()[1]
    marks = [(0.0, "normal", ":"), (-theta_i, "incident", "--"), (theta_i, "mirror", "-.")]
    if theta_i < 8:  # the three directions (nearly) coincide: one label says so
        marks = [(0.0, "normal = incident = mirror" if theta_i == 0 else "normal", ":")]
    for angle, _, style in marks:
        ax.plot([np.radians(angle)] * 2, [0, top], style, color="grey", lw=1)
    for angle, name, _ in marks:
        # Inside the rim, so the labels never sit on the angle ticks outside it.
        ax.text(
            np.radians(angle),
            top * 0.9,
            name,
            ha="center",
            va="center",
            fontsize=11,
            color="dimgrey",
            bbox={"facecolor": "white", "edgecolor": "none", "pad": 1},
        )
    ax.set_ylim(0, top)
    ax.tick_params(labelsize=10)
    ax.set_title(f"{what} in the plane of incidence, θi = {theta_i:g}°", fontsize=12)
    ax.legend(loc="upper left", fontsize=11, bbox_to_anchor=(-0.05, 0.05), ncol=2, frameon=False)


def save_render(
    renderer,
    view: str,
    model: Model,
    values,
    theta: float,
    phi: float,
    out: str | Path,
    size: int = 512,
    exposure: float = 0.0,
    lights=None,
    ambient=(0.0, 0.0, 0.0),
) -> None:
    """Any view as a PNG: the sphere as an image (with `lights` and `ambient` when given),
    the others as labelled plots for the light (theta, phi)."""
    if view == "sphere":
        image = renderer.sphere(
            model, values, (theta, phi), size=size, lights=lights, ambient=ambient
        )
        save_image(image, out, exposure)
    else:
        save_view(renderer, view, model, values, theta, phi, out, size=size)


def save_view(
    renderer,
    view: str,
    model: Model,
    values,
    theta: float,
    phi: float,
    out: str | Path,
    size: int = 512,
) -> None:
    """Render a plot view (polar, lobe3d, slice, albedo) of one model to a readable PNG."""
    import matplotlib.pyplot as plt

    if view == "polar":
        fig, ax = _figure(polar=True)
        polar_axes(ax, renderer.polar(model, values, theta, phi), model.name)
        style_polar(ax, theta, "f_r (1/sr, luminance)")
    elif view == "lobe3d":
        from lab.views.lobe3d import save_lobe3d

        save_lobe3d(renderer, model, values, theta, phi, out, width=max(size, 320))
        return
    elif view == "slice":
        fig, ax = _figure()
        image = luminance(
            renderer.slice(model, values, phi_d=phi if phi else 90.0, size=min(size, 512)).astype(
                np.float64
            )
        )
        shown = ax.imshow(
            np.log10(np.maximum(image, 1e-4)), extent=(0, 90, 0, 90), cmap="magma", aspect="equal"
        )
        fig.colorbar(shown, label="log10 f_r")
        ax.set_xlabel("θh (degrees)")
        ax.set_ylabel("θd (degrees)")
        ax.set_title(f"{model.name}: image slice at φd = {phi if phi else 90.0:g}°", fontsize=10)
    elif view == "albedo":
        fig, ax = _figure()
        thetas = np.arange(0.0, 90.0, 1.0)
        a = renderer.albedo(model, values, thetas, phi)
        for channel, color in enumerate(("tab:red", "tab:green", "tab:blue")):
            ax.plot(thetas, a[:, channel], color=color, label="RGB"[channel])
        ax.axhline(1.0, color="black", lw=1, ls="--", label="albedo = 1")
        gain = a.max(axis=1) > 1.0
        if gain.any():
            ax.fill_between(
                thetas,
                1.0,
                a.max(axis=1),
                where=gain,
                color="red",
                alpha=0.2,
                label="energy gain (not physical)",
            )
        ax.set_xlabel("θi (degrees)")
        ax.set_ylabel("directional albedo")
        ax.set_ylim(0, max(1.1, float(a.max()) * 1.05))
        ax.legend(fontsize=8)
        ax.set_title(f"{model.name}: directional albedo", fontsize=10)
    else:
        raise ValueError(f"unknown view {view!r}")
    fig.tight_layout()
    # The figure is 6 inches wide: this dpi makes it `size` pixels (320 at least, to stay legible).
    fig.savefig(out, dpi=max(size, 320) / fig.get_size_inches()[0])
    plt.close(fig)

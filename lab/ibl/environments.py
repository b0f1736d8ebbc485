"""Environment maps for image-based lighting: the lab's own procedural ones and HDR files.

An environment is an equirectangular float32 image (H, W, 3) of radiance: row 0 is the
zenith (+y), row H-1 the nadir; column W/2 looks down -z (behind the sphere the camera
sees). Directions and pixels map as in shaders/views/ibl.glsl.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import moderngl
import numpy as np

from lab.constants import LUMA
from lab.gl import table_texture

PROCEDURAL = ("sky", "furnace", "studio", "grey_room")
FILE_TYPES = (".hdr", ".pic", ".exr")
DEFAULT_SIZE = (512, 256)  # width, height: 0.7 degree pixels
ENV_UNIT = 8  # texture units 8..11 hold the environment (models' own data binds lower units)


class EnvironmentError(ValueError):
    """An environment that cannot be made or read; the message says what to do."""


@dataclass
class Sampling:
    """The environment's sampling tables: density over (u, v) and the two CDFs."""

    density: np.ndarray  # (H, W) pdf over the unit square (u, v)
    marginal: np.ndarray  # (H + 1,) CDF over rows
    conditional: np.ndarray  # (H, W + 1) CDF over the columns of each row


def directions(width: int, height: int) -> np.ndarray:
    """Unit direction (H, W, 3) at each pixel centre (rotation 0)."""
    u = (np.arange(width) + 0.5) / width
    v = (np.arange(height) + 0.5) / height
    phi = (u - 0.5) * 2.0 * np.pi
    theta = v * np.pi
    st = np.sin(theta)[:, None]
    return np.stack(
        [
            st * np.sin(phi)[None, :],
            np.repeat(np.cos(theta)[:, None], width, axis=1),
            -st * np.cos(phi)[None, :],
        ],
        axis=-1,
    )


def _cap(d: np.ndarray, axis, radius_deg: float, soft_deg: float) -> np.ndarray:
    """1 inside a cap of `radius_deg` around `axis`, fading to 0 over `soft_deg` (smooth)."""
    axis = np.asarray(axis, dtype=np.float64)
    axis = axis / np.linalg.norm(axis)
    angle = np.degrees(np.arccos(np.clip(d @ axis, -1.0, 1.0)))
    t = np.clip((radius_deg + soft_deg - angle) / soft_deg, 0.0, 1.0)
    return t * t * (3.0 - 2.0 * t)


def _rect_light(d: np.ndarray, centre, half_width_deg: float, half_height_deg: float):
    """A rectangular area light facing the centre: its angular footprint around `centre`."""
    c = np.asarray(centre, dtype=np.float64)
    c = c / np.linalg.norm(c)
    right = np.cross([0.0, 1.0, 0.0], c)
    right /= np.linalg.norm(right)
    up = np.cross(c, right)
    along = d @ c
    x = np.degrees(np.arctan2(d @ right, along))
    y = np.degrees(np.arctan2(d @ up, along))
    return ((along > 0) & (np.abs(x) < half_width_deg) & (np.abs(y) < half_height_deg)).astype(
        np.float64
    )


def procedural(name: str, size: tuple[int, int] = DEFAULT_SIZE) -> np.ndarray:
    """One of PROCEDURAL as an (H, W, 3) float32 radiance image."""
    width, height = size
    d = directions(width, height)
    up = d[..., 1:2]
    if name == "furnace":
        return np.ones((height, width, 3), np.float32)
    if name == "sky":
        # Blue sky brightening toward the horizon, a sun 5-8 degrees wide about 40 degrees up
        # (about 40% of the light on a horizontal surface), a dim brown ground.
        zenith, horizon = np.array([0.18, 0.35, 0.8]), np.array([0.75, 0.85, 1.0])
        t = np.sqrt(np.clip(up, 0.0, 1.0))
        sky = horizon * (1 - t) + zenith * t
        ground = np.array([0.16, 0.13, 0.1]) * np.ones_like(up)
        image = np.where(up >= 0.0, sky, ground)
        sun = _cap(d, (0.45, 0.64, -0.62), 2.5, 1.5)[..., None]
        image = image + np.array([120.0, 110.0, 90.0]) * sun
        return image.astype(np.float32)
    if name == "studio":
        # Dark grey walls and two softbox area lights: a warm key, a cool fill.
        image = 0.03 + 0.02 * np.clip(up, 0.0, 1.0) * np.ones((1, 1, 3))
        key = _rect_light(d, (-0.7, 0.5, 0.5), 18.0, 12.0)[..., None]
        fill = _rect_light(d, (0.8, 0.2, 0.3), 10.0, 20.0)[..., None]
        image = image + np.array([5.0, 4.6, 4.0]) * key + np.array([1.2, 1.45, 1.8]) * fill
        return image.astype(np.float32)
    if name == "grey_room":
        # A closed grey room: ceiling 0.8, walls 0.5 with darker skirting, floor 0.3.
        ceiling = np.clip(up * 4.0, 0.0, 1.0)
        floor = np.clip(-up * 4.0, 0.0, 1.0)
        wall = 1.0 - ceiling - floor
        grey = 0.8 * ceiling + 0.5 * wall + 0.3 * floor
        return np.repeat(grey, 3, axis=-1).astype(np.float32)
    raise EnvironmentError(
        f"unknown environment {name!r}: use one of {', '.join(PROCEDURAL)} or an .hdr/.exr file"
    )


def read_file(path: str | Path) -> np.ndarray:
    """An equirectangular .hdr (Radiance RGBE) or .exr (OpenEXR) file as (H, W, 3) float32."""
    path = Path(path)
    if not path.is_file():
        raise EnvironmentError(f"{path}: no such file")
    suffix = path.suffix.lower()
    if suffix not in FILE_TYPES:
        raise EnvironmentError(
            f"{path}: unknown environment file type {suffix!r}: give a Radiance .hdr or OpenEXR "
            "equirectangular image, or one of " + ", ".join(PROCEDURAL)
        )
    try:
        if suffix == ".exr":
            image = _read_exr(path)
        else:
            import imagecodecs

            image = np.asarray(imagecodecs.rgbe_decode(path.read_bytes()), dtype=np.float32)
    except EnvironmentError:
        raise
    except Exception as err:  # the readers raise their own kinds; say which file and why
        raise EnvironmentError(f"{path}: cannot read it as {suffix[1:]} ({err})") from None
    if image.ndim == 2:
        image = np.repeat(image[..., None], 3, axis=-1)
    image = image[..., :3]
    if image.ndim != 3 or image.shape[-1] != 3 or min(image.shape[:2]) < 2:
        raise EnvironmentError(f"{path}: expected a colour image, got shape {image.shape}")
    height, width = image.shape[:2]
    if abs(width - 2 * height) > 1:
        raise EnvironmentError(
            f"{path}: {width}x{height} is not equirectangular (width must be twice the height)"
        )
    if not np.all(np.isfinite(image)):
        raise EnvironmentError(f"{path}: contains NaN or infinite pixels")
    return np.ascontiguousarray(np.maximum(image, 0.0), dtype=np.float32)


def _read_exr(path: Path) -> np.ndarray:
    import OpenEXR

    with OpenEXR.File(str(path)) as exr:
        channels = exr.channels()
        if "RGB" in channels:
            return np.asarray(channels["RGB"].pixels, dtype=np.float32)
        if "RGBA" in channels:
            return np.asarray(channels["RGBA"].pixels, dtype=np.float32)[..., :3]
        if all(c in channels for c in "RGB"):
            return np.stack([np.asarray(channels[c].pixels) for c in "RGB"], -1).astype("f4")
        if "Y" in channels:
            return np.asarray(channels["Y"].pixels, dtype=np.float32)
        raise EnvironmentError(f"{path}: no R, G, B or Y channels (has {sorted(channels)})")


def write_hdr(path: str | Path, image: np.ndarray) -> None:
    """Save (H, W, 3) radiance as a Radiance .hdr file."""
    import imagecodecs

    Path(path).write_bytes(imagecodecs.rgbe_encode(np.ascontiguousarray(image, np.float32)))


def load(source: str | Path, size: tuple[int, int] = DEFAULT_SIZE) -> np.ndarray:
    """A procedural environment by name, or an HDR file by path."""
    text = str(source)
    if text in PROCEDURAL:
        return procedural(text, size)
    if Path(text).suffix.lower() not in FILE_TYPES and not Path(text).is_file():
        raise EnvironmentError(
            f"unknown environment {text!r}: use one of {', '.join(PROCEDURAL)} or an .hdr/.exr file"
        )
    return read_file(text)


def sampling_tables(image: np.ndarray) -> Sampling:
    """Importance sampling by luminance times sin(theta): a CDF over rows, one per row.

    Each pixel is chosen with probability w_ij / sum(w), then a point uniform inside it;
    the density over (u, v) is w_ij / sum(w) * W * H (Pharr et al., PBR 4th ed., 2.4.7).
    """
    height, width = image.shape[:2]
    theta = (np.arange(height) + 0.5) / height * np.pi
    weight = np.maximum(image.astype(np.float64) @ np.array(LUMA), 0.0) * np.sin(theta)[:, None]
    if weight.sum() <= 0.0:  # a black map: sample uniformly in (u, v) rather than divide by 0
        weight = np.ones_like(weight) * np.sin(theta)[:, None]
    # A floor keeps every pixel reachable, so env sampling alone stays unbiased.
    weight = weight + 1e-4 * weight.mean() * np.sin(theta)[:, None]
    rows = weight.sum(axis=1)
    total = rows.sum()
    marginal = np.concatenate([[0.0], np.cumsum(rows) / total])
    conditional = np.concatenate([np.zeros((height, 1)), np.cumsum(weight, axis=1)], axis=1)
    conditional /= np.maximum(conditional[:, -1:], 1e-300)
    marginal[-1] = 1.0
    conditional[:, -1] = 1.0
    density = weight / total * width * height
    return Sampling(
        density.astype(np.float32), marginal.astype(np.float32), conditional.astype(np.float32)
    )


def contrast(image: np.ndarray) -> float:
    """1 - E[L]^2 / E[L^2] of the map's luminance over the sphere (solid-angle weights):
    0 for a constant map (the furnace), near 1 where small bright sources hold the light
    (the sky's sun). The "auto" strategy samples the map only where it is above 0."""
    lum = image @ np.array(LUMA, np.float32)
    weight = np.sin((np.arange(lum.shape[0]) + 0.5) / lum.shape[0] * np.pi)[:, None]
    mean = float((lum * weight).sum() / (weight.sum() * lum.shape[1]))
    square = float((lum * lum * weight).sum() / (weight.sum() * lum.shape[1]))
    return max(0.0, 1.0 - mean * mean / square) if square > 0.0 else 0.0


@dataclass
class Environment:
    """An environment image with its sampling tables and GL textures (made on first use)."""

    image: np.ndarray
    name: str = "environment"
    tables: Sampling = field(init=False)
    contrast: float = field(init=False)  # contrast(image)
    _textures: list = field(default_factory=list, init=False, repr=False)

    def __post_init__(self):
        self.image = np.ascontiguousarray(self.image, dtype=np.float32)
        self.tables = sampling_tables(self.image)
        self.contrast = contrast(self.image)

    @classmethod
    def load(cls, source, size=DEFAULT_SIZE) -> Environment:
        return cls(load(source, size), str(source))

    @property
    def size(self) -> tuple[int, int]:
        return self.image.shape[1], self.image.shape[0]

    def bind(self, ctx: moderngl.Context) -> dict:
        if not self._textures:
            t = self.tables  # image, density w x h; marginal (h + 1) x 1; conditional (w + 1) x h
            tables = [self.image, t.density, t.marginal.reshape(1, -1), t.conditional]
            self._textures = [table_texture(ctx, array) for array in tables]
        for unit, texture in enumerate(self._textures):
            texture.use(ENV_UNIT + unit)
        return {
            "u_env": ENV_UNIT,
            "u_density": ENV_UNIT + 1,
            "u_marginal": ENV_UNIT + 2,
            "u_conditional": ENV_UNIT + 3,
            "u_env_size": (float(self.size[0]), float(self.size[1])),
        }

    def release(self) -> None:
        for texture in self._textures:
            texture.release()
        self._textures.clear()

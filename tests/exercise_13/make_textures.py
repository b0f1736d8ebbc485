"""Writes exercise 13's committed textures (exercises/13_svbrdf/textures/*.png): painted tiles
with brushed-metal bands, the roughness varying along the bands. Hidden mode generates others.

    python tests/exercise_13/make_textures.py
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
from PIL import Image

OUT = Path(__file__).resolve().parents[2] / "exercises" / "13_svbrdf" / "textures"
WIDTH, HEIGHT = 128, 64  # u across (around the torus' big circle), v down


def smooth(t: np.ndarray) -> np.ndarray:
    t = np.clip(t, 0.0, 1.0)
    return t * t * (3.0 - 2.0 * t)


def main() -> None:
    v, u = np.meshgrid(
        (np.arange(HEIGHT) + 0.5) / HEIGHT, (np.arange(WIDTH) + 0.5) / WIDTH, indexing="ij"
    )
    # Paint: a checker of brick red and cream; the metal bands take the albedo as their
    # specular colour (a gold and a steel band alternate).
    tile = (np.floor(u * 16) + np.floor(v * 6)) % 2
    paint = np.where(tile[..., None] > 0, [0.85, 0.8, 0.65], [0.7, 0.2, 0.08])
    band = np.floor(u * 4) % 2
    metal = np.where(band[..., None] > 0, [0.95, 0.7, 0.3], [0.75, 0.78, 0.8])
    # Metal where a wavy band crosses v: soft edges a few texels wide.
    wave = 0.5 + 0.5 * np.sin(2 * np.pi * (u * 4 + 0.15 * np.sin(2 * np.pi * v)))
    mask = smooth((wave - 0.35) / 0.12)
    albedo = paint + (metal - paint) * mask[..., None]
    roughness = 0.08 + 0.32 * smooth(0.5 + 0.5 * np.cos(2 * np.pi * (2 * v + u)))
    OUT.mkdir(parents=True, exist_ok=True)
    for name, data in (("albedo", albedo), ("roughness", roughness), ("mask", mask)):
        image = np.clip(np.round(np.asarray(data) * 255), 0, 255).astype(np.uint8)
        Image.fromarray(image, "RGB" if image.ndim == 3 else "L").save(OUT / f"{name}.png")


if __name__ == "__main__":
    main()

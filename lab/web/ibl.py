"""The IBL demo page's data: an environment and its sampling tables, made by lab.ibl (the
page never computes them itself), written as one float32 file and a JSON header."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from lab.ibl.integrator import Environment

DEMO_ENVIRONMENTS = ("sky", "studio")
DEMO_SIZE = (256, 128)  # width, height: 1.4 degree pixels, 0.5 MB for the page per map


def write_environments(outdir: Path) -> list[Path]:
    """ibl/<name>.bin (image RGB, density, marginal CDF, conditional CDFs, float32, in that
    order, rows from the zenith) and ibl/<name>.json (their sizes) for each demo map."""
    folder = outdir / "ibl"
    folder.mkdir(parents=True, exist_ok=True)
    written = []
    for name in DEMO_ENVIRONMENTS:
        env = Environment.load(name, DEMO_SIZE)
        t = env.tables
        parts = [env.image, t.density, t.marginal, t.conditional]
        data = np.concatenate([np.asarray(p, np.float32).ravel() for p in parts])
        (folder / f"{name}.bin").write_bytes(data.astype("<f4").tobytes())
        width, height = env.size
        header = {
            "name": name,
            "width": width,
            "height": height,
            "lengths": [int(np.asarray(p).size) for p in parts],
        }
        (folder / f"{name}.json").write_text(json.dumps(header) + "\n", encoding="utf-8")
        written += [folder / f"{name}.bin", folder / f"{name}.json"]
    return written

"""The spatially varying BRDF in four steps, as the object view draws them, for the deck:
geometry only, one BRDF, a diffuse texture only, textures driving the BRDF's parameters."""

from __future__ import annotations

from pathlib import Path

from lab.app.renderer import MODES, AppRenderer
from lab.diagrams import record_text
from lab.models import load_model
from lab.plots import save_image
from lab.render import Light

NAMES = ("geometry", "single", "diffuse", "textured")  # svbrdf_<name>.png, in MODES' order
VALUES = {"kd": (0.6, 0.6, 0.6), "m": 0.3, "f0": (0.04, 0.04, 0.04)}  # preset 08's
LIGHTS = [
    Light(35.0, 0.0),
    Light(60.0, 150.0, (0.3, 0.3, 0.35)),
    Light(50.0, 250.0, (0.2, 0.2, 0.2)),
]


def render_steps(outdir: str | Path, renderer: AppRenderer | None = None) -> list[Path]:
    """One PNG per step (svbrdf_geometry.png, ...), the torus with Cook-Torrance."""
    outdir = Path(outdir)
    outdir.mkdir(parents=True, exist_ok=True)
    renderer = renderer or AppRenderer()
    model = load_model("cook_torrance")
    paths = []
    for mode, name in enumerate(NAMES[: len(MODES)]):
        image = renderer.object(model, VALUES, LIGHTS, (0.03,) * 3, shape=0, mode=mode, size=320)
        path = outdir / f"svbrdf_{name}.png"
        save_image(image, path)
        record_text(path, [])  # a picture: no text for the slides' test to measure
        paths.append(path)
    return paths

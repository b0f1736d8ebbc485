"""A lit object with several lights and ambient light, and the spatially varying BRDF
steps (geometry only, single BRDF, diffuse texture only, textures driving the BRDF)."""

from __future__ import annotations

from lab.views import Setting, ViewSpec

SHAPES = ("torus", "sphere", "rounded box", "bumpy sphere")
MODES = ("geometry only", "single BRDF", "diffuse texture only", "textures drive the BRDF")

VIEW = ViewSpec(
    name="object",
    title="Lit object / spatially varying",
    settings={
        "shape": Setting(
            0, 0, len(SHAPES) - 1, "shape", choices=SHAPES, doc="the lit object's shape"
        ),
        "mode": Setting(
            1,
            0,
            len(MODES) - 1,
            "mode",
            choices=MODES,
            doc="the lecture's steps to spatially varying BRDFs",
        ),
        "lights": Setting(3, 1, 4, "lights"),
        "ambient": Setting(0.03, 0.0, 0.3, "ambient", 0.01),
        "yaw": Setting(0.6, label="yaw"),
        "pitch": Setting(0.5, -1.5, 1.5, "pitch"),
    },
    dock=("bottom", 0),
    size=(0.35, 0.3),
    short_title="Object",
    widget="lab.app.views.object:ObjectView",
    order=70,
)

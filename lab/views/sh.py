"""Spherical harmonics of the lobe: projection, reconstruction and error by order."""

from __future__ import annotations

from lab.views import Setting, ViewSpec

VIEW = ViewSpec(
    name="sh",
    title="Spherical harmonics",
    settings={"sh_order": Setting(8, 0, 16, "order")},
    dock=("right", 1),
    size=(0.37, 0.42),
    short_title="SH",
    widget="lab.app.views.sh:SHView",
    order=40,
)

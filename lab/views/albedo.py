"""Directional albedo against θi, energy gain flagged (shaders/views/albedo.glsl)."""

from __future__ import annotations

from lab.views import ViewSpec
from lab.views._plots import matplotlib_plot

VIEW = ViewSpec(
    name="albedo",
    title="Directional albedo",
    dock=("bottom", 0),
    widget="lab.app.views.albedo:AlbedoView",
    plot=matplotlib_plot("albedo"),
    order=60,
)

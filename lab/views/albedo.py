"""Directional albedo against θi, energy gain flagged (shaders/views/albedo.glsl)."""

from __future__ import annotations

from lab.views import ViewSpec, plot_with_matplotlib

VIEW = ViewSpec(
    name="albedo",
    title="Directional albedo",
    dock=("bottom", 0),
    widget="lab.app.views:AlbedoView",
    plot=plot_with_matplotlib("albedo"),
    order=60,
)

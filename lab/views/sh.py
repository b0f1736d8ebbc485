"""Spherical harmonics of the lobe: projection, reconstruction and error by order."""

from __future__ import annotations

from lab.views import Setting, ViewSpec

MAX_ORDER = 16  # the highest order of the series (the order setting's top)
# Gauss-Legendre nodes in cos θ x uniform φ over the hemisphere: exact enough to order 16.
GRID = (48, 96)

VIEW = ViewSpec(
    name="sh",
    title="Spherical harmonics",
    settings={"sh_order": Setting(8, 0, MAX_ORDER, "order")},
    dock=("right", 1),
    size=(0.37, 0.42),
    short_title="SH",
    widget="lab.app.views.sh:SHView",
    order=40,
    page_data={"max_order": MAX_ORDER, "grid": GRID},  # the page's sh.js (useGrid)
)

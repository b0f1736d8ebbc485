"""The lit object's spatially varying mode: procedural maps drive the model's parameters."""

from __future__ import annotations

import numpy as np
import pytest

from lab.models import load_model
from lab.render import Light


@pytest.mark.parametrize("name", ["lambert", "oren_nayar", "lommel_seeliger", "phong", "ggx"])
def test_textures_drive_the_models_own_parameters(app_renderer, name):
    """Mode 3 (textures drive the BRDF) differs from mode 1 (one BRDF), even for models whose
    colour parameter is called `albedo`, the name the view's own albedo map once shadowed."""
    lights = [Light(40.0, 20.0)]
    model = load_model(name)
    single = app_renderer.object(model, None, lights, mode=1, size=96)
    varying = app_renderer.object(model, None, lights, mode=3, size=96)
    inside = single[..., 3] > 0
    assert inside.mean() > 0.2
    changed = np.abs(varying - single)[inside].max(axis=-1) > 1e-3
    assert changed.mean() > 0.3
    assert np.isfinite(varying).all() and (varying >= 0).all()

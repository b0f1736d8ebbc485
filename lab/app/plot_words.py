"""What each plot widget shows, in words, as its accessible description (WCAG 1.1.1): the
words of lab/describe_views.py (the web page says the same) on the numbers the view drew,
set after each full-quality draw (View.redraw). The polar plot describes itself
(lab/app/views/polar.py, lab/describe.py)."""

from __future__ import annotations

import numpy as np
from PyQt6.QtWidgets import QWidget

from lab import describe_views
from lab.constants import LUMA
from lab.glsl import ShaderCompileError
from lab.models import ModelError

LOBE_GRID = (46, 72)  # θo rows (normal to 89.5°) x φo columns of the 3D lobe's description


def lobe_grid(rows: int = LOBE_GRID[0], cols: int = LOBE_GRID[1]) -> np.ndarray:
    """(θo, φo) pairs in radians, flat; row 0 is the normal (describe_views.lobe3d)."""
    theta = np.radians(np.linspace(0.0, 89.5, rows))
    phi = np.radians(np.linspace(0.0, 360.0, cols, endpoint=False))
    t, p = np.meshgrid(theta, phi, indexing="ij")
    return np.stack([t.ravel(), p.ravel()], axis=1).ravel()


def _lobe_words(view, s) -> list[str]:
    from lab.geometry import direction

    angles = lobe_grid()
    pairs = angles.reshape(-1, 2)
    V = direction(np.degrees(pairs[:, 0]), np.degrees(pairs[:, 1]))
    L = np.repeat(direction(s["theta_i"], s["phi_i"])[None], len(V), axis=0)
    words = []
    what = "f_r cos θo" if s["polar_cos"] else "f_r"
    # A model's words are computed again only when it or the light changes (a probe each).
    known = view.__dict__.setdefault("words_cache", {})
    for state, (_, spike) in view.data:
        key = (
            state.model.code,
            str(state.model.path),
            sorted(state.values.items()),
            state.label,
            s["theta_i"],
            s["phi_i"],
            s["polar_cos"],
        )
        hit = known.get(id(state))
        if hit is None or hit[0] != key:
            f = view.renderer.probe(state.model, state.values, L, V).astype(np.float64) @ LUMA
            if s["polar_cos"]:
                f = f * np.maximum(V[:, 2], 0.0)
            text = describe_views.lobe3d(
                state.label, f, angles, s["theta_i"], s["phi_i"], what, spike
            )
            known[id(state)] = hit = (key, text)
        words.append(hit[1])
    return words


def _plots(view) -> list[QWidget]:
    """The view and its pyqtgraph plot widgets (where the keyboard and a reader land)."""
    import pyqtgraph as pg

    return [view, *view.findChildren(pg.GraphicsView)]


def view_words(view) -> tuple[str, list[QWidget]]:
    """What `view` shows, in words (lab/describe_views.py, as the web page says it), and the
    widgets that show it; ('', []) for a view described elsewhere (the polar plot)."""
    s = view.lab.settings
    name = view.name
    if name == "sphere":
        words = [
            describe_views.sphere(st.label, image, s["theta_i"], s["phi_i"])
            for st, image in view.floats
        ]
        return " ".join(words), [view.canvas]
    if name == "albedo":
        words = [describe_views.albedo(st.label, t, a) for st, t, a in view.data]
        return " ".join(words), [view.plot]
    if name == "slice":
        words = [describe_views.image_slice(st.label, im, s["phi_d"]) for st, im in view.data]
        return " ".join(words), [view.canvas]
    if name == "object":
        state = view.subject()
        if state is None or view.image is None:
            return "no model to light", [view.canvas]
        return describe_views.picture(state.label, "lit object", view.image), [view.canvas]
    if name == "terms":
        words = [
            describe_views.terms(label, t.theta, t.D, t.theta_o, t.G, t.F)
            for label, t in view.shown
        ]
        if view.info.text():
            words.append(view.info.text() + ".")
        return " ".join(words), _plots(view)
    if name == "sh":
        state = view.subject()
        if view.data is None or state is None:
            return view.info.text(), _plots(view)
        return describe_views.sh(state.label, view.data.errors, view.order), _plots(view)
    if name == "lobe3d":
        return " ".join(_lobe_words(view, s)), [view.canvas]
    if name == "ibl":
        return _ibl_words(view), [view.canvas]
    return "", []


def _ibl_words(view) -> str:
    """The IBL estimate: while it refines, how far it is; once it stops, each strategy's
    picture (read once, not at every pass)."""
    if not getattr(view, "timer_followed", False):  # described again when a run stops
        view.timer_followed = True
        view.timer.timeout.connect(lambda: view.stopped and describe_view(view))
    state = view.lab.selected
    if not view.runs or state is None:
        return view.note or "no model to light"
    if not view.stopped:
        return f"image-based lighting of {state.label}: refining ({view.status.text()})."
    words = [
        describe_views.picture(state.label, f"image-based lighting ({run.strategy})", run.image())
        + f" {run.samples} samples per pixel."
        for run in view.runs
    ]
    return " ".join(words) + f" {view.stopped}."


def describe_view(view) -> None:
    """Sets each of the view's plot widgets' accessible description to its words, after a
    full-quality draw; a key hint set before (OrbitKeys) stays after the words."""
    try:
        text, widgets = view_words(view)
    except (ShaderCompileError, ModelError):
        return  # the view shows the error itself
    for widget in widgets:
        keys = widget.property("keys_hint") or ""
        widget.setAccessibleDescription(f"{text} {keys}".strip() if text else keys)

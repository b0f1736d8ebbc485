"""The desktop lab for screen readers and the keyboard: every widget that takes focus has an
accessible name (what QAccessible gives a screen reader, not just a property), and the plot
widgets describe their lobes in words (lab/describe.py)."""

from __future__ import annotations

from tests.qtapp import settle


def spoken_name(widget) -> str:
    """The name Qt's accessibility bridge gives `widget` (QAccessibleWidget::text(Name)): its
    accessibleName, else a button's text, else the text of the label whose buddy it is.
    (PyQt6 has no QAccessible to ask directly.)"""
    from PyQt6.QtWidgets import QAbstractButton, QLabel

    if widget.accessibleName().strip():
        return widget.accessibleName()
    if isinstance(widget, QAbstractButton) and widget.text().replace("&", "").strip():
        return widget.text()
    top = widget.window()
    for label in top.findChildren(QLabel):
        if label.buddy() is widget and label.text().strip():
            return label.text()
    return ""


def unnamed(root) -> list[str]:
    """Focusable, visible, enabled widgets under `root` without a spoken name."""
    from PyQt6.QtCore import Qt
    from PyQt6.QtWidgets import QWidget

    out = []
    for widget in [root, *root.findChildren(QWidget)]:
        if widget.focusPolicy() == Qt.FocusPolicy.NoFocus or not widget.isVisibleTo(root):
            continue
        if not widget.isEnabled() or not spoken_name(widget).strip():
            if widget.isEnabled():
                parent = widget.parentWidget()
                out.append(
                    f"{type(widget).__name__} {widget.objectName()!r} in "
                    f"{type(parent).__name__} {parent.objectName()!r}"
                )
    return out


def test_every_focusable_widget_has_a_name(qtbot, window):
    from lab.models import load_model

    # Models of every kind of parameter (float, colour, menu, check box) in the panel.
    for name in ("phong", "cook_torrance", "ward"):
        window.lab.add(load_model(name))
    settle(qtbot, window)
    for dock in window.docks.values():
        dock.show()
    qtbot.wait(10)
    missing = unnamed(window)
    assert missing == [], "\n".join(missing)


def test_sliders_say_their_value_in_their_unit(qtbot, window):
    settle(qtbot, window)
    window.lab.settings.set("theta_i", 30.0)
    slider = window.theta_slider.slider
    assert slider.accessibleName() == "θi" or "θ" in slider.accessibleName()
    assert slider.accessibleDescription() == "30 degrees"


def test_polar_plot_describes_its_lobes_as_lab_describe(qtbot, window):
    """The accessible description is lab.describe's words for the plotted lobes; the numbers
    in it are the reference's at the same settings."""
    from lab import describe
    from lab.models import load_model

    window.lab.add(load_model("phong"), {"ke": 20.0})
    window.lab.add(load_model("ggx"), {"alpha": 0.3})
    window.lab.settings.set("theta_i", 45.0)
    settle(qtbot, window)
    view = next(v for v in window.views if v.name == "polar")
    text = view.plot.accessibleDescription()
    phong, ggx = window.lab.visible_models()
    assert text.startswith(f"{phong.label}, θi 45°: peak of f_r at θo 45°, the mirror direction")
    for state in (phong, ggx):
        ref = describe.summarise(describe.reference_lobe(state.model.name, state.values, 45.0))
        assert f"{describe.fmt(ref.peak)} sr⁻¹; half width {describe.deg(ref.half_width)}" in text
    assert "Highest peak:" in text


def test_3d_lobe_and_lit_object_turn_by_keys(qtbot, window):
    from PyQt6.QtCore import Qt

    settle(qtbot, window)
    s = window.lab.settings
    lobe = next(v for v in window.views if v.name == "lobe3d").canvas
    yaw, zoom = s["lobe_yaw"], s["lobe_zoom"]
    qtbot.keyClick(lobe, Qt.Key.Key_Right)
    qtbot.keyClick(lobe, Qt.Key.Key_Plus)
    assert s["lobe_yaw"] > yaw and s["lobe_zoom"] > zoom
    thing = next(v for v in window.views if v.name == "object").canvas
    pitch = s["pitch"]
    qtbot.keyClick(thing, Qt.Key.Key_Up)
    assert s["pitch"] > pitch
    for widget in (lobe, thing):
        assert widget.focusPolicy() != Qt.FocusPolicy.NoFocus


def test_a_rejected_value_is_said_at_its_field(qtbot, window):
    from lab.app.params import ParamControl
    from lab.models import load_model

    window.lab.add(load_model("phong"))
    settle(qtbot, window)
    row = next(c for c in window.findChildren(ParamControl) if c.param.name == "ke")
    assert row.slider.accessibleName() == "ke"
    assert row.slider.accessibleDescription().startswith("50;")
    row.text.setText("fifty")
    row.text.editingFinished.emit()
    said = row.text.accessibleDescription()
    assert "rejected" in said and "ke" in said
    assert window.statusBar().currentMessage() == said


def test_every_plot_widget_describes_what_it_shows(qtbot, window):
    """Each view's plot widget has lab/describe_views.py's words for the numbers it drew as
    its accessible description (the web page says the same words: tests/test_a11y_views.py);
    they follow the light."""
    from lab import describe_views as dv
    from lab.models import load_model
    from tests.qtapp import floating_view

    window.lab.add(load_model("phong"), {"ke": 40.0})
    window.lab.settings.set("theta_i", 40.0)
    settle(qtbot, window)
    for name in ("sphere", "albedo", "slice", "lobe3d", "terms", "sh", "object"):
        floating_view(qtbot, window, name)
    settle(qtbot, window)
    views = {v.name: v for v in window.views}
    state = window.lab.visible_models()[0]
    sphere = views["sphere"]
    ((_, image),) = sphere.floats
    assert sphere.canvas.accessibleDescription() == dv.sphere(state.label, image, 40.0, 0.0)
    assert "0° from the halfway vector" in sphere.canvas.accessibleDescription() or (
        "1° from the halfway vector" in sphere.canvas.accessibleDescription()
    )
    albedo = views["albedo"]
    ((_, thetas, values),) = albedo.data
    assert albedo.plot.accessibleDescription() == dv.albedo(state.label, thetas, values)
    said = {
        n: w.accessibleDescription()
        for n, w in (
            ("slice", views["slice"].canvas),
            ("lobe3d", views["lobe3d"].canvas),
            ("terms", views["terms"]),
            ("sh", views["sh"]),
            ("object", views["object"].canvas),
        )
    }
    assert said["slice"].startswith(f"{state.label}, image slice at φd 90°: f_r from")
    assert "toward θo 40°, φo 180°, the mirror direction" in said["lobe3d"]
    assert said["lobe3d"].endswith("Arrows turn it, plus and minus zoom.")
    assert "MICROFACET_TERMS" in said["terms"]  # Phong has no D, G, F: it says why
    assert said["sh"].startswith(f"{state.label}: spherical harmonics to order")
    assert said["object"].startswith(f"lit object of {state.label}: brightest")
    window.lab.settings.set("theta_i", 60.0)
    settle(qtbot, window)
    assert "toward θo 60°" in views["lobe3d"].canvas.accessibleDescription()


def test_the_ibl_picture_is_described_once_it_stops(qtbot, window):
    """While it refines the IBL view says so; once stopped, each strategy's picture in
    describe_views' words and the samples it took."""
    from lab.models import load_model
    from tests.qtapp import floating_view

    window.lab.add(load_model("ggx"), {"alpha": 0.2})
    window.lab.settings.set("ibl_samples", 16)
    view = floating_view(qtbot, window, "ibl", (900, 420))
    window.settle()
    qtbot.waitUntil(lambda: view.stopped is not None, timeout=60000)
    said = view.canvas.accessibleDescription()
    run = view.runs[0]
    assert said.startswith(f"image-based lighting ({run.strategy}) of {view.lab.selected.label}:")
    assert f"{run.samples} samples per pixel." in said and said.endswith(f"{view.stopped}.")

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

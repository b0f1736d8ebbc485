"""Names for screen readers that the widgets cannot give themselves (WCAG 4.1.2).

Most controls are named where they are made (widgets.py, model_list.py); this names what Qt
makes on its own (dock tab bars, a scroll area's viewport, a spin box's line edit) and the
plot widgets (by their view's title), once at start and for each widget as it gets focus.
"""

from __future__ import annotations

from PyQt6.QtWidgets import QAbstractScrollArea, QAbstractSpinBox, QApplication, QTabBar, QWidget


def name_of_context(widget: QWidget) -> str:
    """A name for an unnamed widget from what holds it; '' when none is found."""
    from lab.app.views.base import View

    if isinstance(widget, QTabBar):
        tabs = ", ".join(widget.tabText(i) for i in range(widget.count()))
        return f"view tabs: {tabs}" if tabs else "view tabs"
    parent = widget.parentWidget()
    if parent is not None and (
        isinstance(parent, (QAbstractScrollArea, QAbstractSpinBox)) and parent.accessibleName()
    ):
        return parent.accessibleName()  # a viewport or a spin box's text field
    holder = widget
    while holder is not None and not isinstance(holder, View):
        holder = holder.parentWidget()
    if holder is not None and isinstance(widget, QAbstractScrollArea):
        return f"{holder.title} of the visible models"
    if isinstance(widget, QAbstractScrollArea):
        return "parameters of the selected model"
    return ""


def name_widgets(root: QWidget) -> None:
    """Names every focusable widget under `root` that has none (its context's name)."""
    from PyQt6.QtCore import Qt

    for _ in range(2):  # a second pass names a viewport after its scroll area
        for widget in [root, *root.findChildren(QWidget)]:
            if widget.focusPolicy() == Qt.FocusPolicy.NoFocus or widget.accessibleName():
                continue
            name = name_of_context(widget)
            if name:
                widget.setAccessibleName(name)


def follow_focus(root: QWidget) -> None:
    """Names widgets made later (a tab bar when docks are tabbed) as the keyboard reaches them."""
    app = QApplication.instance()
    if app is None:
        return

    def focused(_old, new) -> None:
        if new is not None and not new.accessibleName() and root.isAncestorOf(new):
            name = name_of_context(new)
            if name:
                new.setAccessibleName(name)

    app.focusChanged.connect(focused)
    name_widgets(root)

"""Names for screen readers that the widgets cannot give themselves (WCAG 4.1.2).

Most controls are named where they are made (widgets.py, model_list.py); this names what Qt
makes on its own (dock tab bars, a scroll area's viewport, a spin box's line edit) and the
plot widgets (by their view's title), once at start and for each widget as it gets focus;
and gives the 3D pictures keys to turn them (OrbitKeys). What each plot shows, in words, is
lab/app/plot_words.py's.
"""

from __future__ import annotations

from PyQt6.QtCore import QEvent, QObject, Qt
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


class OrbitKeys(QObject):
    """Arrows turn a 3D picture (yaw, pitch settings), + and − zoom it: what a drag and the
    wheel do, for the keyboard. Installed on the picture's widget, which takes focus."""

    STEP = 0.2  # radians per key press (Shift: a quarter)

    def __init__(self, widget: QWidget, settings, yaw: str, pitch: str, zoom: str | None = None):
        super().__init__(widget)
        self.settings, self.yaw, self.pitch, self.zoom = settings, yaw, pitch, zoom
        widget.setFocusPolicy(Qt.FocusPolicy.StrongFocus)
        keys = "Arrows turn it" + (", plus and minus zoom." if zoom else ".")
        widget.setProperty("keys_hint", keys)  # describe_view keeps it after the words
        widget.setAccessibleDescription(keys)
        widget.installEventFilter(self)

    def eventFilter(self, widget, event) -> bool:
        if event.type() != QEvent.Type.KeyPress:
            return False
        s, key = self.settings, event.key()
        step = self.STEP / (4 if event.modifiers() & Qt.KeyboardModifier.ShiftModifier else 1)
        K = Qt.Key
        if key in (K.Key_Left, K.Key_Right):
            s.set(self.yaw, s[self.yaw] + (step if key == K.Key_Right else -step))
        elif key in (K.Key_Up, K.Key_Down):
            turn = step if key == K.Key_Up else -step
            s.set(self.pitch, min(max(s[self.pitch] + turn, -1.5), 1.5))
        elif self.zoom and key in (K.Key_Plus, K.Key_Equal, K.Key_Minus, K.Key_Underscore):
            factor = 1.2 if key in (K.Key_Plus, K.Key_Equal) else 1 / 1.2
            s.set(self.zoom, min(max(s[self.zoom] * factor, 0.2), 8.0))
        else:
            return False
        return True

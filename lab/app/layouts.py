"""The main window's layouts (lab.presets.LAYOUTS): the desk grid for a laptop, the focus
layouts for a projector, the room each dock gets and a window that stays on its screen.

A focus layout shows one or two views large beside compact controls, at presenter fonts:
widgets 1.6 times the desktop's, text inside the plots at least PLOT_TEXT_PX. It is made
for 1024x768, 1280x720 and 1280x800 screens (tests/test_focus_layouts.py measures them).
`win` is always the lab's MainWindow (lab.app.window, which imports this module: typed
here as the QMainWindow it is, so that the two do not import each other).
"""

from __future__ import annotations

from PyQt6 import sip
from PyQt6.QtCore import QRect, Qt, QTimer
from PyQt6.QtGui import QFont
from PyQt6.QtWidgets import QApplication, QDockWidget, QMainWindow, QWidget

from lab import views
from lab.app.views.base import PLOT_TEXT_PX
from lab.presets import DEFAULT_FOCUS, LAYOUTS

QWIDGETSIZE_MAX = 16777215  # Qt's "no maximum" for a widget's size
DOCK_AREAS = {
    "right": Qt.DockWidgetArea.RightDockWidgetArea,
    "bottom": Qt.DockWidgetArea.BottomDockWidgetArea,
}
PRESENTER_SCALE = 1.6  # widget text when presenting, against the desktop's
CONTROLS_MIN = 300  # the controls' narrowest: a colour field, its swatch and reset button
NARROW = 1200  # a screen narrower than this fits two views in a row beside the controls
# A screen at least this tall keeps a heavy view (spec.tab_of) open as a tab behind its
# owner from the start, where its tab names it (its tab bar takes some 25 px of the row).
ROOM_FOR_TABS = 700


def later(win: QWidget, ms: int, run) -> None:
    """run() after `ms` milliseconds, unless the window is gone by then (closed at once)."""
    QTimer.singleShot(ms, lambda: None if sip.isdeleted(win) else run())


def screen_room(win: QWidget) -> QRect:
    """The part of the window's screen a window may use (the panels left out)."""
    screen = win.screen() or QApplication.primaryScreen()
    return screen.availableGeometry()


def keep_on_screen(win: QWidget) -> None:
    """Shrink and move the window (frame included) to lie inside its screen: a view opened
    from the View menu must not push the status bar off a projector's 768 rows."""
    room = screen_room(win)
    frame, inner = win.frameGeometry(), win.geometry()
    edge_w, edge_h = frame.width() - inner.width(), frame.height() - inner.height()
    width = min(inner.width(), room.width() - edge_w)
    height = min(inner.height(), room.height() - edge_h)
    if (width, height) != (inner.width(), inner.height()):
        win.resize(width, height)
    x = min(max(frame.left(), room.left()), room.right() + 1 - (width + edge_w))
    y = min(max(frame.top(), room.top()), room.bottom() + 1 - (height + edge_h))
    if (x, y) != (frame.left(), frame.top()):
        win.move(x, y)


def controls_width(win: QMainWindow) -> int:
    """The controls' width: 27 % of the desk, a compact column in a focus layout. It
    depends on the window's width only, so a preset never changes it."""
    width = max(win.width(), 800)
    if win.presenting:
        return max(320, int(0.22 * width))
    return max(CONTROLS_MIN, int(0.27 * width))


def pin_width(win: QMainWindow, dock: QDockWidget, width: int) -> None:
    """Give `dock` exactly `width` now, then let the user drag it again. (Qt's resizeDocks
    does not move the separator between the left and right areas once a preset has hidden
    the bottom row: the two areas then share the width half and half.)"""
    dock.setFixedWidth(width)

    def release() -> None:  # once the layout has taken the fixed width
        dock.setMinimumWidth(CONTROLS_MIN)
        dock.setMaximumWidth(width if win.presenting else QWIDGETSIZE_MAX)

    later(dock, 0, release)


def room_for_tabs(win: QWidget) -> bool:
    """Whether the window's screen has room for the tab bar of a heavy view's tab."""
    return screen_room(win).height() >= ROOM_FOR_TABS


def in_front(win: QMainWindow, dock: QDockWidget) -> bool:
    """Whether an open dock shows: alone, or the tab in front of its group (a tab behind
    is "visible" to Qt, but nothing of it is on screen)."""
    if dock.isHidden():
        return False
    return not win.tabifiedDockWidgets(dock) or not dock.widget().visibleRegion().isEmpty()


def place_desk(win: QMainWindow) -> None:
    """Every view's dock where its spec puts it: rows in its area stack (the spheres on
    top), the views of a row sit side by side, a heavy view is a tab behind its owner."""
    rows: dict[tuple[str, int], list[QDockWidget]] = {}
    tabs: list[tuple[str, QDockWidget]] = []
    for spec in views.all_views():
        dock = win.docks[spec.name]
        win.addDockWidget(DOCK_AREAS[spec.dock[0]], dock)
        if spec.tab_of:
            tabs.append((spec.tab_of, dock))
        else:
            rows.setdefault(spec.dock, []).append(dock)
    for area in DOCK_AREAS:
        stack = [rows[key] for key in sorted(k for k in rows if k[0] == area)]
        # The rows stacked first, then split into their views: each row spans the area.
        for above, row in zip(stack, stack[1:], strict=False):
            win.splitDockWidget(above[0], row[0], Qt.Orientation.Vertical)
        for row in stack:
            for left, right in zip(row, row[1:], strict=False):
                win.splitDockWidget(left, right, Qt.Orientation.Horizontal)
    for owner, dock in tabs:
        win.tabifyDockWidget(win.docks[owner], dock)
        win.docks[owner].raise_()
    if screen_room(win).width() < NARROW:  # a 1024-pixel screen: the third view is a tab
        for row in rows.values():
            for extra in row[2:]:
                win.tabifyDockWidget(row[1], extra)
            if len(row) > 2:
                row[1].raise_()


def place_focus(win: QMainWindow, name: str) -> None:
    """The layout's one or two views beside the controls; every other view closed."""
    layout = LAYOUTS[name]
    shown = [win.docks[n] for n in layout.views if n in win.docks]
    for view_name, dock in win.docks.items():
        if view_name not in layout.views:
            dock.hide()
    for dock in shown:  # out of any tab group, into the right area
        win.addDockWidget(Qt.DockWidgetArea.RightDockWidgetArea, dock)
        dock.show()
    turn = Qt.Orientation.Horizontal if layout.across else Qt.Orientation.Vertical
    for first, second in zip(shown, shown[1:], strict=False):
        win.splitDockWidget(first, second, turn)


def fit_docks(win: QMainWindow) -> None:
    """Dock sizes for the window's size: the controls' width (controls_width), the rest
    to the views, shared by the focus layout's shares or the views' specs' `size` (each
    row's height, each view's width in its row)."""
    keep_on_screen(win)  # a preset's views may need less room than the last ones
    width, height = max(win.width(), 800), max(win.height(), 600)
    left = controls_width(win)
    pin_width(win, win.controls_dock, left)
    QTimer.singleShot(0, win.fit_titles)  # tabs share their bar's width
    right = width - left
    layout = LAYOUTS[win.layout_name]
    if layout.focus:
        shown = [win.docks[n] for n in layout.views if n in win.docks]
        if len(shown) > 1:
            turn = Qt.Orientation.Horizontal if layout.across else Qt.Orientation.Vertical
            room = right if layout.across else height
            total = sum(layout.shares)
            win.resizeDocks(shown, [int(s / total * room) for s in layout.shares], turn)
        return
    rows = win.view_rows
    if not rows:
        return
    dock = {spec.name: win.docks[spec.name] for row in rows for spec in row}
    # A view in front as a tab (the IBL view before the spheres) asks its row for its height.
    tabbed = [s for s in views.all_views() if s.tab_of and in_front(win, win.docks[s.name])]
    picked = []  # one dock per shown row (a preset may hide a row's first dock, or all)
    for row in rows:
        shown = [dock[s.name] for s in row if not dock[s.name].isHidden()]
        names = {s.name for s in row}
        front = [t for t in tabbed if t.tab_of in names]
        share = max(s.size[1] for s in [*row, *front])
        if shown:  # (Qt sizes a tab group by the tab in front)
            picked.append((win.docks[front[0].name] if front else shown[0], share))
    if picked:
        total = sum(share for _, share in picked)
        win.resizeDocks(
            [d for d, _ in picked],
            [int(share / total * height) for _, share in picked],
            Qt.Orientation.Vertical,
        )
    for row in rows:
        if len(row) > 1:
            total = sum(s.size[0] for s in row)
            win.resizeDocks(
                [dock[s.name] for s in row],
                [int(s.size[0] / total * right) for s in row],
                Qt.Orientation.Horizontal,
            )


def plot_font(font: QFont, presenting: bool, dpi: float) -> QFont:
    """Text inside the views: a little smaller than the widgets' on the desk, at least
    PLOT_TEXT_PX when presenting (read from the back of a lecture hall)."""
    small = QFont(font)
    small.setPointSizeF(font.pointSizeF() * 0.9)
    if presenting:
        small.setPointSizeF(max(font.pointSizeF(), PLOT_TEXT_PX * 72.0 / dpi))
    return small


def apply_fonts(win: QMainWindow) -> None:
    """The desktop's fonts, or the presenter's: larger widgets and plot text."""
    font = QFont(win.base_font)
    font.setBold(False)  # set, not inherited: the docks' bold titles stay theirs
    if win.presenting:
        font.setPointSizeF(win.base_font.pointSizeF() * PRESENTER_SCALE)
    QApplication.setFont(font)
    for widget in win.findChildren(QWidget):
        widget.setFont(font)
    dpi = (win.screen() or QApplication.primaryScreen()).logicalDotsPerInch()
    small = plot_font(font, win.presenting, dpi)
    for view in win.views:
        view.apply_font(font, small)
    # A dock paints its title in the platform's small title font unless its own font
    # differs from the application's: bold titles at the presenter size.
    title = QFont(font)
    title.setBold(win.presenting)
    for dock in win.findChildren(QDockWidget):
        dock.setFont(title)
    win.model_list.arrange(2 if win.presenting else 4)


def set_layout(win: QMainWindow, name: str) -> None:
    """Switch to layout `name`: a focus layout presents (large fonts, full screen), the
    desk gives the laptop's window back with the views that were shown there."""
    layout = LAYOUTS[name]
    was_desk = not LAYOUTS[win.layout_name].focus
    if was_desk and layout.focus:  # remember the desk's views for the way back
        win.desk_shown = [n for n, d in win.docks.items() if not d.isHidden()]
    win.layout_name = name
    presenting = layout.focus
    if presenting != win.presenting:
        win.presenting = presenting
        apply_fonts(win)
    if layout.focus:
        place_focus(win, name)
        win.showFullScreen()
        later(win, 0, lambda: cover_screen(win))
    else:
        for dock in win.docks.values():
            dock.show()
        place_desk(win)
        for view_name, dock in win.docks.items():
            dock.setVisible(view_name in win.desk_shown)
        if win.isFullScreen():
            win.showNormal()
    for action in win.layout_actions.values():
        action.setChecked(False)
    win.layout_actions[name].setChecked(True)
    later(win, 0, lambda: keep_on_screen(win))
    QTimer.singleShot(50, win.fit_docks)  # new fonts and size: lay the docks out again
    win.request()


def cover_screen(win: QMainWindow) -> None:
    """Without a window manager (Xvfb, some projector set-ups) full screen changes nothing:
    then the presenting window takes the screen's free area itself."""
    screen = win.screen() or QApplication.primaryScreen()
    if win.presenting and win.frameGeometry() != screen.geometry():
        win.setGeometry(screen.availableGeometry())


def toggle_presenter(win: QMainWindow) -> None:
    """F11: the preset's focus layout, or back to the desk."""
    set_layout(win, "desk" if win.presenting else win.preset_layout or DEFAULT_FOCUS)


def view_opened(win: QMainWindow, dock: QDockWidget, shown: bool) -> None:
    """A view opened from the View menu while presenting: the focus layout that has it
    (the IBL view alone), or else it shares the room as a tab; the window stays on screen."""
    if shown and not win.presenting:
        dock.raise_()  # a tab opened from the menu comes to the front
    if not shown or not win.presenting:
        later(win, 0, lambda: keep_on_screen(win))
        QTimer.singleShot(0, win.fit_docks)  # an opened tab may want a taller row
        return
    name = dock.objectName()
    current = LAYOUTS[win.layout_name]
    if name in current.views:
        return
    alone = next((k for k, lay in LAYOUTS.items() if lay.views == (name,)), None)
    if alone is not None:
        later(win, 0, lambda: set_layout(win, alone))
    else:  # behind the layout's last view, as a tab
        win.tabifyDockWidget(win.docks[current.views[-1]], dock)
        dock.raise_()
        later(win, 0, lambda: keep_on_screen(win))

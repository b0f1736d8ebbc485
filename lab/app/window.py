"""The main window: docks for the models, the light and every view; files, presets, export."""

from __future__ import annotations

import html
import time
from pathlib import Path

from PyQt6.QtCore import Qt, QTimer, pyqtSignal
from PyQt6.QtGui import QAction, QFont, QFontMetrics, QKeySequence
from PyQt6.QtWidgets import (
    QApplication,
    QDockWidget,
    QFileDialog,
    QFrame,
    QLabel,
    QMainWindow,
    QPlainTextEdit,
    QScrollArea,
    QVBoxLayout,
    QWidget,
)

from lab import views
from lab.app import layouts
from lab.app.a11y import follow_focus
from lab.app.files import ModelFiles
from lab.app.model_list import ModelList
from lab.app.params import ParamPanel
from lab.app.renderer import AppRenderer
from lab.app.state import LabState
from lab.app.views.base import View
from lab.app.widgets import SettingSlider
from lab.models import ModelError, load_model, model_names
from lab.presets import DEFAULT_FOCUS, LAYOUTS, dump_toml, read_preset, shipped_presets

REFINE_DELAY_MS = 150


def close_for_exit(app: QApplication, window: QMainWindow) -> None:
    """Close and delete the window while Qt still runs, before Python exits.

    Left to Python's exit, PyQt's clean-up visited a half torn-down window and crashed
    (SIGSEGV after the last line was printed) in a third of the exits on a loaded machine.
    """
    from PyQt6 import sip

    window.close()
    if not sip.isdeleted(window):
        sip.delete(window)
    app.processEvents()


class MainWindow(ModelFiles, QMainWindow):
    """The lab. `frame_done(n)` is emitted after each redraw of the visible views."""

    frame_done = pyqtSignal(int)
    file_reloaded = pyqtSignal(str)

    def __init__(self, renderer: AppRenderer | None = None):
        super().__init__()
        self.setWindowTitle("brdf-lab")
        self.renderer = renderer or AppRenderer()
        self.lab = LabState()
        self.frames = 0
        self.frame_times: list[float] = []
        self.view_times: dict[str, list[float]] = {}  # each view's redraw, for the benchmark
        self.presets = shipped_presets()
        self.preset_index = -1
        self.presenting = False  # a focus layout, large fonts, full screen (lab/app/layouts)
        self.layout_name = "desk"
        self.preset_layout = DEFAULT_FOCUS  # the focus layout presenter mode opens
        self.desk_shown: list[str] = []  # the views the desk shows (kept while presenting)
        self.base_font = QFont(QApplication.font())
        self.setDockNestingEnabled(True)
        # The controls take the whole left edge: room for every parameter at 1280x800.
        self.setCorner(Qt.Corner.BottomLeftCorner, Qt.DockWidgetArea.LeftDockWidgetArea)
        self.setCorner(Qt.Corner.TopLeftCorner, Qt.DockWidgetArea.LeftDockWidgetArea)
        self._build_controls()
        self.views: list[View] = []
        self.docks: dict[str, QDockWidget] = {}
        self._build_views()
        self._build_menus()
        # Redraws are coalesced: many changes in one event-loop turn make one frame.
        self._pending = False
        self._refine: list[View] = []
        self.refine_timer = QTimer(self)
        self.refine_timer.setSingleShot(True)
        self.refine_timer.timeout.connect(self._refine_step)
        self.lab.changed.connect(self.request)
        self.lab.selection_changed.connect(self.request)  # the object and SH views follow it
        self._init_files()
        self.statusBar().showMessage("ready")  # created now so the layout does not jump later
        self.resize(1280, 800)
        self.desk_shown = [n for n, d in self.docks.items() if not d.isHidden()]
        self._fitted = False
        follow_focus(self)  # names for what Qt makes itself (lab/app/a11y.py)

    def showEvent(self, event) -> None:
        super().showEvent(event)
        if not self._fitted:  # dock sizes need the window's real size: once, when first shown
            self._fitted = True
            layouts.keep_on_screen(self)  # 1280x800 is too large for a 1024x768 screen
            QTimer.singleShot(0, self.fit_docks)

    def resizeEvent(self, event) -> None:
        super().resizeEvent(event)
        QTimer.singleShot(0, self.fit_titles)

    def fit_titles(self) -> None:
        """A dock too narrow for its view's title (presenter fonts) shows a short one."""
        for spec in views.all_views():
            dock = self.docks.get(spec.name)
            if dock is None:
                continue
            font = QFont(dock.font())
            room = dock.width() - 50  # the float and close buttons
            # Docks tabbed together share the width of their tab bar.
            tabs = [d for d in self.tabifiedDockWidgets(dock) if not d.isHidden()]
            if tabs and not dock.isHidden():
                room = dock.width() // (len(tabs) + 1) - 30  # a tab's margins
            title = spec.title
            if QFontMetrics(font).horizontalAdvance(title) > room:
                title = spec.short_title or title
            if dock.windowTitle() != title:
                dock.setWindowTitle(title)

    # -- layout -------------------------------------------------------------------------
    def _build_controls(self) -> None:
        panel = QWidget()
        layout = QVBoxLayout(panel)
        layout.setContentsMargins(4, 4, 4, 4)
        layout.setSpacing(4)
        self.model_list = ModelList(self.lab)
        self.model_list.open_file.connect(self.ask_open)
        layout.addWidget(self.model_list)
        s = self.lab.settings
        self.theta_slider = SettingSlider.of(s, "theta_i")
        self.phi_slider = SettingSlider.of(s, "phi_i")
        layout.addWidget(self.theta_slider)
        layout.addWidget(self.phi_slider)
        self.params = ParamPanel(self.lab)
        scroll = QScrollArea()
        scroll.setWidgetResizable(True)
        scroll.setWidget(self.params)
        layout.addWidget(scroll, 1)
        scroll.setFrameShape(QFrame.Shape.NoFrame)
        # A preset's notes, wrapped: the status bar would cut a long one short.
        self.notes = QLabel()
        self.notes.setWordWrap(True)
        self.notes.setStyleSheet("QLabel { background: #ffffe0; color: black; padding: 3px; }")
        self.notes.hide()
        layout.addWidget(self.notes)
        dock = QDockWidget("Models and light", self)
        dock.setObjectName("controls")
        dock.setWidget(panel)
        dock.setMinimumWidth(300)
        self.controls_dock = dock
        self.addDockWidget(Qt.DockWidgetArea.LeftDockWidgetArea, dock)
        self.errors = QPlainTextEdit()
        self.errors.setReadOnly(True)
        self.errors.setPlaceholderText("compile errors of opened files appear here")
        self.error_dock = QDockWidget("Errors", self)
        self.error_dock.setObjectName("errors")
        self.error_dock.setWidget(self.errors)
        self.addDockWidget(Qt.DockWidgetArea.LeftDockWidgetArea, self.error_dock)
        self.error_dock.hide()

    def _build_views(self) -> None:
        # Every registered view gets a dock, placed by its spec (layouts.place_desk).
        rows: dict[tuple[str, int], list[views.ViewSpec]] = {}
        for spec in views.all_views():
            view = spec.widget_class()(self.lab, self.renderer)
            dock = QDockWidget(spec.title, self)
            dock.setObjectName(spec.name)
            dock.setWidget(view)
            dock.visibilityChanged.connect(lambda shown: shown and self.request())
            dock.toggleViewAction().triggered.connect(
                lambda shown, d=dock: layouts.view_opened(self, d, shown)
            )
            self.addDockWidget(layouts.DOCK_AREAS[spec.dock[0]], dock)
            self.views.append(view)
            self.docks[spec.name] = dock
            if not spec.tab_of:
                rows.setdefault(spec.dock, []).append(spec)
        # The rows top down: the right area's (beside the controls), then the bottom's.
        areas = list(layouts.DOCK_AREAS)
        self.view_rows = [rows[k] for k in sorted(rows, key=lambda k: (areas.index(k[0]), k[1]))]
        layouts.place_desk(self)
        for spec in views.all_views():
            if spec.tab_of:  # a tab behind its owner, where the window has room for a tab bar
                dock = self.docks[spec.name]
                dock.setVisible(layouts.room_for_tabs(self))
                # brought to the front or put back, the row takes its share (fit_docks)
                dock.visibilityChanged.connect(lambda _: QTimer.singleShot(0, self.fit_docks))

    def fit_docks(self) -> None:
        """Dock sizes for the window's size and layout (lab/app/layouts.py)."""
        layouts.fit_docks(self)

    def set_layout(self, name: str) -> None:
        """Switch to the desk or a focus layout (lab.presets.LAYOUTS)."""
        layouts.set_layout(self, name)

    def toggle_presenter(self) -> None:
        """Presenter mode: the preset's focus layout at large fonts, full screen."""
        layouts.toggle_presenter(self)

    def view(self, name: str) -> View:
        return next(v for v in self.views if v.name == name)

    def _build_menus(self) -> None:
        bar = self.menuBar()
        file_menu = bar.addMenu("&File")
        add_menu = file_menu.addMenu("Add model")
        for name in model_names():
            add_menu.addAction(name, lambda n=name: self.lab.add(load_model(n)))
        self._action(file_menu, "Open model file (.glsl, .brdf)…", self.ask_open, "Ctrl+O")
        self._action(file_menu, "Open measured BRDF (.binary)…", self.ask_open_measured, "Ctrl+M")
        file_menu.addSeparator()
        self._action(file_menu, "Load preset…", self.ask_load_preset, "Ctrl+L")
        self._action(file_menu, "Save preset…", self.ask_save_preset, "Ctrl+S")
        export = file_menu.addMenu("Export view as PNG")
        for view in self.views:
            export.addAction(view.title, lambda v=view: self.ask_export(v))
        for view in self.views:  # a view's own exports (the polar plot's CSV)
            for text, slot in view.file_actions():
                self._action(file_menu, text, slot)
        file_menu.addSeparator()
        self._action(file_menu, "Quit", self.close, "Ctrl+Q")
        presets = bar.addMenu("&Presets")
        for index, path in enumerate(self.presets):
            title = read_preset(path).get("title", path.stem)
            presets.addAction(title, lambda i=index: self.step_preset(to=i))
        presets.addSeparator()
        self._action(presets, "Next preset", lambda: self.step_preset(1), "PgDown")
        self._action(presets, "Previous preset", lambda: self.step_preset(-1), "PgUp")
        view_menu = bar.addMenu("&View")
        for dock in self.findChildren(QDockWidget):
            view_menu.addAction(dock.toggleViewAction())
        view_menu.addSeparator()
        self._action(
            view_menu, "Presenter mode (large fonts, full screen)", self.toggle_presenter, "F11"
        )
        layout_menu = view_menu.addMenu("Layout")
        self.layout_actions: dict[str, QAction] = {}
        for index, (name, layout) in enumerate(LAYOUTS.items()):
            action = self._action(
                layout_menu,
                layout.title,
                lambda _=False, n=name: self.set_layout(n),
                f"Ctrl+{index}",
            )
            action.setCheckable(True)
            action.setChecked(name == self.layout_name)
            self.layout_actions[name] = action

    def _action(self, menu, text: str, slot, shortcut: str | None = None) -> QAction:
        action = menu.addAction(text)
        action.triggered.connect(slot)
        if shortcut:
            action.setShortcut(QKeySequence(shortcut))
            action.setShortcutContext(Qt.ShortcutContext.ApplicationShortcut)
        return action

    # -- frames -------------------------------------------------------------------------
    def request(self) -> None:
        if not self._pending:
            self._pending = True
            QTimer.singleShot(0, self.frame)

    def frame(self) -> None:
        """Redraw every shown view at interactive quality; refinement comes later."""
        self._pending = False
        start = time.perf_counter()
        for state in self.lab.models:
            if not state.from_file:
                state.error = ""
        self._refine = []
        for view in self.views:
            if view.is_shown():
                began = time.perf_counter()
                if view.redraw(fast=True):
                    self._refine.append(view)
                self.view_times.setdefault(view.name, []).append(time.perf_counter() - began)
        self.frames += 1
        self.frame_times.append(time.perf_counter() - start)
        if self._refine:
            self.refine_timer.start(REFINE_DELAY_MS)
        self.frame_done.emit(self.frames)

    def _refine_step(self) -> None:
        # One view's step (one model's full-quality result) per event-loop turn, so a
        # refinement never holds back user input for long; unfinished views queue again.
        if self._refine:
            view = self._refine.pop(0)
            if view.is_shown() and view.redraw(fast=False):
                self._refine.append(view)
        if self._refine:
            self.refine_timer.start(0)

    def settle(self) -> None:
        """Run pending frames and refinements now (tests, export, benchmark)."""
        if self._pending:
            self.frame()
        self.refine_timer.stop()
        while self._refine:
            self._refine_step()
        self.refine_timer.stop()

    # -- presets ------------------------------------------------------------------------
    def preset_dict(self, path: Path | None = None) -> dict:
        data = {"title": self.windowTitle().removeprefix("brdf-lab — ") or "brdf-lab state"}
        data.update(self.lab.to_dict(path.parent if path else None))
        data["views"] = (
            list(self.desk_shown)
            if self.presenting
            else [name for name, dock in self.docks.items() if not dock.isHidden()]
        )
        data["layout"] = self.preset_layout
        return data

    def save_preset(self, path: str | Path) -> Path:
        path = Path(path)
        data = self.preset_dict(path)
        settings = data.pop("settings")
        ordered = {k: v for k, v in data.items() if k != "model"}
        ordered["settings"] = settings
        ordered["model"] = data["model"]
        path.write_text(dump_toml(ordered), encoding="utf-8")
        return path

    def load_preset(self, path: str | Path) -> None:
        """Replace the whole state with a preset's; raises ModelError on a bad file."""
        path = Path(path).resolve()
        data = read_preset(path)
        clamped = self.lab.from_dict(data, base=path.parent, where=str(path))
        shown = data.get("views")  # names checked by read_preset
        self.preset_layout = data.get("layout", DEFAULT_FOCUS)
        if shown is not None:
            self.desk_shown = list(shown)
            if not self.presenting:
                for name, dock in self.docks.items():
                    dock.setVisible(name in shown)
        if self.presenting:  # presenting the next preset: its own focus layout
            self.set_layout(self.preset_layout)
        else:
            QTimer.singleShot(0, self.fit_docks)  # the shown views share the room again
        for state in self.lab.models:
            if state.from_file:
                self.watch(str(Path(state.model.path).resolve()))
        if not any(m.error for m in self.lab.models):
            self.errors.clear()  # the previous state's errors do not belong to this one
            self.error_dock.hide()
        title = str(data.get("title", path.stem))
        self.setWindowTitle(f"brdf-lab — {title}")
        notes = str(data.get("notes", ""))
        self.statusBar().showMessage(title)
        self.notes.setText(f"<b>{html.escape(title)}</b>: {html.escape(notes)}" if notes else "")
        self.notes.setVisible(bool(notes))
        if clamped:  # bad values were clamped or ignored: say so where the eye is
            self.errors.setPlainText("\n".join(clamped))
            self.error_dock.show()
            self.statusBar().showMessage(
                clamped[0] + (" (more in Errors)" if len(clamped) > 1 else "")
            )
        self.request()

    def ask_load_preset(self) -> None:
        path, _ = QFileDialog.getOpenFileName(self, "Load preset", "", "Presets (*.toml)")
        if path:
            try:
                self.load_preset(path)
            except ModelError as err:
                self.show_error(path, err)

    def ask_save_preset(self) -> None:
        path, _ = QFileDialog.getSaveFileName(
            self, "Save preset", "preset.toml", "Presets (*.toml)"
        )
        if path:
            self.save_preset(path)
            self.statusBar().showMessage(f"saved {path}", 4000)

    def step_preset(self, step: int = 1, to: int | None = None) -> None:
        """Go to the next/previous shipped preset (presenter keys: PgDown / PgUp)."""
        if not self.presets:
            return
        if to is None:
            to = (self.preset_index + step) % len(self.presets)
        self.preset_index = to
        self.load_preset(self.presets[to])

    # -- export -------------------------------------------------------------------------
    def ask_export(self, view: View) -> None:
        path, _ = QFileDialog.getSaveFileName(
            self, "Export view", f"{view.name}.png", "PNG (*.png)"
        )
        if path:
            self.settle()
            view.export_png(path)

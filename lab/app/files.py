"""Model files in the window: open (.glsl, .brdf, MERL tables), compile-check, watch and
reload on save, keeping the last good version running when an edit breaks it."""

from __future__ import annotations

from pathlib import Path

import moderngl
from PyQt6.QtCore import QFileSystemWatcher, QTimer
from PyQt6.QtWidgets import QFileDialog

from lab.glsl import ShaderCompileError, loop_warning
from lab.models import Model, ModelError
from lab.presets import load_any

NOT_YET = "it was not added: it is added when a saved version compiles"


class ModelFiles:
    """The main window's file handling (a mixin of MainWindow: it uses its lab, renderer,
    error panel and status bar)."""

    def _init_files(self) -> None:
        # Watched model files: reload on save, keep the last good version on errors.
        self.watcher = QFileSystemWatcher(self)
        self.watcher.fileChanged.connect(self._file_changed)
        # A file an editor deleted (to write it anew) is waited for through its folder.
        self.watcher.directoryChanged.connect(self._folder_changed)
        self.missing_files: set[str] = set()
        self.pending_files: set[str] = set()
        self._changed_files: set[str] = set()
        self.reload_timer = QTimer(self)
        self.reload_timer.setSingleShot(True)
        self.reload_timer.setInterval(120)
        self.reload_timer.timeout.connect(self._reload_changed)

    def ask_open(self) -> None:
        path, _ = QFileDialog.getOpenFileName(
            self,
            "Open a model",
            "",
            "Models (*.glsl *.brdf *.binary);;Measured BRDFs (*.binary);;All files (*)",
        )
        if path:
            self.open_file(path)

    def ask_open_measured(self) -> None:
        path, _ = QFileDialog.getOpenFileName(
            self, "Open a measured BRDF", "", "MERL tables (*.binary);;All files (*)"
        )
        if path:
            self.open_measured(path)

    def open_measured(self, path: str | Path):
        """Add a MERL .binary table as the `measured` model; errors go to the error panel."""
        from lab.measured.model import measured_model  # the first frame does without it

        path = str(Path(path).resolve())
        try:
            model = measured_model(path)
            self.check(model)
        except (ModelError, ShaderCompileError, moderngl.Error, ValueError, MemoryError) as err:
            self.show_error(path, err, "the table was not opened")
            return None
        self.statusBar().showMessage(f"opened the measured BRDF {path}", 5000)
        return self.lab.add(model)

    def check(self, model: Model) -> None:
        """Compile the model for the views it is drawn in; raises ShaderCompileError."""
        s = self.lab.settings
        self.renderer.sphere(model, model.defaults(), (s["theta_i"], s["phi_i"]), size=8)
        stop = self.renderer.loop_stop()
        self.renderer.polar(model, model.defaults(), s["theta_i"], s["phi_i"])
        stop = stop or self.renderer.loop_stop()
        if stop is not None:  # the guard kept the GPU alive: say which loop it stopped
            self.show_error(
                str(model.path),
                ValueError(loop_warning(model, stop[0])),
                "the loop guard stopped a loop; the views show what it had computed",
            )

    def show_error(self, path: str, err: Exception, outcome: str | None = None) -> None:
        outcome = outcome or "the last good version keeps running"
        text = str(err)
        self.errors.setPlainText(f"{path}: {outcome}.\n{text}")
        self.error_dock.show()
        self.statusBar().showMessage(text.splitlines()[0] if text else "error", 10000)

    def error_text(self) -> str:
        return self.errors.toPlainText()

    def open_file(self, path: str | Path):
        """Add a model from a file and watch it; errors go to the error panel."""
        if str(path).endswith(".binary"):
            return self.open_measured(path)  # data, not code: nothing to watch
        path = str(Path(path).resolve())
        self.watch(path)
        try:
            model = load_any(path)
            self.check(model)
        except (ModelError, ShaderCompileError) as err:
            self.pending_files.add(path)
            self.show_error(path, err, NOT_YET)
            return None
        self.pending_files.discard(path)
        self.statusBar().showMessage(f"opened {path} (watched for changes)", 5000)
        return self.lab.add(model, from_file=True)

    def watch(self, path: str) -> None:
        """Watch a file; while it does not exist, watch its folder for it to come back."""
        if Path(path).exists():
            self.missing_files.discard(path)
            if path not in self.watcher.files():
                self.watcher.addPath(path)
            return
        self.missing_files.add(path)
        folder = str(Path(path).parent)
        if Path(folder).is_dir() and folder not in self.watcher.directories():
            self.watcher.addPath(folder)

    def _folder_changed(self, folder: str) -> None:
        for path in sorted(self.missing_files):
            if str(Path(path).parent) == folder and Path(path).exists():
                self.missing_files.discard(path)
                self._file_changed(path)
        if not any(str(Path(p).parent) == folder for p in self.missing_files):
            self.watcher.removePath(folder)

    def _file_changed(self, path: str) -> None:
        self._changed_files.add(path)
        self.reload_timer.start()

    def _reload_changed(self) -> None:
        for path in sorted(self._changed_files):
            self.reload(path)
        self._changed_files.clear()

    def reload(self, path: str) -> None:
        """Recompile a watched file; on error keep the last good version running."""
        self.watch(path)  # editors that save by renaming drop the watch
        states = [
            m for m in self.lab.models if m.from_file and str(Path(m.model.path).resolve()) == path
        ]
        if not states and path not in self.pending_files:
            return
        try:
            model = load_any(path)
            self.check(model)
        except (ModelError, ShaderCompileError) as err:
            for state in states:
                state.error = str(err)
            # A file that never compiled has no last good version to keep running.
            self.show_error(path, err, None if states else NOT_YET)
            self.lab.changed.emit()
            self.file_reloaded.emit(path)
            return
        self.errors.clear()
        self.error_dock.hide()
        if path in self.pending_files:
            self.pending_files.discard(path)
            self.lab.add(model, from_file=True)
        for state in states:
            old = state.model
            state.error = ""
            state.replace_model(model)
            self.renderer.forget(old) if old.code != model.code else None
        self.statusBar().showMessage(f"reloaded {path}", 4000)
        self.file_reloaded.emit(path)

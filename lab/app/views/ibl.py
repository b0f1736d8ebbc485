"""The desktop lab's image-based lighting view: the selected model's sphere under an
environment, integrated progressively on the GPU (lab/ibl), optionally beside a second
strategy at equal samples, with the estimated error against samples on a log-log plot.

The error needs no reference: each strategy runs as two independent halves (different
seeds), and RMS(A - B) / 2 / RMS((A + B) / 2) estimates the relative RMS error of their
mean. Passes run from the view's own timer while it is shown, so the window's refinement
(and the tests' flush) never waits for convergence. They go on until that estimate is at
the chosen error, or the time budget is spent, or the samples/pixel cap is reached, and
the status line says which; a pass's size adapts to take about PASS_SECONDS.
"""

from __future__ import annotations

import time
from pathlib import Path

import numpy as np
import pyqtgraph as pg
from PyQt6.QtCore import Qt, QTimer
from PyQt6.QtWidgets import (
    QComboBox,
    QFileDialog,
    QHBoxLayout,
    QLabel,
    QPushButton,
    QSplitter,
)

from lab.app.views.base import ImageRow, View, state_key, tonemap
from lab.app.views.ibl_widgets import LogAxis, SamplesCombo
from lab.app.widgets import LiveText, SettingCombo, SettingSlider
from lab.constants import LUMA
from lab.glsl import ShaderCompileError
from lab.ibl import environments
from lab.ibl.integrator import (
    STRATEGY_TITLES,
    Environment,
    IBLRenderer,
    Progressive,
    fallback,
    local_view,
    ring_peak,
)
from lab.models import ModelError
from lab.views.ibl import (
    COMPARE,
    ENVIRONMENTS,
    SEQUENCE_TITLES,
    SEQUENCES,
    STOP_ERRORS,
    STOP_SECONDS,
    STRATEGIES,
    TARGETS,
)

SIZE = 192  # pixels per sphere
PASS_SECONDS = 0.1  # a step of passes this long keeps the window responsive
MAX_PASS_SPP = 64
MIN_SAMPLES_TO_STOP = 32  # per half: the error estimate of fewer is too noisy to trust
COLORS = ("#ffb000", "#4aa3ff")


class Run:
    """One strategy as two independent progressive halves."""

    def __init__(
        self,
        renderer,
        model,
        values,
        env,
        strategy,
        size,
        shape=None,
        turn=(0.6, 0.5),
        sequence="random",
    ):
        self.halves = [
            Progressive(
                renderer,
                model,
                values,
                env,
                strategy,
                size,
                seed=seed,
                shape=shape,
                yaw=turn[0],
                pitch=turn[1],
                sequence=sequence,
            )
            for seed in (11, 29)
        ]
        self.strategy = strategy
        self.history: list[tuple[int, float]] = []

    @property
    def samples(self) -> int:
        return sum(h.samples for h in self.halves)

    def add(self, spp: int) -> None:
        for half in self.halves:
            half.add(spp)

    def image(self) -> np.ndarray:
        a, b = (h.image() for h in self.halves)
        mean = 0.5 * (a + b)
        mask = mean[..., 3] > 0.5
        if mask.any():
            rms = np.sqrt(np.mean(mean[..., :3][mask] ** 2))
            error = np.sqrt(np.mean((a[..., :3][mask] - b[..., :3][mask]) ** 2)) / 2.0
            if rms > 0 and (not self.history or self.history[-1][0] != self.samples):
                self.history.append((self.samples, float(error / rms)))
        return mean

    @property
    def error(self) -> float | None:
        """The latest estimate of the relative RMS error (None before the first image)."""
        return self.history[-1][1] if self.history else None

    def release(self) -> None:
        for half in self.halves:
            half.release()


class IBLView(View):
    title = "Image-based lighting"
    name = "ibl"

    def __init__(self, lab, renderer):
        super().__init__(lab, renderer)
        s = lab.settings
        self.gl = IBLRenderer(renderer.ctx)
        # Two short rows, combos that may shrink: the view must fit a 1024-pixel projector
        # in presenter mode, where it shares the spheres' column.
        combos = [
            SettingCombo(s, "ibl_env", ENVIRONMENTS),
            SettingCombo(s, "ibl_strategy", STRATEGIES),
            SettingCombo(s, "ibl_compare", COMPARE),
            SettingCombo(s, "ibl_target", TARGETS),
            SettingCombo(s, "ibl_sequence", SEQUENCE_TITLES),
            SettingCombo(s, "ibl_stop_error", [f"until {e * 100:g}%" for e in STOP_ERRORS]),
            SettingCombo(s, "ibl_stop_time", ["or 10 s", "or 1 min", "or 5 min", "or 30 min"]),
        ]
        for combo in combos:
            combo.setSizeAdjustPolicy(
                QComboBox.SizeAdjustPolicy.AdjustToMinimumContentsLengthWithIcon
            )
            combo.setMinimumContentsLength(5)
        self.open_button = QPushButton("HDR…")
        self.open_button.setToolTip("open an equirectangular .hdr or .exr environment")
        self.open_button.clicked.connect(self.open_file)
        combos[3].setToolTip("light the sphere, or the object view's shape (its yaw and pitch)")
        self.samples = SamplesCombo(s)
        combos[4].setToolTip("random numbers, or each pixel's scrambled Sobol' sequence")
        combos[5].setToolTip("refine until the estimated error is this low...")
        combos[6].setToolTip("...or until this much time is spent")
        for widget in (combos[3], combos[0], self.open_button, combos[1], combos[2]):
            self.tools.addWidget(widget)
        # The second row: how it refines and when it stops, each choice shown whole; the
        # third: the environment's rotation and exposure (one row of all would widen the dock
        # past a 1024 px screen).
        second = QHBoxLayout()
        for combo in combos[4:]:
            combo.setSizeAdjustPolicy(QComboBox.SizeAdjustPolicy.AdjustToContents)
            second.addWidget(combo)
        second.addWidget(QLabel("at most"))
        second.addWidget(self.samples)
        second.addStretch(1)
        self.second = second
        self.layout_.addLayout(second)
        third = QHBoxLayout()
        third.addWidget(SettingSlider.of(s, "ibl_rotation"), 1)
        third.addWidget(SettingSlider.of(s, "ibl_exposure"), 1)
        self.layout_.addLayout(third)
        self.canvas = ImageRow()
        self.canvas.setMinimumSize(64, 48)
        # One line whatever the width: in a narrow dock the short form (count and gain),
        # the tooltip holds it all. The dock must stay short on the desk.
        self.status = LiveText(optional=False)
        self.plot = pg.PlotWidget(
            axisItems={"bottom": LogAxis("bottom", base=4), "left": LogAxis("left", percent=True)}
        )
        self.plot.setMinimumSize(64, 48)
        self.plot.setLogMode(True, True)
        self.plot.setLabel("bottom", "samples per pixel")
        self.plot.setLabel("left", "RMS error")  # relative: its ticks in %
        self.plot.addLegend(offset=(-5, 5))
        # Picture and plot side by side in a wide view, the plot below in a tall one.
        self.split = QSplitter()
        self.split.addWidget(self.canvas)
        self.split.addWidget(self.plot)
        self.split.setSizes([600, 300])
        self.layout_.addWidget(self.split, 1)
        self.layout_.addWidget(self.status)
        self.user_file: Path | None = None
        self.environments: dict[str, Environment] = {}
        self.runs: list[Run] = []
        self.key: tuple | None = None
        self.note = ""
        self.timer = QTimer(self)
        self.timer.setSingleShot(True)
        self.timer.timeout.connect(self.step)
        self.pass_spp = 1
        self.elapsed = 0.0  # seconds of passes since the last restart
        self.stopped: str | None = None  # why refinement stopped (None: still refining)

    def resizeEvent(self, event) -> None:
        wide = self.width() > 1.3 * self.height()
        turn = Qt.Orientation.Horizontal if wide else Qt.Orientation.Vertical
        if self.split.orientation() != turn:
            self.split.setOrientation(turn)
            length = self.width() if wide else self.height()
            self.split.setSizes([int(0.62 * length), int(0.38 * length)])
        super().resizeEvent(event)

    # -- inputs ---------------------------------------------------------------------------
    def open_file(self) -> None:
        name, _ = QFileDialog.getOpenFileName(
            self, "Open an environment", "", "HDR images (*.hdr *.pic *.exr)"
        )
        if name:
            self.load_file(name)

    def load_file(self, path) -> None:
        """Use an equirectangular .hdr/.exr file (reported in the status line if bad)."""
        try:
            self.environments[str(path)] = Environment.load(path)
            self.user_file = Path(path)
        except environments.EnvironmentError as err:
            self.status.short = None
            self.status.setText(f"cannot use that file: {err}")
            return
        self.request()

    def environment(self) -> Environment:
        name = str(self.user_file) if self.user_file else ENVIRONMENTS[self.lab.settings["ibl_env"]]
        if name not in self.environments:
            self.environments[name] = Environment.load(name)
        return self.environments[name]

    def strategies(self) -> list[str]:
        s = self.lab.settings
        chosen = [STRATEGIES[s["ibl_strategy"]]]
        if s["ibl_compare"] > 0:
            chosen.append(STRATEGIES[s["ibl_compare"] - 1])
        return chosen

    def inputs(self) -> tuple:
        s = self.lab.settings
        state = self.lab.selected
        model = state_key(state) if state else None
        env = str(self.user_file) if self.user_file else s["ibl_env"]
        target = self.target()
        turn = (s["yaw"], s["pitch"]) if target else ()
        return (
            model,
            env,
            tuple(self.strategies()),
            s["ibl_rotation"],
            s["ibl_samples"],
            s["ibl_sequence"],
            s["ibl_stop_error"],
            s["ibl_stop_time"],
            target,
            *turn,
        )

    def target(self) -> str | None:
        """The object view's shape to light, or None for the sphere."""
        chosen = TARGETS[self.lab.settings["ibl_target"]]
        return None if chosen == "sphere" else chosen

    def request(self) -> None:
        """Ask the main window for a frame (a floating dock's window() is the dock)."""
        widget = self.parentWidget()
        while widget is not None and not hasattr(widget, "request"):
            widget = widget.parentWidget()
        if widget is not None:
            widget.request()

    # -- drawing --------------------------------------------------------------------------
    def draw(self, fast: bool) -> bool:
        """Restart the runs when the inputs changed; passes continue from the timer."""
        key = self.inputs()
        if key != self.key:
            self.key = key
            self.restart()
        elif self.runs and not self.timer.isActive():
            self.timer.start(0)  # brought forward again: carry on where it stopped
        self.show_images()
        return False

    def restart(self) -> None:
        for run in self.runs:
            run.release()
        self.runs = []
        self.plot.clear()
        self.pass_spp, self.elapsed, self.stopped = 1, 0.0, None
        state = self.lab.selected
        if state is None:
            self.note = "add a model to light it"
            return
        env = self.environment()
        s = self.lab.settings
        try:
            for strategy in self.strategies():
                run = Run(
                    self.gl,
                    state.model,
                    state.values,
                    env,
                    strategy,
                    SIZE,
                    self.target(),
                    (s["yaw"], s["pitch"]),
                    SEQUENCES[s["ibl_sequence"]],
                )
                for half in run.halves:
                    half.rotation = s["ibl_rotation"]
                self.runs.append(run)
        except (ShaderCompileError, ModelError) as err:
            self.note = f"{state.label}: {err}"
            self.runs = []
            return
        notes = [n for n in (fallback(state.model, st) for st in self.strategies()) if n]
        self.note = "; ".join(dict.fromkeys(notes))
        self.step()

    def stop_reason(self) -> str | None:
        """Why refinement is over: the error target, the time budget or the sample cap
        (None: go on). The error is the first run's estimate."""
        s = self.lab.settings
        run = self.runs[0]
        goal, budget = STOP_ERRORS[s["ibl_stop_error"]], STOP_SECONDS[s["ibl_stop_time"]]
        error = run.error
        if run.samples >= s["ibl_samples"]:
            return f"stopped at the cap of {s['ibl_samples']} samples/pixel"
        if error is not None and error <= goal and run.samples >= 2 * MIN_SAMPLES_TO_STOP:
            return f"done: error {error:.2%} ≤ target {goal:.2%} in {self.elapsed:.1f} s"
        if self.elapsed >= budget:
            at = f", error {error:.2%} > target {goal:.2%}" if error is not None else ""
            return f"time budget of {budget:.0f} s spent{at}"
        return None

    def step(self) -> None:
        """One pass for each run, then the next, until stop_reason says why not."""
        cap = self.lab.settings["ibl_samples"]
        if not self.runs or not self.is_shown() or self.stopped:
            return
        start = time.perf_counter()
        for run in self.runs:
            run.add(max(min(self.pass_spp, (cap - run.samples) // 2), 1))
        self.gl.ctx.finish()
        seconds = time.perf_counter() - start
        self.elapsed += seconds
        # Passes of about PASS_SECONDS: a pass has a fixed cost, so short ones waste time.
        scale = min(max(PASS_SECONDS / max(seconds, 1e-3), 0.5), 2.0)
        self.pass_spp = int(min(max(round(self.pass_spp * scale), 1), MAX_PASS_SPP))
        self.show_images()  # the error estimate the stop reads comes from here
        self.stopped = self.stop_reason()
        if self.stopped:
            self.show_images()
        else:
            self.timer.start(0)

    def show_images(self) -> None:
        s = self.lab.settings
        env = self.environment()
        images, texts = [], []
        for run in self.runs:
            image = run.image() if run.samples else np.zeros((SIZE, SIZE, 4), np.float32)
            shown = image.copy()
            shown[..., 3] = 1.0  # the environment behind the sphere
            if env.name == "furnace" and self.target() is None:
                shown = self.mark_gain(shown)
            title = STRATEGY_TITLES[run.halves[0].chosen]
            if run.strategy == "auto":
                title = f"auto: {title}"
            images.append((tonemap(shown, s["ibl_exposure"], 2.2), title))
            texts.append(self.gain_text(image, env))
        self.canvas.images = [(img, cap, COLORS[i]) for i, (img, cap) in enumerate(images)]
        self.canvas.update()
        self.draw_plot()
        count = self.runs[0].samples if self.runs else 0
        parts = [f"{count} samples per pixel"]
        short = [f"{count} spp"]
        if len(self.runs) > 1:
            parts[0] += " each (equal samples)"
        if self.runs:
            error = self.runs[0].error
            goal = STOP_ERRORS[s["ibl_stop_error"]]
            parts.append(
                self.stopped
                or (
                    f"refining: error {error:.2%} → {goal:.2%}" if error is not None else "refining"
                )
                + f", {self.elapsed:.1f} of {STOP_SECONDS[s['ibl_stop_time']]:.0f} s"
            )
            if error is not None:
                short.append(f"{error:.1%}" + (" done" if self.stopped else ""))
        short += [brief for _, brief in texts if brief]
        parts += [t for t, _ in texts if t] + ([self.note] if self.note else [])
        self.status.short = " · ".join(dict.fromkeys(short))
        self.status.setText(" · ".join(dict.fromkeys(parts)))
        self.status.setToolTip(self.status.text())

    def gain_text(self, image: np.ndarray, env: Environment) -> tuple[str, str]:
        """Under the white furnace, radiance above 1 is energy the BRDF creates: say so
        (rings of equal view angle on the sphere; on an object, its brightest 1%), in full
        and in brief (a narrow status line)."""
        lit = image[..., 3] > 0.5
        if env.name != "furnace" or not lit.any():
            return "", ""
        if self.target() is None:
            peak = ring_peak(image)
        else:
            peak = float(np.percentile(image[..., :3][lit] @ np.array(LUMA), 99))
        if peak > 1.01:
            return (
                f"ENERGY GAIN: reflects up to {peak:.2f}× the light it receives (> 1)",
                f"ENERGY GAIN {peak:.2f}×",
            )
        return f"furnace: at most {peak:.2f} of the light is reflected (≤ 1)", f"≤ {peak:.2f}"

    @staticmethod
    def mark_gain(image: np.ndarray) -> np.ndarray:
        """Tint red the rings of the sphere whose mean reflectance exceeds 1 (in the white
        furnace they would otherwise vanish into the white background)."""
        theta, _, mask = local_view(image.shape[0])
        rings = np.minimum((theta / 90.0 * 24).astype(int), 23)
        lum = image[..., :3] @ np.array(LUMA)
        for ring in range(24):
            where = mask & (rings == ring)
            if where.any() and lum[where].mean() > 1.01:
                image[where, :3] = np.minimum(image[where, :3], 1.0) * 0.3 + np.array(
                    [0.7, 0.0, 0.0]
                )
        return image

    def draw_plot(self) -> None:
        self.plot.clear()
        first = None
        for index, run in enumerate(self.runs):
            if len(run.history) < 2:
                continue
            n, e = np.array(run.history).T
            self.plot.plot(n, e, pen=pg.mkPen(COLORS[index], width=2), name=run.strategy)
            first = first or (n[0], e[0], n[-1])
        if first:  # the 1/sqrt(N) line through the first run's first point
            n0, e0, n1 = first
            ns = np.array([n0, max(n1, n0 * 4)])
            self.plot.plot(
                ns,
                e0 * np.sqrt(n0 / ns),
                pen=pg.mkPen("#999", width=1, style=Qt.PenStyle.DashLine),
                name="1/√N",
            )

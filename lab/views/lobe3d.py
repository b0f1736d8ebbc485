"""The 3D lobe: f_r over the hemisphere as a surface drawn by the model's own GLSL in the
vertex stage (shaders/views/lobe_mesh*.glsl), its camera and marks; `LobeMesh` gives the
Renderer its `lobe_peak` and `lobe_mesh`."""

from __future__ import annotations

import math
from dataclasses import dataclass

import moderngl
import numpy as np

from lab import glsl
from lab.constants import PLOT_DECADES
from lab.geometry import direction
from lab.models import Model
from lab.sources import as_model
from lab.views import PlotJob, Setting, ViewSpec

LOBE_GRID = (61, 121)  # vertices in theta_o and phi_o (the mirror direction is one of them)
LOBE_FAST_GRID = (25, 49)  # while a slider moves (llvmpipe sets triangles up on one core)
LOBE_DECADES = PLOT_DECADES  # the log scale's range, as the polar plot's
LOBE_STYLES = ("solid", "wire")
LOBE_MAX_SEGMENTS = 96  # shaders/views/lobe_mesh_lines.glsl's MAX_SEGMENTS
LOBE_MARK_RGB = {
    "normal": (0.78, 0.78, 0.78),
    "incident": (1.0, 0.82, 0.0),
    "mirror": (0.47, 0.78, 1.0),
}


@dataclass(frozen=True)
class LobeCamera:
    """The 3D lobe's orbit camera (radians); `project` is shaders/views/lobe_mesh_common's
    lobe_view and lobe_clip in numpy, for placing labels and for tests."""

    yaw: float = -0.6
    pitch: float = 0.35
    zoom: float = 1.0
    perspective: bool = True

    TARGET = (0.0, 0.0, 0.3)
    DISTANCE = 5.0
    SCALE = 0.85

    def uniforms(self, width: int, height: int) -> dict:
        """The camera's uniforms. Clip y is flipped so that GL's first row, read back
        first, is the picture's top row (no flip of the pixels afterwards)."""
        short = float(min(width, height))
        return {
            "u_yaw": float(self.yaw),
            "u_pitch": float(self.pitch),
            "u_zoom": float(self.zoom),
            "u_perspective": bool(self.perspective),
            "u_aspect": (short / width, -short / height),
        }

    def project(self, points, size: tuple[int, int]) -> np.ndarray:
        """Pixel positions (x right, y down from the top row) of world points (n, 3)."""
        p = np.asarray(points, dtype=np.float64).reshape(-1, 3)
        c, s = math.cos(self.yaw), math.sin(self.yaw)
        q = np.stack([c * p[:, 0] - s * p[:, 1], s * p[:, 0] + c * p[:, 1], p[:, 2]], axis=-1)
        q = q - np.array(self.TARGET)
        cp, sp = math.cos(self.pitch), math.sin(self.pitch)
        view = np.stack([q[:, 0], q[:, 1] * sp + q[:, 2] * cp, q[:, 2] * sp - q[:, 1] * cp], -1)
        w = (self.DISTANCE - view[:, 2]) / self.DISTANCE if self.perspective else 1.0
        width, height = size
        short = min(width, height)
        ndc_x = view[:, 0] * self.SCALE * self.zoom * short / width / w
        ndc_y = view[:, 1] * self.SCALE * self.zoom * short / height / w
        return np.stack([(ndc_x + 1.0) * 0.5 * width, (1.0 - ndc_y) * 0.5 * height], axis=-1)


def _view_text(name: str) -> str:
    return (glsl.VIEW_DIR / f"{name}.glsl").read_text(encoding="utf-8")


def _lobe_common() -> str:
    """The grid and camera code every lobe program starts with (read once)."""
    text = _LOBE_COMMON.get("text")
    if text is None:
        text = _LOBE_COMMON["text"] = _view_text("lobe_mesh_common")
    return text


_LOBE_COMMON: dict[str, str] = {}


def _lobe_radius(value: float, peak: float, log: bool) -> float:
    """Where lobe_mesh.glsl puts `value` (the same formula, for the spike)."""
    if log:
        floor = peak * 10.0**-LOBE_DECADES
        r = max(math.log10(max(value, floor) / floor), 0.0) / LOBE_DECADES
    else:
        r = value / peak
    return min(r, 1.5)


def _lobe_marks(theta_i: float, phi_i: float) -> list:
    """Horizon circle, X and Y axes, and the normal, incident and mirror directions."""
    angle = np.radians(np.linspace(0.0, 360.0, 73))
    ring = np.stack([np.cos(angle), np.sin(angle), np.zeros_like(angle)], axis=-1)
    grey = (0.55, 0.55, 0.6, 1.0)
    segments = [
        (tuple(a), tuple(b), grey, (1.3, 0.0)) for a, b in zip(ring[:-1], ring[1:], strict=True)
    ]
    faint = (0.45, 0.45, 0.5, 0.8)
    segments.append(((-1.0, 0.0, 0.0), (1.0, 0.0, 0.0), faint, (1.0, 0.0)))
    segments.append(((0.0, -1.0, 0.0), (0.0, 1.0, 0.0), faint, (1.0, 0.0)))
    origin = (0.0, 0.0, 0.0)
    ends = {
        "normal": direction(0.0, 0.0),
        "incident": direction(theta_i, phi_i),
        "mirror": direction(theta_i, phi_i + 180.0),
    }
    for name, end in ends.items():
        segments.append((origin, tuple(1.15 * end), (*LOBE_MARK_RGB[name], 1.0), (1.6, 7.0)))
    return segments


class LobeMesh:
    """The Renderer's 3D-lobe methods (it supplies ctx, _run, _read, _assemble, _programs)."""

    def lobe_peak(
        self,
        model: Model | str,
        values,
        theta_i: float,
        phi_i: float = 0.0,
        cos_weighted: bool = False,
        grid: tuple[int, int] = LOBE_GRID,
    ) -> tuple[float, float]:
        """(largest value, spike) of the lobe that `lobe_mesh` draws with this grid.

        The values are luminances of f_r (times cos theta_o when `cos_weighted`) at the
        mesh's own vertices, grazing ones (beyond 87 deg) left out; `spike` is the luminance
        of a delta model's reflectance (0 for other models). Compiles the model's lobe
        programs, so a model that cannot be drawn raises ShaderCompileError here.
        """
        model = as_model(model)
        self._lobe_program(model, values, {})
        uniforms = {
            "u_grid": tuple(grid),
            "u_light_angles": (math.radians(theta_i), math.radians(phi_i)),
            "u_cos": bool(cos_weighted),
        }
        fbo = self._run(
            model, "lobe_mesh_peak", values, (grid[1], grid[0]), uniforms, _lobe_common()
        )
        texels = self._read(fbo)
        shown = texels[..., 1]
        shown = shown[np.isfinite(shown)]
        peak = float(shown.max()) if shown.size else 0.0
        spike = float(texels[0, 0, 2]) if model.delta else 0.0
        return max(peak, 0.0), spike if math.isfinite(spike) else 0.0

    def lobe_mesh(
        self,
        layers: list[tuple[Model | str, dict, tuple[float, float, float]]],
        theta_i: float,
        phi_i: float = 0.0,
        size: tuple[int, int] = (512, 512),
        camera: LobeCamera | None = None,
        cos_weighted: bool = False,
        log: bool = False,
        grid: tuple[int, int] = LOBE_GRID,
        style: str = "solid",
        marks: bool = True,
        peak: float | None = None,
        peaks: list[tuple[float, float]] | None = None,
        background: tuple[float, float, float, float] = (0.0, 0.0, 0.0, 0.0),
        supersample: int = 1,
        dtype: str = "f4",
    ) -> np.ndarray:
        """The 3D lobes of `layers` (model, values, colour), overlaid: (h, w, 4) float32.

        Each model's BRDF runs in the vertex stage (shaders/views/lobe_mesh.glsl) on a
        hemisphere grid; the surface lies at r * V with r = f_r (or f_r cos theta_o) over
        `peak` (by default the largest value of all layers, spikes included; `peaks`, the
        layers' `lobe_peak` results when the caller has them at hand), or on a log
        scale over LOBE_DECADES decades. A delta model's spike is a line of its reflectance.
        `marks` adds the horizon circle and the normal, incident and mirror directions.
        `style` is "solid" or "wire" (the grid lines only). The light (theta_i, phi_i) is in
        the local frame (N = z, X = x). Colours are display values; RGB is premultiplied
        by alpha over `background` (alpha 0: transparent). Row 0 is the top. `dtype` "u1"
        renders and returns 8-bit RGBA instead (for display, over an opaque background).
        """
        if style not in LOBE_STYLES:
            raise ValueError(f"unknown lobe style {style!r}: use one of {LOBE_STYLES}")
        camera = camera or LobeCamera()
        k = max(int(supersample), 1)
        width, height = int(size[0]) * k, int(size[1]) * k
        layers = [(as_model(m), v, tuple(float(c) for c in rgb)) for m, v, rgb in layers]
        if peaks is None:
            peaks = [self.lobe_peak(m, v, theta_i, phi_i, cos_weighted, grid) for m, v, _ in layers]
        if peak is None:
            peak = max([p for pair in peaks for p in pair] + [0.0])
        peak = peak if math.isfinite(peak) and peak > 0.0 else 1e-12
        light = (math.radians(theta_i), math.radians(phi_i))
        common = {
            "u_grid": tuple(grid),
            "u_light_angles": light,
            **camera.uniforms(width, height),
        }
        fbo = self._lobe_target(width, height, dtype)
        fbo.use()
        fbo.clear(*background, depth=1.0)
        ctx = self.ctx
        ctx.enable(moderngl.DEPTH_TEST | moderngl.BLEND)
        ctx.front_face = "cw"  # the camera draws upside down (see LobeCamera.uniforms)
        ctx.blend_func = (
            moderngl.SRC_ALPHA,
            moderngl.ONE_MINUS_SRC_ALPHA,
            moderngl.ONE,
            moderngl.ONE_MINUS_SRC_ALPHA,
        )
        try:
            ctx.depth_func = "<"
            indices = self._lobe_indices(grid)
            for model, values, rgb in layers:
                uniforms = {
                    **common,
                    "u_peak": peak,
                    "u_log": bool(log),
                    "u_decades": LOBE_DECADES,
                    "u_cos": bool(cos_weighted),
                    "u_color": rgb,
                    "u_wire": style == "wire",
                }
                program = self._lobe_program(model, values, uniforms)
                vao = ctx.vertex_array(program, [], index_buffer=indices, index_element_size=4)
                try:
                    vao.render(moderngl.TRIANGLES)
                finally:
                    vao.release()
            segments = []
            if marks:
                segments += _lobe_marks(theta_i, phi_i)
            for (model, _, rgb), (_, spike) in zip(layers, peaks, strict=True):
                if model.delta and spike > 0.0:
                    r = _lobe_radius(spike, peak, log)
                    mirror = direction(theta_i, phi_i + 180.0)
                    segments.append(((0.0, 0.0, 0.0), tuple(r * mirror), (*rgb, 1.0), (4.0, 0.0)))
            if segments:
                self._lobe_lines(segments, common, width, height, k)
        finally:
            ctx.disable(moderngl.DEPTH_TEST | moderngl.BLEND)
            ctx.depth_func = "<"
            ctx.blend_func = moderngl.DEFAULT_BLENDING
            ctx.front_face = "ccw"
            fbo.depth_mask = True
        image = np.empty((height, width, 4), np.uint8 if dtype == "u1" else np.float32)
        fbo.read_into(image, components=4, dtype=dtype if dtype == "f4" else "f1")
        if k > 1:
            image = image.reshape(height // k, k, width // k, k, 4).mean(axis=(1, 3))
            image = image.astype(np.float32) if dtype == "f4" else (image + 0.5).astype(np.uint8)
        return image

    def _lobe_target(self, width: int, height: int, dtype: str = "f4") -> moderngl.Framebuffer:
        if dtype not in ("f4", "u1"):
            raise ValueError(f"unknown lobe image dtype {dtype!r}: use 'f4' or 'u1'")
        key = ("lobe", width, height, dtype)
        fbo = self._targets.get(key)
        if fbo is None:
            texture = self.ctx.texture((width, height), 4, dtype="f4" if dtype == "f4" else "f1")
            fbo = self.ctx.framebuffer(
                color_attachments=[texture],
                depth_attachment=self.ctx.depth_renderbuffer((width, height)),
            )
            self._targets[key] = fbo
        return fbo

    def _lobe_indices(self, grid: tuple[int, int]) -> moderngl.Buffer:
        """Two triangles per grid cell; vertex i * columns + j is grid vertex (i, j)."""
        cache = self.__dict__.setdefault("_lobe_index_buffers", {})
        buffer = cache.get(tuple(grid))
        if buffer is None:
            rows, cols = grid
            i, j = np.meshgrid(np.arange(rows - 1), np.arange(cols - 1), indexing="ij")
            v00 = (i * cols + j).ravel()
            v01, v10 = v00 + 1, v00 + cols
            triangles = np.stack([v00, v10, v10 + 1, v00, v10 + 1, v01], axis=-1)
            buffer = self.ctx.buffer(triangles.astype("u4").tobytes())
            cache[tuple(grid)] = buffer
        return buffer

    def _lobe_program(self, model: Model, values, uniforms: dict) -> moderngl.Program:
        """The model's lobe program (its BRDF in the vertex stage), uniforms set."""
        resolved = model.resolve(values)
        enums = {k: v for k, v in resolved.items() if model.params[k].kind == "enum"}
        preamble = _lobe_common()
        key = (str(model.path), model.code, "lobe_mesh", tuple(sorted(enums.items())), preamble)
        program = self._programs.get(key)
        if program is None:
            _, source = self._assemble(model, "lobe_mesh", enums, preamble)
            fragment = glsl.vertex_source().split("\n", 1)[0] + "\n" + _view_text("lobe_mesh_shade")
            try:
                program = self.ctx.program(vertex_shader=source.text, fragment_shader=fragment)
            except moderngl.Error as err:
                log = str(err)
                raise glsl.ShaderCompileError(glsl.translate_log(log, source), log) from None
            self._programs[key] = program
            self._vaos[id(program)] = self.ctx.vertex_array(program, [])  # for forget()
        bind = getattr(model, "bind", None)
        data_uniforms = bind(self.ctx) if bind is not None else {}
        for name, value in {
            **glsl.uniform_values(model, resolved),
            **data_uniforms,
            **uniforms,
        }.items():
            if name in program:
                program[name].value = value
        return program

    def _lobe_lines(self, segments: list, common: dict, width: int, height: int, k: int):
        """Draw marks: faint where the lobe hides them, then in full where it does not."""
        program = self.__dict__.get("_lobe_line_program")
        if program is None:
            head = glsl.vertex_source().split("\n", 1)[0] + "\n"
            text = _view_text("lobe_mesh_lines")
            program = self.ctx.program(
                vertex_shader=head + "#define VERTEX\n" + _lobe_common() + "\n" + text,
                fragment_shader=head + text,
            )
            self._lobe_line_program = program
        segments = segments[:LOBE_MAX_SEGMENTS]
        pad = LOBE_MAX_SEGMENTS - len(segments)
        zero = [(0.0, 0.0, 0.0)] * pad
        uniforms = {
            **common,
            "u_viewport": (float(width), float(height)),
            "u_a": [tuple(map(float, s[0])) for s in segments] + zero,
            "u_b": [tuple(map(float, s[1])) for s in segments] + zero,
            "u_rgba": [tuple(map(float, s[2])) for s in segments] + [(0.0,) * 4] * pad,
            "u_style": [(s[3][0] * k, s[3][1] * k) for s in segments] + [(0.0, 0.0)] * pad,
        }
        for name, value in uniforms.items():
            if name in program:
                program[name].value = value
        vao = self.ctx.vertex_array(program, [])
        fbo = self.ctx.fbo
        try:
            fbo.depth_mask = False
            for func, fade in ((">", 0.3), ("<=", 1.0)):
                self.ctx.depth_func = func
                program["u_fade"].value = fade
                vao.render(moderngl.TRIANGLES, vertices=6 * len(segments))
        finally:
            vao.release()
            fbo.depth_mask = True


LOBE_BACKGROUND = (40, 40, 44)  # the desktop lab's background
LOBE_COLOR = (0.95, 0.55, 0.2)


def save_lobe3d(
    renderer,
    model: Model,
    values,
    theta: float,
    phi: float,
    out,
    width: int = 640,
    log: bool = False,
    cos_weighted: bool = False,
) -> None:
    """The 3D lobe drawn on the GPU by the model's GLSL (Renderer.lobe_mesh) with a caption
    and the normal, incident and mirror directions named."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    width = int(width)
    height = int(round(width * 0.75))
    camera = LobeCamera()
    background = tuple(c / 255.0 for c in LOBE_BACKGROUND)
    peak = renderer.lobe_peak(model, values, theta, phi, cos_weighted)
    image = renderer.lobe_mesh(
        [(model, values, LOBE_COLOR)],
        theta,
        phi,
        (width, height),
        camera,
        cos_weighted=cos_weighted,
        log=log,
        peaks=[peak],
        background=(*background, 1.0),
        supersample=2,
    )
    dpi = 100
    caption = 36
    fig = plt.figure(figsize=(width / dpi, (height + caption) / dpi), dpi=dpi)
    fig.patch.set_facecolor(background)
    ax = fig.add_axes((0.0, 0.0, 1.0, height / (height + caption)))
    ax.imshow(np.clip(image[..., :3], 0.0, 1.0), interpolation="none")
    ax.set_axis_off()
    ends = [direction(0.0, 0.0), direction(theta, phi), direction(theta, phi + 180.0)]
    points = camera.project(1.22 * np.array(ends), (width, height))
    for (x, y), name in zip(points, ("normal", "incident", "mirror"), strict=True):
        ax.text(x, y, name, color=LOBE_MARK_RGB[name], fontsize=9, ha="center", va="center")
    quantity = "f_r cos θo" if cos_weighted else "f_r"
    scale = ", log scale (3 decades)" if log else ""
    what = f"{model.name}: {quantity} for light from θi = {theta:g}°, φi = {phi:g}°{scale}"
    if model.delta:
        what += f"; the spike: reflectance {peak[1]:.3g}"
    fig.text(
        0.5,
        1.0 - 0.5 * caption / (height + caption),
        what,
        color="0.85",
        fontsize=10,
        ha="center",
        va="center",
    )
    fig.savefig(out, dpi=dpi, facecolor=fig.get_facecolor())
    plt.close(fig)


def plot(job: PlotJob) -> None:
    save_lobe3d(
        job.renderer,
        job.model,
        job.values,
        job.theta_i,
        job.phi_i,
        job.out,
        width=max(job.size, 320),
    )


VIEW = ViewSpec(
    name="lobe3d",
    title="3D lobe",
    settings={
        "lobe_yaw": Setting(-0.6, label="yaw"),
        "lobe_pitch": Setting(0.35, -1.5, 1.5, "pitch"),
        "lobe_zoom": Setting(1.0, 0.2, 8.0, "zoom"),
    },
    dock=("right", 1),
    short_title="Lobe",
    page_data={"grid": LOBE_GRID, "fast_grid": LOBE_FAST_GRID},
    size=(0.3, 0.42),
    widget="lab.app.views.lobe3d:LobeView",
    plot=plot,
    order=30,
)

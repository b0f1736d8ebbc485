"""Offscreen views of a model, rendered by its GLSL and returned as float32 arrays.

Every view runs the model's own `BRDF` function on the GPU: the sphere, the probe
(BRDF values for given direction pairs, from which the polar and 3D lobes are made),
the (theta_h, theta_d) slice and the directional albedo.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import moderngl
import numpy as np

from lab import glsl
from lab.brdf_explorer import ExplorerModel, glsl_version
from lab.brdf_explorer import assemble as assemble_explorer
from lab.constants import MAX_LIGHTS
from lab.geometry import direction, plane_of_incidence
from lab.gl import get_context
from lab.models import Model, Value
from lab.sources import as_model
from lab.views.lobe3d import (
    LOBE_FAST_GRID,
    LOBE_GRID,
    LOBE_MARK_RGB,
    LobeCamera,
    LobeMesh,
)

__all__ = [
    "LOBE_FAST_GRID",
    "LOBE_GRID",
    "LOBE_MARK_RGB",
    "Light",
    "LobeCamera",
    "Polar",
    "Renderer",
    "as_model",
    "light_uniforms",
    "direction",
    "plane_of_incidence",
]


@dataclass(frozen=True)
class Light:
    """A directional light: direction in degrees (theta from the view axis) and colour."""

    theta: float
    phi: float = 0.0
    rgb: tuple[float, float, float] = (1.0, 1.0, 1.0)


@dataclass
class Polar:
    """The lobe in the plane of incidence: theta_o in degrees, -90 (light side) to 90."""

    theta_o: np.ndarray
    values: np.ndarray  # (n, 3)
    theta_i: float
    spike: np.ndarray | None = None  # delta models: reflectance of the spike at theta_o = theta_i


def light_uniforms(lights: list[Light]) -> dict[str, list]:
    """`u_light_dir` and `u_light_rgb` for 1 to MAX_LIGHTS lights, padded with dark ones."""
    if not 1 <= len(lights) <= MAX_LIGHTS:
        raise ValueError(f"give 1 to {MAX_LIGHTS} lights, not {len(lights)}")
    pad = MAX_LIGHTS - len(lights)
    return {
        "u_light_dir": [tuple(direction(lt.theta, lt.phi)) for lt in lights]
        + [(0.0, 0.0, 1.0)] * pad,
        "u_light_rgb": [tuple(lt.rgb) for lt in lights] + [(0.0, 0.0, 0.0)] * pad,
    }


class Renderer(LobeMesh):
    """Renders views of models with one OpenGL context; programs are compiled once."""

    def __init__(self, ctx: moderngl.Context | None = None):
        self.ctx = ctx or get_context()
        self._programs: dict[tuple, moderngl.Program] = {}
        self._vaos: dict[int, moderngl.VertexArray] = {}
        self._targets: dict[tuple[int, int], moderngl.Framebuffer] = {}
        self._last: moderngl.Framebuffer | None = None  # the last full-screen view's target

    # -- plumbing -------------------------------------------------------------------------
    def program(
        self, model: Model, view: str, enums: dict | None = None, preamble: str = ""
    ) -> moderngl.Program:
        """The compiled program for `model` in `view`; raises ShaderCompileError."""
        enums = enums or {}
        key = (
            str(model.path),
            model.code,
            view,
            tuple(sorted(enums.items())),
            preamble,
            model.loop_limit,
        )
        program = self._programs.get(key)
        if program is None:
            vertex, source = self._assemble(model, view, enums, preamble)
            try:
                program = self.ctx.program(vertex_shader=vertex, fragment_shader=source.text)
            except moderngl.Error as err:
                log = str(err)
                raise glsl.ShaderCompileError(glsl.translate_log(log, source), log) from None
            self._programs[key] = program
            self._vaos[id(program)] = self.ctx.vertex_array(program, [])
        return program

    def _assemble(self, model: Model, view: str, enums: dict, preamble: str):
        """Vertex shader text and fragment Source for `model` in `view`.

        BRDF Explorer files were written for GLSL 4.10 and lean on its implicit int-to-float
        conversions, so they get the highest version the context offers.
        """
        if isinstance(model, ExplorerModel):
            version = glsl_version(self.ctx)
            source = assemble_explorer(model, view, version, preamble, enums)
            return f"#version {version} core\n" + glsl.VERTEX_SHADER, source
        source = glsl.assemble_fragment(model, view, preamble=preamble, enums=enums)
        return glsl.vertex_source(), source

    def target(self, width: int, height: int) -> moderngl.Framebuffer:
        fbo = self._targets.get((width, height))
        if fbo is None:
            texture = self.ctx.texture((width, height), 4, dtype="f4")
            flag = self.ctx.texture((width, height), 1, dtype="f4")  # the loop guard's output
            fbo = self.ctx.framebuffer(color_attachments=[texture, flag])
            self._targets[(width, height)] = fbo
        return fbo

    def loop_stop(self) -> tuple[int, int, int] | None:
        """After a full-screen view: (line, x, y) of a loop the guard stopped, else None.

        x, y is the first such pixel in GL order (row 0 at the bottom); the line is the
        model file's (lab.glsl.guard_loops)."""
        fbo = self._last
        if fbo is None:
            return None
        width, height = fbo.size
        data = np.frombuffer(fbo.read(components=1, dtype="f4", attachment=1), np.float32)
        hits = np.flatnonzero(data > 0.5)
        if hits.size == 0:
            return None
        first = int(hits[0])
        return int(round(float(data[first]))), first % width, first // width

    def _run(
        self, model: Model, view: str, values, size, uniforms: dict, preamble: str = ""
    ) -> moderngl.Framebuffer:
        resolved = model.resolve(values)
        enums = {k: v for k, v in resolved.items() if model.params[k].kind == "enum"}
        program = self.program(model, view, enums, preamble)
        # A model that carries data (lab.measured's table) binds its textures here.
        bind = getattr(model, "bind", None)
        data_uniforms = bind(self.ctx) if bind is not None else {}
        uniforms = {**glsl.uniform_values(model, resolved), **data_uniforms, **uniforms}
        for name, value in uniforms.items():
            if name in program:  # the driver drops uniforms the code never reads
                uniform = program[name]
                if isinstance(value, list):  # arrays may be trimmed to what the code reads
                    value = value[: uniform.array_length]
                    value = value[0] if uniform.array_length == 1 else value
                uniform.value = value
        fbo = self.target(*size)
        fbo.use()  # no clear: the triangle covers every pixel
        self._vaos[id(program)].render(moderngl.TRIANGLES, vertices=3)
        self._last = fbo
        return fbo

    @staticmethod
    def _read(fbo: moderngl.Framebuffer) -> np.ndarray:
        width, height = fbo.size
        data = np.frombuffer(fbo.read(components=4, dtype="f4"), dtype=np.float32)
        return data.reshape(height, width, 4)

    # -- views ----------------------------------------------------------------------------
    def sphere(
        self,
        model: Model | str,
        values: dict[str, Value] | None = None,
        light: tuple[float, float] = (45.0, 0.0),
        size: int = 512,
        multiply_cos: bool = True,
        lights: list[Light] | None = None,
        ambient: tuple[float, float, float] = (0.0, 0.0, 0.0),
        readback: bool = True,
    ) -> np.ndarray | None:
        """Lit sphere, (size, size, 4) RGBA float32 radiance, row 0 at the top.

        Light directions are in camera space: theta = 0 is a light at the eye.
        Alpha is 1 on the sphere and 0 on the background.
        """
        model = as_model(model)
        lights = lights if lights is not None else [Light(*light)]
        uniforms = {
            **light_uniforms(lights),
            "u_resolution": (float(size), float(size)),
            "u_ambient": tuple(ambient),
            "u_multiply_cos": multiply_cos,
        }
        preamble = f"const int LIGHT_COUNT = {len(lights)};"
        if not readback:
            self._run(model, "sphere", values, (size, size), uniforms, preamble)
            self.ctx.finish()
            return None
        return self.image(model, "sphere", values, size, uniforms, preamble)

    def image(
        self, model: Model, view: str, values, size: int, uniforms: dict, preamble: str = ""
    ) -> np.ndarray:
        """A square image view drawn in one full-screen pass (the sphere, the grader's and the
        app's own templates): (size, size, 4) float32, row 0 at the top."""
        fbo = self._run(as_model(model), view, values, (size, size), uniforms, preamble)
        return self._read(fbo)[::-1].copy()

    def _probe(self, model: Model | str, values, view: str, inputs: list[np.ndarray]) -> np.ndarray:
        """Run a probe view over n texels; `inputs` are (n, k<=4) arrays, one texture each."""
        model = as_model(model)
        n = len(inputs[0])
        if n == 0:
            return np.zeros((0, 3), np.float32)
        width = min(n, 1024)
        height = math.ceil(n / width)
        textures, uniforms = [], {}
        for unit, data in enumerate(inputs):
            padded = np.zeros((width * height, 4), np.float32)
            padded[:n, : data.shape[1]] = data
            texture = self.ctx.texture((width, height), 4, padded, dtype="f4")
            texture.filter = (moderngl.NEAREST, moderngl.NEAREST)
            texture.use(unit)
            textures.append(texture)
        uniforms = {"u_L": 0, "u_V": 1} if view == "probe" else {"u_angles": 0}
        try:
            fbo = self._run(model, view, values, (width, height), uniforms)
            return self._read(fbo).reshape(-1, 4)[:n, :3].copy()
        finally:
            for texture in textures:
                texture.release()

    def probe(self, model: Model | str, values, L: np.ndarray, V: np.ndarray) -> np.ndarray:
        """f_r (n, 3) for direction pairs L, V (n, 3) in the local frame N = z."""
        L = np.asarray(L, dtype=np.float32).reshape(-1, 3)
        V = np.asarray(V, dtype=np.float32).reshape(-1, 3)
        return self._probe(model, values, "probe", [L, V])

    def eval_angles(self, model: Model | str, values, angles_deg: np.ndarray) -> np.ndarray:
        """f_r for rows (theta_i, phi_i, theta_o, phi_o) in degrees (directions made on the GPU)."""
        radians = np.radians(np.asarray(angles_deg, dtype=np.float64).reshape(-1, 4))
        return self._probe(model, values, "probe_angles", [radians.astype(np.float32)])

    def polar(
        self, model: Model | str, values, theta_i: float, phi_i: float = 0.0, cos_weighted=False
    ) -> Polar:
        """The lobe in the plane of incidence, theta_o from -90 to 90 deg in 1 deg steps."""
        model = as_model(model)
        theta_o, V = plane_of_incidence(theta_i, phi_i)
        L = np.repeat(direction(theta_i, phi_i)[None], len(V), axis=0)
        f = self.probe(model, values, L, V)
        if cos_weighted:
            f = f * np.maximum(V[:, 2:3], 0.0).astype(np.float32)
        spike = None
        if model.delta:
            spike = self.delta_reflectance(model, values, theta_i, phi_i)
        return Polar(theta_o, f, theta_i, spike)

    def delta_reflectance(self, model: Model, values, theta_i: float, phi_i: float = 0.0):
        """Reflectance of a delta model's spike for light from (theta_i, phi_i)."""
        # An albedo row with every sample below the horizon leaves only the delta's share.
        return self.albedo(model, values, [theta_i], phi_i, samples=1, wedges=1, only_delta=True)[0]

    def lobe3d(
        self,
        model: Model | str,
        values,
        theta_i: float,
        phi_i: float = 0.0,
        n_theta: int = 46,
        n_phi: int = 121,
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """f_r on a hemisphere grid: theta_o, phi_o (degrees) and values (n_theta, n_phi, 3)."""
        theta_o = np.linspace(0.0, 90.0, n_theta)
        phi_o = np.linspace(0.0, 360.0, n_phi)
        tt, pp = np.meshgrid(theta_o, phi_o, indexing="ij")
        V = direction(tt.ravel(), pp.ravel())
        L = np.repeat(direction(theta_i, phi_i)[None], len(V), axis=0)
        f = self.probe(model, values, L, V)
        return theta_o, phi_o, f.reshape(n_theta, n_phi, 3)

    def slice(self, model: Model | str, values, phi_d: float = 90.0, size: int = 256) -> np.ndarray:
        """f_r (size, size, 3) over theta_h (columns, 0..90 deg) and theta_d (rows, 90..0 deg)."""
        model = as_model(model)
        uniforms = {"u_resolution": (float(size), float(size)), "u_phi_d": math.radians(phi_d)}
        fbo = self._run(model, "slice", values, (size, size), uniforms)
        return self._read(fbo)[::-1, :, :3].copy()

    def albedo(
        self,
        model: Model | str,
        values,
        thetas_deg,
        phi_i: float = 0.0,
        samples: int = 256,
        wedges: int = 64,
        only_delta: bool = False,
    ) -> np.ndarray:
        """Directional albedo (n, 3) at theta_i (degrees), one pass when evenly spaced."""
        model = as_model(model)
        thetas = np.asarray(thetas_deg, dtype=np.float64).ravel()
        step = float(thetas[1] - thetas[0]) if len(thetas) > 1 else 0.0
        if len(thetas) > 2 and not np.allclose(np.diff(thetas), step):
            return np.concatenate(
                [
                    self.albedo(model, values, [t], phi_i, samples, wedges, only_delta)
                    for t in thetas
                ]
            )
        uniforms = {
            "u_theta0": math.radians(thetas[0]),
            "u_theta_step": math.radians(step),
            "u_phi_i": math.radians(phi_i),
            "u_samples": 0 if only_delta else samples,
            "u_wedges": wedges,
        }
        fbo = self._run(model, "albedo", values, (wedges, len(thetas)), uniforms)
        return self._read(fbo)[:, :, :3].sum(axis=1, dtype=np.float64)

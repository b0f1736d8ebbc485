"""The app's renderer: the core Renderer plus the procedural object view."""

from __future__ import annotations

import re

import numpy as np

from lab import glsl
from lab.constants import MAX_LIGHTS
from lab.models import Model
from lab.render import Light, Renderer, light_uniforms
from lab.views.object import MODES, SHAPES

__all__ = ["MODES", "SHAPES", "AppRenderer"]

UNIFORM_LINE = re.compile(r"^uniform (float|vec3) ([A-Za-z_]\w*);$")


def spatially_varying(source: glsl.Source, model: Model) -> None:
    """Turn float/colour parameter uniforms into per-pixel globals and add `sv_assign`.

    The procedural maps of the object view then drive the model's own parameters: the
    albedo map scales the first colour, the variation map moves every log-scaled float
    toward the far end of its range (rougher or smoother, whichever is farther).
    """
    for index, (label, _) in enumerate(source.origins):
        if label.endswith("(parameters)"):
            match = UNIFORM_LINE.match(source.lines[index])
            if match:
                kind, name = match.groups()
                source.lines[index] = f"uniform {kind} {name}_base; {kind} {name};"
    body = []
    first_color = True
    for p in model.params.values():
        if p.kind == "color":
            scale = " * sv_albedo" if first_color else ""
            first_color = False
            body.append(f"    {p.name} = {p.name}_base{scale};")
        elif p.kind == "float" and p.scale == "log":
            limits = f"{p.minimum:.9g}, {p.maximum:.9g}"
            body.append(f"    {p.name} = sv_vary({p.name}_base, {limits}, sv_amount);")
        elif p.kind == "float":
            body.append(f"    {p.name} = {p.name}_base;")
    source.add(
        "float sv_vary(float base, float lo, float hi, float t) {\n"
        "    float a = log(base);\n"
        "    float far_end = (a - log(lo) > log(hi) - a) ? log(lo) : log(hi);\n"
        "    return exp(mix(a, far_end, 0.75 * t));\n"
        "}\n"
        "void sv_assign(float sv_amount, vec3 sv_albedo) {\n" + "\n".join(body) + "\n}",
        "<host: spatially varying parameters>",
    )


class AppRenderer(Renderer):
    """Adds the `object` view, whose parameters vary over the surface."""

    def _assemble(self, model: Model, view: str, enums: dict, preamble: str):
        vertex, source = super()._assemble(model, view, enums, preamble)
        if view == "object":
            spatially_varying(source, model)
        return vertex, source

    def forget(self, model: Model) -> None:
        """Release the programs compiled for an older version of a model file."""
        for key in [k for k in self._programs if k[0] == str(model.path) and k[1] != model.code]:
            program = self._programs.pop(key)
            self._vaos.pop(id(program)).release()
            program.release()

    def object(
        self,
        model: Model,
        values,
        lights: list[Light],
        ambient=(0.0, 0.0, 0.0),
        shape: int = 0,
        mode: int = 1,
        yaw: float = 0.5,
        pitch: float = 0.5,
        size: int = 384,
    ) -> np.ndarray:
        """The procedural object lit by `lights` (camera space), (size, size, 4) float32."""
        resolved = model.resolve(values)
        lights = lights[:MAX_LIGHTS] or [Light(45.0, 0.0)]
        uniforms = {
            f"{name}_base": value
            for name, value in glsl.uniform_values(model, resolved).items()
            if model.params[name].kind in ("float", "color")
        }
        uniforms.update(
            {
                **light_uniforms(lights),
                "u_resolution": (float(size), float(size)),
                "u_ambient": tuple(ambient),
                "u_shape": int(shape),
                "u_mode": int(mode),
                "u_yaw": float(yaw),
                "u_pitch": float(pitch),
            }
        )
        preamble = f"const int LIGHT_COUNT = {len(lights)};"
        return self.image(model, "object", resolved, size, uniforms, preamble)

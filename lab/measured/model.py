"""The `measured` model: a tabulated BRDF rendered in every view through a 3D texture.

The GLSL lives in measured.glsl beside this file (a model file with the usual header).
It is not in shaders/brdfs because it needs data: a MeasuredModel carries its table and
binds it as a texture whenever the Renderer draws it (Renderer._run calls `bind`).
"""

from __future__ import annotations

from dataclasses import dataclass, field, fields, make_dataclass
from pathlib import Path
from typing import Any

import moderngl
import numpy as np

from lab.measured.merl import TABLE_UNIFORM, MerlTable, read_merl
from lab.models import Model, ModelError, load_model

MODEL_FILE = Path(__file__).resolve().parent / "measured.glsl"
# Texture unit of the table: above the units the views use for their own inputs (probe: 0, 1).
TABLE_UNIT = 7


@dataclass
class MeasuredModel(Model):
    """The measured model with its table; `bind(ctx)` uploads it (once) and binds it."""

    table: MerlTable | None = None
    _textures: dict = field(default_factory=dict, repr=False)

    @property
    def no_terms_reason(self) -> str:
        """What the D, G, F view says of a table (not: define MICROFACET_TERMS)."""
        path = self.table.path if self.table is not None else None
        name = str(path) if path else "TABLE.binary"
        return (
            f"{name}: a measured table has no D, G and F of its own: fit a microfacet model "
            f"to it ('brdf-lab fit {name} --model ggx' writes a preset) and view the fit's terms"
        )

    def texture(self, ctx: moderngl.Context) -> moderngl.Texture3D:
        """The table as an RGB float texture (n_p, n_d, n_h) in `ctx`, made once per context."""
        if self.table is None:
            raise ValueError("the measured model has no table: use measured_model(table)")
        texture = self._textures.get(id(ctx))
        if texture is None:
            n_h, n_d, n_p = self.table.dims
            limit = int(ctx.info.get("GL_MAX_3D_TEXTURE_SIZE", 256))
            if max(n_h, n_d, n_p) > limit:
                raise ModelError(
                    f"the table has {self.table.dims} bins; this OpenGL takes at "
                    f"most {limit} per axis of a 3D texture: resample it",
                    self.table.path or "table",
                )
            # Unmeasured (negative) entries become 0 here, so filtering never blends them in.
            texels = np.ascontiguousarray(np.maximum(self.table.rgb, 0.0), dtype=np.float32)
            try:
                texture = ctx.texture3d((n_p, n_d, n_h), 3, texels.tobytes(), dtype="f4")
            except moderngl.Error as err:
                raise ModelError(
                    f"cannot upload the table as a texture ({err})", self.table.path or "table"
                ) from None
            # The linear choice uses the texture unit's trilinear filter: phi_d is periodic,
            # the theta axes clamp at their edges. The nearest choice fetches texels itself.
            texture.filter = (moderngl.LINEAR, moderngl.LINEAR)
            texture.repeat_x = True
            texture.repeat_y = False
            texture.repeat_z = False
            self._textures[id(ctx)] = texture
        return texture

    def bind(self, ctx: moderngl.Context) -> dict[str, object]:
        """Bind the table before a draw; returns the uniforms that point the shader at it."""
        self.texture(ctx).use(TABLE_UNIT)
        return {"u_measured": TABLE_UNIT}

    def release(self) -> None:
        for texture in self._textures.values():
            texture.release()
        self._textures.clear()


def measured_model(table: MerlTable | str | Path) -> MeasuredModel:
    """The `measured` model for a table (or the path of a .binary file)."""
    if not isinstance(table, MerlTable):
        table = read_merl(table)
    base = load_model(MODEL_FILE)
    fields = {name: getattr(base, name) for name in Model.__dataclass_fields__}
    return MeasuredModel(**fields, table=table)


# -- any model that reads a table: the measured model's texture bound to its sampler -------


def _bind_table(self, ctx: moderngl.Context) -> dict[str, object]:
    """Bind the table (and whatever the model binds itself) before a draw."""
    inner = getattr(super(type(self), self), "bind", None)
    uniforms = dict(inner(ctx)) if inner is not None else {}
    self.table_source.texture(ctx).use(TABLE_UNIT)
    return {**uniforms, self.table_uniform: TABLE_UNIT}


_TABLED: dict[type, type] = {}


def _tabled_class(cls: type) -> type:
    """A subclass of the model's class that also binds a table (dataclasses.replace keeps
    it, so copies of the model, such as the grader's instrumented ones, read it too)."""
    if cls not in _TABLED:
        _TABLED[cls] = make_dataclass(
            f"Tabled{cls.__name__}",
            [("table_source", Any, None), ("table_uniform", str, TABLE_UNIFORM)],
            bases=(cls,),
            namespace={"bind": _bind_table},
        )
    return _TABLED[cls]


def with_table(model: Model, source: MeasuredModel, uniform: str = TABLE_UNIFORM) -> Model:
    """`model` reading `source`'s table through its `uniform highp sampler3D <uniform>;`."""
    base = type(model)
    if base in _TABLED.values():
        if model.table_source is source and model.table_uniform == uniform:
            return model
        base = base.__mro__[1]
    values = {f.name: getattr(model, f.name) for f in fields(base) if f.init}
    return _tabled_class(base)(**values, table_source=source, table_uniform=uniform)

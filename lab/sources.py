"""One way to open a model, whatever the user names: every front end calls `open_model`.

- a library name (`phong`), or a `.glsl` model file;
- a BRDF Explorer `.brdf` file;
- a MERL `.binary` table, opened as the `measured` model (`table=` gives the table
  separately, as `render measured --table FILE.binary` does); with a model file that
  declares `uniform highp sampler3D u_table;` (exercise 12's lookup), the table is bound
  to it.
"""

from __future__ import annotations

import re
from pathlib import Path

from lab.models import Model, ModelError, load_model

MEASURED = "measured"  # the model that reads a measured table


def open_model(spec: str | Path, table: str | Path | None = None) -> Model:
    """The model `spec` names; `table` is the data file of the measured model."""
    text = str(spec)
    if table is not None and text != MEASURED:
        return _reading_table(spec, table)
    if table is not None or text == MEASURED:
        if table is None:
            raise ModelError(
                "the measured model needs its data: open a MERL .binary table "
                "(make one with 'brdf-lab tabulate MODEL -o FILE.binary')"
            )
        return _measured(table)
    if text.endswith(".brdf"):
        from lab.brdf_explorer import read_brdf  # BRDF Explorer's file format

        return read_brdf(spec)
    if text.endswith(".binary"):
        return _measured(spec)
    return load_model(spec)


def as_model(model: Model | str | Path) -> Model:
    """`model` itself, or the model a name or file opens."""
    return model if isinstance(model, Model) else open_model(model)


def open_with_settings(spec: str | Path, settings: list[str] | None) -> tuple[Model, dict]:
    """The model `spec` names and its values from `NAME=VALUE` strings (e.g. `--set`)."""
    model = open_model(spec)
    return model, model.parse_settings(settings or [])


def _reading_table(spec: str | Path, table: str | Path) -> Model:
    """A model file that declares the table's sampler (exercise 12's lookup), bound to it."""
    from lab.measured.merl import TABLE_UNIFORM

    model = load_model(spec)
    if not re.search(rf"\buniform\s+(?:highp\s+)?sampler3D\s+{TABLE_UNIFORM}\s*;", model.code):
        raise ModelError(
            f"a table is for the measured model, or for a model file that declares "
            f"'uniform highp sampler3D {TABLE_UNIFORM};': open {MEASURED!r} with it, "
            f"not {str(spec)!r}"
        )
    from lab.measured.model import with_table

    return with_table(model, _measured(table))


def _measured(table: str | Path) -> Model:
    if not Path(table).is_file():
        raise ModelError(
            f"{table}: no such file (make one with 'brdf-lab tabulate MODEL -o {table}')"
        )
    from lab.measured.model import measured_model  # numpy tables: loaded only when used

    return measured_model(table)

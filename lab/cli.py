"""The `brdf-lab` command line."""

from __future__ import annotations

import argparse
import csv
import importlib
import os
import sys
import traceback
from pathlib import Path

from lab import __version__, views
from lab.errors import UsageError, check_output, parse_light, parse_pair, parse_rgb
from lab.models import MODEL_DIR, ModelError
from lab.resources import ResourceError, install_line

# Packages of the whole lab that the lean (grading) install leaves out: lab/requirements-app.txt.
APP_MODULES = {"PyQt6", "pyqtgraph", "glfw", "matplotlib", "scipy"}

__all__ = ["UsageError", "check_output", "main", "parse_light", "parse_pair", "parse_rgb"]

# Feature packages add their own sub-commands through a `register(subparsers)` function.
FEATURE_CLIS = [
    "lab.app.cli",
    "lab.grading.cli",
    "lab.grading.course",
    "lab.web.cli",
    "lab.measured.cli",
    "lab.ibl.cli",
]
MAX_SIZE = 4096  # pixels per side: a 4096² float image is 256 MiB already


def feature_present(module_name: str) -> bool:
    """Whether a feature package's CLI module is part of this checkout."""
    relative = Path(*module_name.split(".")[1:]).with_suffix(".py")
    return (Path(__file__).parent / relative).is_file()


def parse_scene_light(text: str):
    """`THETA,PHI` or `THETA,PHI,R,G,B`: a directional light for the sphere view."""
    from lab.render import Light

    parts = text.split(",")
    if len(parts) not in (2, 3, 5):
        raise UsageError(f"--light {text!r} is malformed: write THETA,PHI or THETA,PHI,R,G,B")
    theta, phi = parse_light(",".join(parts[:2]))
    rgb = parse_rgb(",".join(parts[2:]), "--light colour") if len(parts) > 2 else (1.0, 1.0, 1.0)
    return Light(theta, phi, rgb)


def load_any_model(args):
    """The model and values of a command's MODEL, --set and --table arguments."""
    if args.model == "measured" or args.table:
        return load_measured(args.model, args.table, args.set, args.command)
    from lab.sources import open_with_settings

    return open_with_settings(args.model, args.set)


def load_measured(name: str, table: str | None, settings: list[str], command: str = "render"):
    """The `measured` model for `render/eval measured --table FILE.binary` (lab.measured)."""
    if name != "measured" and not (table and name.endswith(".glsl")):
        raise UsageError(
            f"--table is for the measured model (or a .glsl file that declares "
            f"'uniform highp sampler3D u_table;'): write "
            f"'brdf-lab {command} measured --table {table}', not {name!r}"
        )
    if not table:
        raise UsageError(
            "the measured model needs its data: add --table FILE.binary "
            "(make one with 'brdf-lab tabulate MODEL -o FILE.binary')"
        )
    if not Path(table).is_file():
        raise UsageError(
            f"{table}: no such file (make one with 'brdf-lab tabulate MODEL -o {table}')"
        )
    from lab.models import ModelError
    from lab.sources import open_model

    try:
        model = open_model(name, table)
    except ModelError as err:
        raise UsageError(str(err)) from None
    return model, model.parse_settings(settings or [])


# -- commands -------------------------------------------------------------------------------
def cmd_models(args) -> int:
    from lab.glsl import label_of
    from lab.measured.model import MODEL_FILE
    from lab.models import load_model, model_names, parse_model

    models = [load_model(name) for name in model_names()]
    models.append(parse_model(MODEL_FILE.read_text(encoding="utf-8"), MODEL_FILE))
    for model in models:
        kind = "  (delta)" if model.delta else ""
        if model.name == "measured":
            kind = "  (its data: --table FILE.binary)"
        print(f"{model.name}{kind}  -  {model.title}\n  file: {label_of(model.path)}")
        for p in model.params.values():
            if p.kind == "float":
                spec = f"float [{p.minimum:g}, {p.maximum:g}] default {p.default:g} ({p.scale})"
            elif p.kind == "color":
                spec = "color default " + ",".join(f"{c:g}" for c in p.default)
            elif p.kind == "bool":
                spec = f"bool default {int(p.default)}"
            else:
                spec = f"enum {'|'.join(p.choices)} default {p.default}"
            print(f"    {p.name:13s} {spec}  -  {p.doc}")
    return 0


def cmd_render(args) -> int:
    from lab.constants import MAX_LIGHTS
    from lab.render import Renderer

    model, values = load_any_model(args)
    lights = [parse_scene_light(text) for text in args.light or ["45,0"]]
    if len(lights) > MAX_LIGHTS:
        raise UsageError(f"at most {MAX_LIGHTS} --light options")
    ambient = parse_rgb(args.ambient, "--ambient")
    if not 8 <= args.size <= MAX_SIZE:
        raise UsageError(f"--size {args.size} is outside 8..{MAX_SIZE} pixels")
    out = check_output(args.output, ".png")
    job = views.PlotJob(
        Renderer(), model, values, lights[0].theta, lights[0].phi, out, args.size, args.exposure
    )
    job.lights, job.ambient = lights, ambient
    job.ibl = {"env": args.env, "strategy": args.strategy, "samples": args.samples}
    job.ibl["rotation"] = args.rotate
    job.ibl["shape"] = args.shape
    views.view(args.view).plot(job)
    print(f"wrote {out}")
    for warning in job.warnings:
        print(f"brdf-lab: warning: {model.name}: {warning}", file=sys.stderr)
    return 0


def read_pairs(path: str):
    import numpy as np

    required = ["theta_i", "phi_i", "theta_o", "phi_o"]
    try:
        handle = open(path, newline="", encoding="utf-8-sig")  # tolerate Excel's BOM
    except OSError as err:
        raise UsageError(f"cannot read {path}: {err.strerror}") from None
    with handle:
        reader = csv.reader(handle)
        header = [h.strip() for h in next(reader, [])]
        missing = [c for c in required if c not in header]
        if missing:
            raise UsageError(
                f"{path}:1: missing column(s) {', '.join(missing)}: the header must be "
                "theta_i,phi_i,theta_o,phi_o (degrees)"
            )
        columns = [header.index(c) for c in required]
        rows = []
        for number, row in enumerate(reader, start=2):
            if not any(cell.strip() for cell in row):
                continue
            try:
                rows.append([float(row[c]) for c in columns])
            except (ValueError, IndexError):
                raise UsageError(
                    f"{path}:{number}: expected four numbers, got {','.join(row)!r}"
                ) from None
    angles = np.array(rows, dtype=np.float64).reshape(-1, 4)
    if not np.isfinite(angles).all():
        bad = int(np.argwhere(~np.isfinite(angles))[0][0]) + 2
        raise UsageError(f"{path}:{bad}: angles must be finite numbers")
    return angles


def cmd_eval(args) -> int:
    import numpy as np

    model, values = load_any_model(args)
    angles = read_pairs(args.input)
    out = check_output(args.output) if args.output else None
    if model.delta:
        print(
            f"note: {model.name} is an ideal specular (delta) BRDF; its value is 0 off the "
            "mirror direction and infinite on it, so eval returns 0.",
            file=sys.stderr,
        )
    if args.cpu:
        from lab import reference

        if model.name not in reference.MODELS or model.path.parent != MODEL_DIR:
            raise UsageError(
                f"--cpu: the numpy reference knows only the library models "
                f"({', '.join(reference.MODELS)}); drop --cpu to evaluate {model.path} on the GPU"
            )
        result = reference.brdf_angles(model.name, values, angles)
    else:
        from lab.render import Renderer

        result = Renderer().eval_angles(model, values, angles)
    result = np.asarray(result, dtype=np.float64)
    handle = open(out, "w", newline="", encoding="utf-8") if out else sys.stdout
    try:
        writer = csv.writer(handle)
        writer.writerow(["r", "g", "b"])
        writer.writerows([[repr(float(v)) for v in row] for row in result])
    finally:
        if out:
            handle.close()
            print(f"wrote {len(result)} rows to {out}", file=sys.stderr)
    return 0


def cmd_figures(args) -> int:
    from lab import figures

    outdir = Path(args.outdir)
    try:
        outdir.mkdir(parents=True, exist_ok=True)
    except OSError as err:
        raise UsageError(f"cannot create {outdir}: {err.strerror}") from None
    for path in figures.lecture_figures(outdir):
        print(f"wrote {path}")
    return 0


def cmd_gallery(args) -> int:
    from lab import figures

    outdir = Path(args.outdir)
    outdir.mkdir(parents=True, exist_ok=True)
    path = figures.gallery(outdir)
    print(f"wrote the gallery of every model to {path.resolve()}")
    return 0


def cmd_bench(args) -> int:
    from lab import bench

    bench.run(quick=args.quick)
    return 0


def build_parser(features: list[str] = FEATURE_CLIS) -> argparse.ArgumentParser:
    """The `brdf-lab` parser with the sub-commands of `features` (their lab.*.cli modules)."""
    parser = argparse.ArgumentParser(
        prog="brdf-lab", description="A teaching lab for BRDFs: one GLSL shader per model."
    )
    parser.add_argument("--version", action="version", version=f"brdf-lab {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")

    p = sub.add_parser("models", help="list the models, their parameters and files")
    p.set_defaults(func=cmd_models)

    p = sub.add_parser("render", help="render a view of a model to PNG")
    p.add_argument("model", help="model name (see 'brdf-lab models') or a .glsl file")
    p.add_argument("--set", action="append", metavar="NAME=VALUE", help="parameter value")
    p.add_argument(
        "--light",
        action="append",
        metavar="THETA,PHI[,R,G,B]",
        help="light direction (deg) and colour; repeat for several lights (sphere view; the "
        "plots use the first); default 45,0",
    )
    p.add_argument(
        "--ambient",
        default="0",
        metavar="R,G,B",
        help="ambient light L_a (sphere view; the Phong illumination model reflects ka L_a)",
    )
    p.add_argument("--view", choices=views.plot_views(), default="sphere")
    p.add_argument(
        "--size",
        type=int,
        default=512,
        help="image size in pixels (the sphere's side; a plot's width, at least 320)",
    )
    p.add_argument("--exposure", type=float, default=0.0, help="exposure in stops (sphere)")
    p.add_argument("--table", metavar="FILE.binary", help="the MERL table of the 'measured' model")
    p.add_argument(
        "--env",
        default="sky",
        metavar="NAME|FILE",
        help="ibl view: sky, furnace, studio, grey_room or an equirectangular .hdr/.exr file",
    )
    p.add_argument(
        "--strategy",
        default="auto",
        help="ibl view: how directions are drawn (auto: BRDF sampling under an even map, else MIS)",
    )
    p.add_argument("--samples", type=int, default=256, help="ibl view: samples per pixel")
    p.add_argument("--rotate", type=float, default=0.0, help="ibl view: environment turn (deg)")
    p.add_argument(
        "--shape",
        default="sphere",
        help="ibl view: light the object view's torus, 'rounded box' or 'bumpy sphere' instead",
    )
    p.add_argument("-o", "--output", required=True, metavar="OUT.png")
    p.set_defaults(func=cmd_render)

    p = sub.add_parser("eval", help="BRDF values for direction pairs from a CSV file")
    p.add_argument("model")
    p.add_argument("--set", action="append", metavar="NAME=VALUE")
    p.add_argument("--in", dest="input", required=True, metavar="PAIRS.csv")
    p.add_argument("--out", dest="output", metavar="VALUES.csv")
    p.add_argument("--cpu", action="store_true", help="use the numpy reference, not the GPU")
    p.add_argument("--table", metavar="FILE.binary", help="the data of the measured model")
    p.set_defaults(func=cmd_eval)

    p = sub.add_parser("figures", help="render the lecture's figures from the real shaders")
    p.add_argument("outdir")
    p.set_defaults(func=cmd_figures)

    p = sub.add_parser("gallery", help="render every model (sphere and polar lobe) to a folder")
    p.add_argument("outdir", nargs="?", default="out/gallery")
    p.set_defaults(func=cmd_gallery)

    p = sub.add_parser("bench", help="print rendering benchmarks")
    p.add_argument("--quick", action="store_true", help="fewer repetitions")
    p.set_defaults(func=cmd_bench)

    for module_name in features:
        if feature_present(module_name):
            importlib.import_module(module_name).register(sub)
    return parser


def main(argv: list[str] | None = None) -> int:
    from lab.gl import GLUnavailable
    from lab.glsl import ShaderCompileError

    argv = sys.argv[1:] if argv is None else list(argv)
    # Launching the desktop lab (also the default command) needs only its own sub-command:
    # the other features' CLIs (grading, web, ...) are not imported before its first frame.
    app_only = (not argv or argv[0] == "app") and feature_present("lab.app.cli")
    parser = build_parser(["lab.app.cli"] if app_only else FEATURE_CLIS)
    args = parser.parse_args(argv)
    if not getattr(args, "func", None):
        if feature_present("lab.app.cli"):
            args = parser.parse_args(["app", *argv])
        else:
            args = parser.parse_args(["gallery"])
    try:
        return args.func(args)
    except (UsageError, ModelError, GLUnavailable, ResourceError) as err:
        print(f"brdf-lab: error: {err}", file=sys.stderr)
        return 2
    except ShaderCompileError as err:
        first, *more = str(err).splitlines() or [""]
        print(f"brdf-lab: error: the shader does not compile: {first}", file=sys.stderr)
        for line in more:
            print(f"  {line}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        return 130
    except Exception as err:  # a bug or a broken driver: one line, the trace on request
        if isinstance(err, ModuleNotFoundError) and (err.name or "").split(".")[0] in APP_MODULES:
            print(
                f"brdf-lab: error: '{args.command}' needs {err.name}, which the lean install of "
                f'brdf-lab leaves out: install the whole lab with pip install "{install_line()}"',
                file=sys.stderr,
            )
            return 2
        if os.environ.get("BRDF_LAB_DEBUG"):
            raise
        where = traceback.extract_tb(err.__traceback__)[-1]
        place = f"{Path(where.filename).name}:{where.lineno}"
        print(
            f"brdf-lab: internal error: {type(err).__name__}: {err} (at {place}); run again "
            "with BRDF_LAB_DEBUG=1 for the full trace and report it",
            file=sys.stderr,
        )
        return 3


if __name__ == "__main__":
    sys.exit(main())

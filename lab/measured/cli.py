"""Sub-commands of `brdf-lab` for measured BRDFs: tabulate, fit, sh, render-measured,
measured-bench."""

from __future__ import annotations

import sys
from pathlib import Path

FIT_MODELS = ("ward", "blinn_phong", "cook_torrance", "ggx")


def _usage(message: str):
    from lab.errors import UsageError

    return UsageError(message)


def _dims(text: str) -> tuple[int, int, int]:
    try:
        dims = tuple(int(x) for x in text.split(","))
    except ValueError:
        dims = ()
    if len(dims) != 3 or any(n < 1 or n > 1024 for n in dims):
        raise _usage(
            f"--dims {text!r} is malformed: write N_THETA_H,N_THETA_D,N_PHI_D "
            "(each 1..1024), e.g. 90,90,180"
        )
    return dims  # type: ignore[return-value]


def _read(path: str):
    from lab.measured.merl import read_merl

    if not Path(path).exists():
        raise _usage(f"{path}: no such file (make one with 'brdf-lab tabulate MODEL -o {path}')")
    return read_merl(path)


def cmd_tabulate(args) -> int:
    from lab.errors import check_output
    from lab.measured.merl import write_merl
    from lab.measured.tabulate import tabulate
    from lab.sources import open_with_settings

    model, values = open_with_settings(args.model, args.set)
    if model.delta:
        raise _usage(f"{model.name} is an ideal mirror (a delta): it has no finite table")
    if not args.noise >= 0:
        raise _usage(f"--noise {args.noise:g} must be a sigma >= 0 (e.g. 0.05 for 5 %)")
    out = check_output(args.output)
    table = tabulate(model, values, _dims(args.dims), args.noise, args.seed)
    write_merl(table, out)
    bins = "x".join(map(str, table.dims))
    print(f"wrote {out} ({model.name}, {bins} bins, noise {args.noise:g})")
    return 0


def _write_preset(result, table: str, path: Path) -> None:
    """The fit and the table as a preset (TOML) the desktop lab opens."""
    from lab.presets import write_preset

    data = result.preset(table, path.parent)
    write_preset(data, path, f"brdf-lab fit: open with 'brdf-lab app --preset {path.name}'")


def cmd_fit(args) -> int:
    from lab.measured import fit as fitting
    from lab.measured.figures import fit_figure

    table = _read(args.table)
    models = list(fitting.FIT_MODELS) if args.compare else (args.model or ["cook_torrance"])
    outdir = Path(args.outdir)
    try:
        outdir.mkdir(parents=True, exist_ok=True)
    except OSError as err:
        raise _usage(f"--outdir {outdir}: cannot create the folder ({err.strerror})") from None
    evaluate = fitting.gpu_evaluator() if args.gpu else fitting.cpu_evaluate
    samples = fitting.select_samples(table, args.samples)
    stem = Path(args.table).stem
    results = []
    for name in models:
        result = fitting.fit(samples, name, args.lobes, args.metric, evaluate=evaluate)
        results.append(result)
        print(
            f"{name} ({args.lobes} lobe(s)): error {result.error:.5g} ({args.metric}), "
            f"{result.seconds:.1f} s, {result.evaluations} evaluations"
        )
        for k, values in enumerate(result.lobes, start=1):
            shown = ", ".join(
                f"{n}={','.join(f'{c:.4g}' for c in v) if isinstance(v, tuple) else f'{v:.4g}'}"
                for n, v in values.items()
            )
            print(f"  lobe {k}: {shown}")
        preset = outdir / f"{stem}-{name}-fit.toml"
        _write_preset(result, args.table, preset)
        print(f"  wrote preset {preset}")
        if not args.no_figure:
            figure = fit_figure(table, result, outdir / f"{stem}-{name}-fit.png")
            print(f"  wrote figure {figure}")
    if len(results) > 1:
        print(f"\n{'model':15s} {'params':>6s} {'error':>10s} {'rel.':>6s}")
        best = min(r.error for r in results)
        for r in sorted(results, key=lambda r: r.error):
            count = sum(3 if isinstance(v, tuple) else 1 for v in r.lobes[0].values())
            print(
                f"{r.model:15s} {count * len(r.lobes):6d} {r.error:10.5f} "
                f"{r.error / best if best > 0 else 1.0:6.2f}"
            )
    return 0


def cmd_sh(args) -> int:
    from lab.measured.figures import sh_figure

    try:
        orders = sorted({int(x) for x in args.orders.split(",")})
    except ValueError:
        raise _usage(f"--orders {args.orders!r} is malformed: write e.g. 0,1,2,4,8,16") from None
    if not orders or orders[0] < 0 or orders[-1] > 40:
        raise _usage("--orders must be between 0 and 40")
    if not 0.0 <= args.theta_i < 90.0:
        raise _usage(f"--theta-i {args.theta_i:g} must be in 0..90 degrees")
    if args.table:
        from lab.measured.merl import lookup

        table = _read(args.table)

        def lobe_fn(L, V):
            return lookup(table, L, V, "linear")

        title = Path(args.table).name
    else:
        from lab import reference
        from lab.sources import open_with_settings

        model, values = open_with_settings(args.model or "ggx", args.set)

        def lobe_fn(L, V):
            return reference.brdf(model.name, values, L, V)

        title = model.name
    from lab.errors import check_output

    out = check_output(args.output, ".png")
    path, rows = sh_figure(lobe_fn, args.theta_i, orders, out, title)
    print(f"{'order':>5s} {'coefficients':>12s} {'relative L2 error':>18s}")
    for order, count, error in rows:
        print(f"{order:5d} {count:12d} {error:18.3e}")
    print(f"wrote {path}")
    return 0


def cmd_render_measured(args) -> int:
    from lab import views
    from lab.errors import check_output, parse_light
    from lab.measured.figures import filter_figure
    from lab.measured.model import measured_model
    from lab.render import Renderer

    table = _read(args.table)
    theta, phi = parse_light(args.light)
    out = check_output(args.output, ".png")
    renderer = Renderer()
    if args.interpolation == "both":
        filter_figure(table, out, renderer, light=(theta, phi))
    else:
        values = {"interpolation": args.interpolation, "gain": args.gain}
        model = measured_model(table)
        job = views.PlotJob(renderer, model, values, theta, phi, out, args.size, args.exposure)
        views.view(args.view).plot(job)
        for warning in job.warnings:
            print(f"brdf-lab: warning: {warning}", file=sys.stderr)
    print(f"wrote {out}")
    return 0


def cmd_bench(args) -> int:
    from lab.measured.bench import run

    run(quick=args.quick)
    return 0


def register(sub) -> None:
    from lab import views

    p = sub.add_parser("tabulate", help="write an analytic model as a MERL .binary table")
    p.add_argument("model", help="model name (see 'brdf-lab models') or a .glsl file")
    p.add_argument("--set", action="append", metavar="NAME=VALUE", help="parameter value")
    p.add_argument(
        "--noise",
        type=float,
        default=0.0,
        metavar="SIGMA",
        help="relative noise (sigma, nearly Gaussian), e.g. 0.05",
    )
    p.add_argument("--seed", type=int, default=0, help="seed of the noise")
    p.add_argument(
        "--dims", default="90,90,180", help="bins theta_h,theta_d,phi_d (MERL: 90,90,180)"
    )
    p.add_argument("-o", "--output", required=True, metavar="FILE.binary")
    p.set_defaults(func=cmd_tabulate)

    p = sub.add_parser("fit", help="fit analytic models to a MERL .binary table")
    p.add_argument("table", metavar="FILE.binary")
    p.add_argument(
        "--model",
        action="append",
        choices=FIT_MODELS,
        help="model to fit (repeat for several; default cook_torrance)",
    )
    p.add_argument("--compare", action="store_true", help="fit all four and print a table")
    p.add_argument("--lobes", type=int, choices=(1, 2), default=1, help="specular lobes")
    p.add_argument(
        "--metric",
        choices=("log", "linear"),
        default="log",
        help="compare log(1 + f cos) (default) or f cos",
    )
    p.add_argument("--samples", type=int, default=20000, help="table bins used for the fit")
    p.add_argument("--gpu", action="store_true", help="evaluate models with their shaders")
    p.add_argument("--outdir", default=".", help="folder for the presets and figures")
    p.add_argument("--no-figure", action="store_true", help="skip the comparison figure")
    p.set_defaults(func=cmd_fit)

    p = sub.add_parser("sh", help="project a lobe on spherical harmonics: error vs order")
    p.add_argument("model", nargs="?", help="analytic model (default ggx), or use --table")
    p.add_argument("--set", action="append", metavar="NAME=VALUE")
    p.add_argument("--table", metavar="FILE.binary", help="a measured table instead of a model")
    p.add_argument("--theta-i", type=float, default=45.0, help="incident angle (deg)")
    p.add_argument("--orders", default="0,1,2,4,8,16", help="orders to show")
    p.add_argument("-o", "--output", required=True, metavar="OUT.png")
    p.set_defaults(func=cmd_sh)

    p = sub.add_parser("render-measured", help="render a view of a MERL .binary table")
    p.add_argument("table", metavar="FILE.binary")
    # Every view with a PNG: one that cannot draw a table (the D, G, F terms) says so.
    p.add_argument("--view", choices=views.plot_views(), default="sphere")
    p.add_argument(
        "--interpolation",
        choices=("linear", "nearest", "both"),
        default="linear",
        help="table lookup; 'both' draws the sphere with each, side by side",
    )
    p.add_argument("--gain", type=float, default=1.0, help="multiplies the table")
    p.add_argument("--light", default="45,0", metavar="THETA,PHI")
    p.add_argument("--size", type=int, default=512)
    p.add_argument("--exposure", type=float, default=0.0)
    p.add_argument("-o", "--output", required=True, metavar="OUT.png")
    p.set_defaults(func=cmd_render_measured)

    p = sub.add_parser("measured-bench", help="load, render and fit timings of measured BRDFs")
    p.add_argument("--quick", action="store_true", help="fewer repetitions")
    p.set_defaults(func=cmd_bench)

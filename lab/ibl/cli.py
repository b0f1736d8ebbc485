"""Command line of the IBL feature: `brdf-lab ibl-bench` (render --view ibl is in lab.cli)."""

from __future__ import annotations


def cmd_ibl_bench(args) -> int:
    from pathlib import Path

    from lab.errors import UsageError
    from lab.ibl import bench

    if args.plot:
        from lab.errors import check_output

        args.plot = check_output(args.plot, ".png")
    against = None
    if args.against:
        against = Path(args.against)
        if not (against / "shaders" / "terms" / "environment.glsl").is_file():
            raise UsageError(
                f"--against {args.against}: no shaders/terms/environment.glsl there: give a "
                "checkout of brdf-lab (e.g. 'git worktree add /tmp/old <commit>')"
            )
    if args.table:
        bench.table_run(args.size, args.reference, args.max_samples)
        return 0
    bench.run(
        args.size, args.reference, args.budget, args.plot, against, args.quick, args.max_samples
    )
    return 0


def register(sub) -> None:
    p = sub.add_parser(
        "ibl-bench",
        help="IBL: where a pass's time goes, samples/s, samples and time to 1%% per strategy",
    )
    p.add_argument("--size", type=int, default=64, help="sphere size for the convergence runs")
    p.add_argument(
        "--reference", type=int, default=8192, help="samples/pixel of the converged reference"
    )
    p.add_argument(
        "--budget", type=float, default=60.0, help="seconds per run before extrapolating"
    )
    p.add_argument(
        "--max-samples", type=int, default=4096, help="samples/pixel per run before extrapolating"
    )
    p.add_argument("--plot", metavar="OUT.png", help="save the log-log convergence plot")
    p.add_argument(
        "--against", metavar="DIR", help="an older checkout: time its pass beside this one's"
    )
    p.add_argument("--quick", action="store_true", help="GGX alpha 0.1 and its twin, furnace")
    p.add_argument(
        "--table",
        action="store_true",
        help="only the table sampler's target: GGX alpha 0.1, 0.5 against the .brdf twin",
    )
    p.set_defaults(func=cmd_ibl_bench)

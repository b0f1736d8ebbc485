"""Command line of the IBL feature: `brdf-lab ibl-bench` (render --view ibl is in lab.cli)."""

from __future__ import annotations


def cmd_ibl_bench(args) -> int:
    from lab.ibl import bench

    if args.plot:
        from lab.errors import check_output

        args.plot = check_output(args.plot, ".png")
    bench.run(args.size, args.reference, args.budget, args.plot)
    return 0


def register(sub) -> None:
    p = sub.add_parser(
        "ibl-bench",
        help="IBL: samples per second (512x512 sphere) and time to 1%% RMS per strategy",
    )
    p.add_argument("--size", type=int, default=64, help="sphere size for the convergence runs")
    p.add_argument(
        "--reference", type=int, default=8192, help="samples/pixel of the converged reference"
    )
    p.add_argument(
        "--budget", type=float, default=20.0, help="seconds per strategy before extrapolating"
    )
    p.add_argument("--plot", metavar="OUT.png", help="save the log-log convergence plot")
    p.set_defaults(func=cmd_ibl_bench)

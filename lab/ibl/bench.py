"""`brdf-lab ibl-bench`: where a pass's time goes, samples per second, and each strategy's
samples and time to 1% error, with random and low-discrepancy samples, for GGX (alpha 0.1
and 0.5), their .brdf twins (sampled from tables) and a MERL table, under the furnace and
the sky; then the ratios issue 28's targets name.

Samples to 1% come from convergence runs on a small sphere (`--size`: a pixel's error does
not depend on the image size); time to 1% is those samples at the samples per second of a
317 x 317 sphere in passes of 16, as the app runs them. With `--against DIR` (a checkout of
an older commit) its estimator's GLSL runs beside this one's in the same process, so the
speed-up is measured in one run.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from lab.ibl.convergence import (
    TARGET,
    Convergence,
    converge,
    reference_image,
    relative_rms,
    throughput,
)
from lab.ibl.integrator import (
    SEQUENCES,
    Environment,
    IBLRenderer,
    Progressive,
    chosen_strategy,
)

__all__ = ["relative_rms", "run"]
TWIN = Path(__file__).resolve().parent / "twins" / "ggx.brdf"
RATE_SIZE = 317
STRATEGIES = ("brdf", "environment", "mis_power", "auto")  # what the convergence runs use
SINGLE = ("brdf", "environment")  # single strategies the default is held against


@dataclass
class Case:
    label: str
    model: object
    values: dict
    kind: str  # "analytic", "twin" (of the analytic case alpha), "measured"


def cases(renderer: IBLRenderer, quick: bool) -> list[Case]:
    """GGX at alpha 0.1 and 0.5, their .brdf twins and a MERL-layout table of GGX."""
    from lab.brdf_explorer import read_brdf
    from lab.measured.model import measured_model
    from lab.measured.tabulate import tabulate

    twin = read_brdf(TWIN)
    out = []
    for alpha in (0.1,) if quick else (0.1, 0.5):
        out.append(Case(f"ggx a={alpha}", "ggx", {"alpha": alpha}, "analytic"))
        out.append(Case(f"ggx.brdf a={alpha}", twin, {"alpha": alpha}, "twin"))
    if not quick:
        dims = (90, 90, 180)
        table = tabulate("ggx", {"alpha": 0.2}, dims, renderer=renderer)
        out.append(Case("MERL table (ggx a=0.2)", measured_model(table), {}, "measured"))
    return out


def environments(quick: bool) -> dict[str, Environment]:
    furnace = Environment(np.ones((16, 32, 3), np.float32), "furnace")
    return {"furnace": furnace} if quick else {"furnace": furnace, "sky": Environment.load("sky")}


def breakdown(renderer: IBLRenderer, env: Environment, size: int = RATE_SIZE) -> list[str]:
    """Where a pass's time goes (GGX alpha 0.1, BRDF sampling): host work, readback, a
    pass's fixed cost, the loop guard's second target, the sample sequence. Each pass
    variant is timed 3 times, alternated, and the fastest kept (others' load only slows)."""
    ctx = renderer.ctx
    job = Progressive(renderer, "ggx", {"alpha": 0.1}, env, "brdf", size)
    ld = Progressive(renderer, "ggx", {"alpha": 0.1}, env, "brdf", size, sequence="sobol")
    plain = job._fbo
    guarded = ctx.framebuffer(color_attachments=[job._texture, job._flag])

    def timed(action, repeat=1) -> float:
        start = time.perf_counter()
        for _ in range(repeat):
            action()
        ctx.finish()
        return (time.perf_counter() - start) / repeat

    def with_guard():
        job._fbo = guarded
        job.add(16)
        job._fbo = plain

    try:
        job.add(1)
        ld.add(1)
        ctx.finish()
        uniforms = timed(lambda: renderer.set_uniforms(job.program, job.model, job.values, {}), 20)
        readback = timed(job.image, 5)
        times: dict[str, list[float]] = {k: [] for k in ("one", "sixteen", "guard", "sobol")}
        for _ in range(3):
            times["one"].append(timed(lambda: job.add(1)))
            times["sixteen"].append(timed(lambda: job.add(16)))
            times["guard"].append(timed(with_guard))
            times["sobol"].append(timed(lambda: ld.add(16)))
        one, sixteen, guard, sobol = (min(times[k]) for k in ("one", "sixteen", "guard", "sobol"))
    finally:
        job._fbo = plain
        guarded.release()
        job.release()
        ld.release()
    per_sample = max(sixteen - one, 0.0) / 15.0
    fixed = max(one - per_sample, 0.0)
    return [
        f"  uniform upload (host)          {uniforms * 1e3:8.3f} ms/pass",
        f"  readback of the running sum    {readback * 1e3:8.3f} ms (once per shown frame)",
        f"  fixed cost of a pass           {fixed * 1e3:8.1f} ms "
        f"(a 1 spp pass: {one * 1e3:.1f} ms)",
        f"  one sample per pixel           {per_sample * 1e3:8.1f} ms",
        f"  16 spp                         {sixteen * 1e3:8.1f} ms; with the loop guard's "
        f"second target {guard * 1e3:.1f} ms (now only for exercises' samplers)",
        f"  16 spp, Sobol' instead of PCG  {sobol * 1e3:8.1f} ms",
        f"  => fixed costs take {fixed / max(sixteen, 1e-9):.0%} of a 16 spp pass, "
        f"{fixed / max(fixed + 2 * per_sample, 1e-9):.0%} of a 2 spp one (the old app's)",
    ]


def against_rates(renderer, old_dir: Path, envs: dict) -> tuple[list[str], dict]:
    """Samples/s of this checkout's estimator and of `old_dir`'s, alternated 3 times."""
    old = IBLRenderer(renderer.ctx)
    old.sampling_terms = old_dir / "shaders" / "terms" / "sampling.glsl"
    old.environment_terms = old_dir / "shaders" / "terms" / "environment.glsl"
    lines, ratios = [], {}
    for name, env in envs.items():
        for strategy in ("brdf", "mis_power"):
            pairs = []
            for _ in range(3):
                a = throughput(old, "ggx", {"alpha": 0.1}, env, strategy)
                b = throughput(renderer, "ggx", {"alpha": 0.1}, env, strategy)
                pairs.append((a, b))
            a, b = np.median(np.array(pairs), axis=0)
            ratio = float(np.median([y / x for x, y in pairs]))
            ratios[(name, strategy)] = ratio
            lines.append(
                f"  {name:8s} {strategy:10s} old {a / 1e6:6.2f}  new {b / 1e6:6.2f} M/s  "
                f"x{ratio:.2f}"
            )
    return lines, ratios


def fmt_time(seconds: float, measured: bool) -> str:
    return f"{seconds:8.2f} s{' ' if measured else '~'}"


def run(
    size: int = 64,
    reference_samples: int = 8192,
    budget_s: float = 60.0,
    plot=None,
    against: Path | None = None,
    quick: bool = False,
    max_samples: int = 4096,
) -> dict:
    """Print the figures (and save the convergence plot to `plot`); returns them too.
    `quick` (for the tests): GGX alpha 0.1 and its twin in the furnace only."""
    renderer = IBLRenderer()
    envs = environments(quick)
    print(f"renderer: {renderer.ctx.info['GL_RENDERER']}")
    print(f"where a pass's time goes ({RATE_SIZE}x{RATE_SIZE} sphere, ggx alpha=0.1, BRDF):")
    for line in breakdown(renderer, envs["furnace"], 64 if quick else RATE_SIZE):
        print(line)
    figures: dict = {"pass": {}, "rate": {}, "runs": {}}
    if against is not None:
        print(f"samples/s against {against} (same process, median of 3 alternations):")
        lines, figures["pass"] = against_rates(renderer, Path(against), envs)
        for line in lines:
            print(line)
    rate_size = 64 if quick else RATE_SIZE
    runs = {}
    all_cases = cases(renderer, quick)
    for case in all_cases:
        for env_name, env in envs.items():
            reference, own = reference_image(
                renderer, case.model, case.values, env, size, reference_samples
            )
            figures.setdefault("reference_error", {})[(case.label, env_name)] = own
            for strategy in STRATEGIES:
                for sequence in SEQUENCES:
                    runs[(case.label, env_name, strategy, sequence)] = converge(
                        renderer, case.model, case.values, env, strategy, reference,
                        size, budget_s, TARGET, own, sequence, max_samples,
                    )  # fmt: skip
    # Samples/s of every program, in rounds over all of them, the best round of each kept:
    # a burst of others' work on a shared machine then spoils one round, not one program.
    programs = {}
    for case in all_cases:
        for env_name, env in envs.items():
            for strategy in STRATEGIES:
                for sequence in SEQUENCES:
                    key = (case.label, env_name, chosen_strategy(strategy, env), sequence)
                    programs[key] = (case, env)  # "auto" runs another strategy's program
    rates: dict = {}
    for _ in range(1 if quick else 3):
        for key, (case, env) in programs.items():
            rate = throughput(
                renderer, case.model, case.values, env, key[2], key[3], rate_size, windows=1
            )
            rates[key] = max(rates.get(key, 0.0), rate)
    for case in all_cases:
        for env_name, env in envs.items():
            own = figures["reference_error"][(case.label, env_name)]
            print(
                f"{case.label} under the {env_name}: samples and time to {TARGET:.0%} "
                f"(reference's own error {own:.2%}, taken out)"
            )
            for strategy in STRATEGIES:
                row = []
                for sequence in SEQUENCES:
                    c = runs[(case.label, env_name, strategy, sequence)]
                    rate = rates[(case.label, env_name, chosen_strategy(strategy, env), sequence)]
                    samples, measured = c.samples_to()
                    seconds = samples * math.pi / 4.0 * rate_size**2 / rate
                    figures["runs"][(case.label, env_name, strategy, sequence)] = (c, seconds)
                    figures["rate"][(case.label, env_name, strategy, sequence)] = rate
                    row.append(
                        f"{sequence:6s} {samples:9.0f} spp{' ' if measured else '~'}"
                        f"{fmt_time(seconds, measured)} {rate / 1e6:5.2f} M/s"
                    )
                print(f"  {strategy:11s} " + " | ".join(row))
    print(f"(~: extrapolated by 1/sqrt(N) past {max_samples} spp or {budget_s:.0f} s; times at "
          f"{rate_size}x{rate_size}, passes of 16 spp, best of 3 rounds)")  # fmt: skip
    figures["targets"] = targets(figures, envs, quick)
    if plot:
        convergence_plot(figures["runs"], plot)
        print(f"wrote {plot}")
    return figures


def targets(figures: dict, envs: dict, quick: bool) -> dict:
    """Print and return the ratios the issue's targets name."""
    runs = figures["runs"]
    out: dict = {}
    print("targets:")
    if figures["pass"]:
        worst = min(figures["pass"].values())
        print(f"  pass: samples/s new / old >= 1.6: x{worst:.2f} at worst")
        out["pass"] = worst
    alphas = (0.1,) if quick else (0.1, 0.5)
    for alpha in alphas:
        label = f"ggx a={alpha}"
        for strategy in ("brdf", "auto"):
            (cr, tr), (cs, ts) = (runs[(label, "furnace", strategy, s)] for s in SEQUENCES)
            shared = [n for n in cs.samples if n in cr.samples]
            worst = max(cs.error_at(n) / cr.error_at(n) for n in shared)
            out[("ld", alpha, strategy)] = (tr / ts, worst)
            print(
                f"  low-discrepancy, {label} furnace {strategy}: time to 1% random / Sobol' "
                f"= {tr / ts:.1f} (>= 2); worst error ratio Sobol'/random over "
                f"{len(shared)} prefixes = {worst:.2f} (<= 1)"
            )
    for alpha in alphas:
        for env_name in envs:
            for strategy in ("brdf", "auto"):
                t_a = runs[(f"ggx a={alpha}", env_name, strategy, "sobol")][1]
                t_t = runs[(f"ggx.brdf a={alpha}", env_name, strategy, "sobol")][1]
                out[("table", alpha, env_name, strategy)] = t_t / t_a
                print(
                    f"  table sampler, ggx.brdf / ggx a={alpha} {env_name} {strategy} "
                    f"(Sobol'): time to 1% x{t_t / t_a:.2f} (<= 2)"
                )
    labels = sorted({key[0] for key in runs})
    for label in labels:
        for env_name in envs:
            best = min(runs[(label, env_name, s, "sobol")][1] for s in SINGLE)
            auto = runs[(label, env_name, "auto", "sobol")][1]
            out[("default", label, env_name)] = auto / best
            print(
                f"  default (auto, Sobol'), {label} {env_name}: time to 1% / best single "
                f"strategy's = {auto / best:.2f} (<= 1.5)"
            )
    return out


def table_run(
    size: int = 64,
    reference_samples: int = 8192,
    max_samples: int = 4096,
    rate_size: int = RATE_SIZE,
    rounds: int = 5,
) -> dict:
    """`ibl-bench --table`: the data-driven sampler's target alone. GGX alpha 0.1 and 0.5
    against the .brdf twin, under the furnace and the sky, BRDF sampling and `auto` on Sobol'
    points: samples to 1% (independent of load), samples/s (the best of 5 rounds over all
    programs, so a burst of others' load spoils a round, not one side of a ratio), their
    ratios twin / analytic, and the table's build time."""
    from lab.brdf_explorer import read_brdf

    renderer = IBLRenderer()
    models = {"ggx": "ggx", "ggx.brdf": read_brdf(TWIN)}
    envs = environments(False)
    print(f"renderer: {renderer.ctx.info['GL_RENDERER']}")
    samples: dict = {}
    for alpha in (0.1, 0.5):
        values = {"alpha": alpha}
        build = renderer.tables.get(renderer, models["ggx.brdf"], values).seconds
        print(f"ggx a={alpha}: table built in {build * 1e3:.0f} ms")
        for env_name, env in envs.items():
            for label, model in models.items():
                reference, own = reference_image(
                    renderer, model, values, env, size, reference_samples
                )
                for strategy in ("brdf", "auto"):
                    samples[(alpha, env_name, label, strategy)] = converge(
                        renderer, model, values, env, strategy, reference, size, 600.0,
                        TARGET, own, "sobol", max_samples,
                    ).samples_to()  # fmt: skip
    rates: dict = {}
    cpu: dict = {}  # CPU seconds (all of llvmpipe's threads) per sample: far less load-bound
    for _ in range(rounds):
        for alpha, env_name, label, strategy in samples:
            env = envs[env_name]
            key = (alpha, env_name, label, chosen_strategy(strategy, env))
            model, values = models[label], {"alpha": alpha}
            rate = throughput(renderer, model, values, env, key[3], "sobol", rate_size, 16, 1)
            rates[key] = max(rates.get(key, 0.0), rate)
            spent = cpu_per_sample(renderer, model, values, env, key[3], rate_size)
            cpu[key] = min(cpu.get(key, math.inf), spent)
    out: dict = {}
    for (alpha, env_name, label, strategy), (n, measured) in samples.items():
        key = (alpha, env_name, label, chosen_strategy(strategy, envs[env_name]))
        seconds = n * math.pi / 4.0 * rate_size**2 / rates[key]
        out[(alpha, env_name, label, strategy)] = (n, rates[key], seconds, cpu[key])
        print(
            f"  a={alpha} {env_name:8s} {label:9s} {strategy:5s} {n:7.0f} spp"
            f"{' ' if measured else '~'} {rates[key] / 1e6:6.2f} M/s "
            f"{fmt_time(seconds, measured)}"
        )
    print(
        f"twin / analytic (time at {rate_size}x{rate_size}, passes of 16; <= 2 is the target; "
        "by CPU time: the same with the time per sample in CPU seconds):"
    )
    for alpha in (0.1, 0.5):
        for env_name in envs:
            for strategy in ("brdf", "auto"):
                (na, ra, ta, ca), (nt, rt, tt, ct) = (
                    out[(alpha, env_name, m, strategy)] for m in ("ggx", "ggx.brdf")
                )
                out[("ratio", alpha, env_name, strategy)] = tt / ta
                out[("cpu ratio", alpha, env_name, strategy)] = nt * ct / (na * ca)
                print(
                    f"  a={alpha} {env_name:8s} {strategy:5s} samples x{nt / na:.2f}, "
                    f"time per sample x{ra / rt:.2f}, time to 1% x{tt / ta:.2f}; by CPU time: "
                    f"per sample x{ct / ca:.2f}, to 1% x{nt * ct / (na * ca):.2f}"
                )
    return out


def cpu_per_sample(renderer, model, values, env, strategy: str, size: int) -> float:
    """CPU seconds per sample on a size x size sphere (Sobol', passes of 16), counting all
    of llvmpipe's threads: what a sample costs, whatever others' load does to the clock."""
    job = Progressive(renderer, model, values, env, strategy, size, sequence="sobol")
    try:
        job.add(1)
        renderer.ctx.finish()
        start, clock = time.process_time(), time.perf_counter()
        samples = 0
        while time.perf_counter() - clock < 0.3 or samples < 32:
            job.add(16)
            renderer.ctx.finish()
            samples += 16
        return (time.process_time() - start) / (samples * math.pi / 4.0 * size * size)
    finally:
        job.release()


def convergence_plot(runs: dict, path) -> None:
    """Log-log error against samples for the first case and environment, random dashed."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    first = next(iter(runs))
    label, env_name = first[0], first[1]
    fig, ax = plt.subplots(figsize=(6.4, 4.4), dpi=120)
    for (case, env, strategy, sequence), (c, _) in runs.items():
        if (case, env) != (label, env_name):
            continue
        style = "-" if sequence == "sobol" else "--"
        ax.loglog(c.samples, c.errors, style, marker="o", ms=3, label=f"{strategy}, {sequence}")
    ax.axhline(TARGET, color="grey", lw=0.8, ls=":")
    ax.set_xlabel("samples per pixel")
    ax.set_ylabel("relative RMS error vs converged reference")
    ax.set_title(f"{label} under the {env_name}")
    ax.legend(fontsize=7)
    ax.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)


__all__ += ["Convergence"]

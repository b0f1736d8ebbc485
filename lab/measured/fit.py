"""Fit analytic models to a tabulated BRDF by nonlinear least squares.

The error follows Ngan, Durand and Matusik, "Experimental Analysis of BRDF Models" (EGSR
2005): compare the cosine-weighted BRDF f_r cos(theta_i), weight each sample by the solid
angle its bin covers, and leave out directions above 80 deg from the normal, where
measurements are least reliable. By default the comparison is made on log(1 + x), so the
bright specular peak does not drown the rest of the lobe; `metric="linear"` compares x.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from scipy.optimize import least_squares

from lab.measured import merl
from lab.models import load_model

FIT_MODELS = ("ward", "blinn_phong", "cook_torrance", "ggx")
MAX_THETA_DEG = 80.0

# Per model: the parameters fitted for each lobe. "color" fits r, g, b; "grey" fits one
# number used for all three channels; "float" one number. Roughness-like floats are fitted
# in log space (their header says `log`). Other parameters keep their defaults.
LOBE_PARAMS: dict[str, list[tuple[str, str]]] = {
    "ward": [("ks", "color"), ("alpha_x", "float")],
    "blinn_phong": [("ks", "color"), ("ke", "float")],
    "cook_torrance": [("ks", "color"), ("m", "float"), ("f0", "grey")],
    "ggx": [("ks", "color"), ("alpha", "float"), ("f0", "grey")],
}
# Starting roughness for the multi-start (sharp, medium, broad lobes).
STARTS: dict[str, list[float]] = {
    "ward": [0.05, 0.15, 0.4],
    "blinn_phong": [800.0, 80.0, 8.0],
    "cook_torrance": [0.05, 0.15, 0.4],
    "ggx": [0.05, 0.15, 0.4],
}
# Colours of the fit preset: the table light grey, the fitted lobes from the app's palette.
MEASURED_COLOR = "#e0e0e0"
FIT_COLORS = ("#e6194b", "#f58231")
ROUGHNESS = {"ward": "alpha_x", "blinn_phong": "ke", "cook_torrance": "m", "ggx": "alpha"}

Evaluate = Callable[[str, dict, np.ndarray, np.ndarray], np.ndarray]


def cpu_evaluate(model: str, values: dict, L: np.ndarray, V: np.ndarray) -> np.ndarray:
    """f_r (n, 3) from the numpy reference (float64, smooth derivatives)."""
    from lab import reference

    return reference.brdf(model, values, L, V)


def gpu_evaluator(renderer=None) -> Evaluate:
    """f_r (n, 3) from the model's own shader (float32)."""
    from lab.render import Renderer

    renderer = renderer or Renderer()

    def evaluate(model: str, values: dict, L: np.ndarray, V: np.ndarray) -> np.ndarray:
        return renderer.probe(model, values, L, V).astype(np.float64)

    return evaluate


@dataclass
class Samples:
    """Bins of a table chosen for fitting: directions, measured f_r and weights."""

    L: np.ndarray
    V: np.ndarray
    f: np.ndarray  # (n, 3)
    weight: np.ndarray  # (n,), sums to 1

    @property
    def cos_i(self) -> np.ndarray:
        return self.L[:, 2:3]


def select_samples(table: merl.MerlTable, count: int = 20000, seed: int = 0) -> Samples:
    """Up to `count` measured bins with theta_i and theta_o <= 80 deg, chosen at random.

    Picking bins uniformly keeps the sqrt spacing of theta_h (many samples near the
    specular peak); the solid-angle weight of each bin undoes that bias in the error.
    """
    dims = table.dims
    th, td, pd = merl.bin_centres(dims)
    rgb = table.rgb.reshape(-1, 3)
    weight = merl.bin_weights(dims).ravel()
    # Cheap pre-selection in angle space, then directions only for the chosen bins.
    candidates = np.flatnonzero(table.measured().ravel() & (weight > 0))
    ih, idd, ip = np.unravel_index(candidates, dims)
    L, V = merl.directions(th[ih], td[idd], pd[ip])
    limit = math.cos(math.radians(MAX_THETA_DEG))
    keep = (L[:, 2] >= limit) & (V[:, 2] >= limit)
    candidates, L, V = candidates[keep], L[keep], V[keep]
    if len(candidates) == 0:
        raise ValueError("the table has no measured values with theta_i, theta_o <= 80 deg")
    if len(candidates) > count:
        pick = np.sort(np.random.default_rng(seed).choice(len(candidates), count, replace=False))
        candidates, L, V = candidates[pick], L[pick], V[pick]
    w = weight[candidates]
    return Samples(L, V, rgb[candidates], w / w.sum())


def transform(metric: str) -> Callable[[np.ndarray], np.ndarray]:
    if metric == "log":
        return np.log1p
    if metric == "linear":
        return lambda x: x
    raise ValueError(f"metric must be log or linear, not {metric!r}")


def fit_error(samples: Samples, model_f: np.ndarray, metric: str = "log") -> float:
    """Weighted RMS difference of g(f_r cos theta_i), g = log(1 + x) or identity."""
    g = transform(metric)
    diff = g(np.maximum(model_f, 0.0) * samples.cos_i) - g(samples.f * samples.cos_i)
    return float(np.sqrt((samples.weight[:, None] * diff**2).sum() / 3.0))


@dataclass
class FitResult:
    model: str
    lobes: list[dict]  # parameter values per lobe, as a preset holds them
    error: float
    metric: str
    seconds: float
    evaluations: int
    samples: int
    history: list[float] = field(default_factory=list)

    def preset(self, table: str | Path | None = None, base: Path | None = None) -> dict:
        """The fit as a preset the lab opens (lab/presets.py layout): the measured table
        (when given; its path relative to the folder `base`) and one entry per lobe."""
        from lab import presets

        entries = []
        if table is not None:
            entries.append(
                {
                    "model": presets.MEASURED,
                    "table": presets.relative(table, base),
                    "label": "measured",
                    "color": MEASURED_COLOR,
                    "visible": True,
                    "values": {"interpolation": "linear", "gain": 1.0},
                }
            )
        many = len(self.lobes) > 1
        for k, values in enumerate(self.lobes):
            label = f"{self.model} fit" + (f", lobe {k + 1} of {len(self.lobes)}" if many else "")
            entries.append(
                {
                    "model": self.model,
                    "label": label,
                    "color": FIT_COLORS[k % len(FIT_COLORS)],
                    "visible": True,
                    "values": presets.plain_values(values),
                }
            )
        source = Path(table).name if table is not None else "a table"
        notes = (
            f"{self.model} fitted to {source}: {self.metric} error {self.error:.4g}"
            f" on {self.samples} samples"
        )
        if many:
            notes += (
                f"; the fit is the SUM of the {len(self.lobes)} {self.model} lobes "
                "(the diffuse term is in lobe 1): each lobe is shown on its own"
            )
        return {
            "title": f"{self.model} fit to {source}",
            "notes": notes,
            "views": ["sphere", "polar", "lobe3d", "sh", "slice", "albedo", "object"],
            "settings": {
                "theta_i": 45.0,
                "phi_i": 0.0,
                "multiply_cos": True,
                "polar_log": True,
                "polar_cos": True,
            },
            "model": entries,
        }


class _Packing:
    """Between the parameter vector least_squares moves and per-lobe value dicts."""

    def __init__(self, model: str, lobes: int):
        self.model = model
        self.header = load_model(model).params
        # (lobe, name, kind, log); the diffuse colour belongs to the first lobe only.
        self.slots: list[tuple[int, str, str, bool]] = [(0, "kd", "color", False)]
        for lobe in range(lobes):
            for name, kind in LOBE_PARAMS[model]:
                self.slots.append((lobe, name, kind, self.header[name].scale == "log"))
        self.lobes = lobes

    def bounds(self) -> tuple[np.ndarray, np.ndarray]:
        low, high = [], []
        for _, name, kind, log in self.slots:
            p = self.header[name]
            a, b = (math.log(p.minimum), math.log(p.maximum)) if log else (p.minimum, p.maximum)
            width = 3 if kind == "color" else 1
            low += [a] * width
            high += [b] * width
        return np.array(low), np.array(high)

    def pack(self, lobes: list[dict]) -> np.ndarray:
        x = []
        for lobe, name, kind, log in self.slots:
            value = lobes[lobe][name]
            if kind == "color":
                x += list(value)
            elif kind == "grey":
                x.append(float(np.mean(value)))
            else:
                x.append(math.log(value) if log else float(value))
        return np.array(x, dtype=np.float64)

    def unpack(self, x: np.ndarray) -> list[dict]:
        lobes: list[dict] = [{} for _ in range(self.lobes)]
        i = 0
        for lobe, name, kind, log in self.slots:
            if kind == "color":
                lobes[lobe][name] = tuple(float(c) for c in x[i : i + 3])
                i += 3
            else:
                value = float(math.exp(x[i]) if log else x[i])
                lobes[lobe][name] = (value,) * 3 if kind == "grey" else value
                i += 1
        for values in lobes[1:]:
            values["kd"] = (0.0, 0.0, 0.0)  # one diffuse term in all
        if self.model == "ward":
            for values in lobes:
                values["alpha_y"] = values["alpha_x"]  # isotropic fit
        # Rounding in exp/log may step a hair outside the header's range.
        for values in lobes:
            for name, value in values.items():
                p = self.header[name]
                if isinstance(value, tuple):
                    values[name] = tuple(min(max(c, p.minimum), p.maximum) for c in value)
                else:
                    values[name] = min(max(value, p.minimum), p.maximum)
        return lobes


def evaluate_lobes(evaluate: Evaluate, model: str, lobes: list[dict], L, V) -> np.ndarray:
    return sum(evaluate(model, values, L, V) for values in lobes)


def fit(
    table: merl.MerlTable | Samples,
    model: str,
    lobes: int = 1,
    metric: str = "log",
    count: int = 20000,
    evaluate: Evaluate | None = None,
    seed: int = 0,
    max_nfev: int = 200,
) -> FitResult:
    """Least-squares fit of `model` (with 1 or 2 specular lobes) to a table."""
    if model not in FIT_MODELS:
        raise ValueError(f"cannot fit {model!r}: choose one of {', '.join(FIT_MODELS)}")
    if lobes not in (1, 2):
        raise ValueError("lobes must be 1 or 2")
    evaluate = evaluate or cpu_evaluate
    samples = table if isinstance(table, Samples) else select_samples(table, count, seed)
    g = transform(metric)
    packing = _Packing(model, lobes)
    low, high = packing.bounds()
    calls = 0

    def _residuals(chosen: Samples) -> Callable[[np.ndarray], np.ndarray]:
        target = g(chosen.f * chosen.cos_i)
        root_w = np.sqrt(chosen.weight / chosen.weight.sum() / 3.0)[:, None]

        def residuals(x: np.ndarray) -> np.ndarray:
            nonlocal calls
            calls += 1
            f = evaluate_lobes(evaluate, model, packing.unpack(x), chosen.L, chosen.V)
            return (root_w * (g(np.maximum(f, 0.0) * chosen.cos_i) - target)).ravel()

        return residuals

    # Start: the diffuse colour from the darkest tenth of the data (away from the peak),
    # a moderate specular weight and several roughness values, each tried briefly on a
    # quarter of the samples; the best start is then refined on all of them.
    kd = np.clip(math.pi * np.percentile(samples.f, 10, axis=0), 1e-3, 1.0)
    start = time.perf_counter()
    header = packing.header
    r = header[ROUGHNESS[model]]
    stride = max(1, min(4, len(samples.f) // 500))  # samples are in bin order: stride
    few = Samples(*(a[::stride] for a in (samples.L, samples.V, samples.f, samples.weight)))
    trials = []
    for rough in STARTS[model]:
        values: list[dict] = []
        for lobe in range(lobes):
            # A second lobe starts broader (for Blinn-Phong: a smaller exponent).
            spread = rough if lobe == 0 else (rough / 8 if model == "blinn_phong" else rough * 4)
            lobe_values = {
                "kd": tuple(kd),
                "ks": (0.5, 0.5, 0.5) if lobe == 0 else (0.1, 0.1, 0.1),
                ROUGHNESS[model]: min(max(spread, r.minimum), r.maximum),
            }
            if model in ("cook_torrance", "ggx"):
                lobe_values["f0"] = (0.5, 0.5, 0.5)
            values.append(lobe_values)
        x0 = np.clip(packing.pack(values), low + 1e-9, high - 1e-9)
        trial = least_squares(
            _residuals(few), x0, bounds=(low, high), x_scale="jac", diff_step=1e-4, max_nfev=40
        )
        trials.append(trial)
    history = [float(np.sqrt(2.0 * t.cost)) for t in trials]
    x0 = min(trials, key=lambda t: t.cost).x
    best = least_squares(
        _residuals(samples),
        x0,
        bounds=(low, high),
        x_scale="jac",
        diff_step=1e-4,
        max_nfev=max_nfev,
    )
    seconds = time.perf_counter() - start
    fitted = packing.unpack(best.x)
    f = evaluate_lobes(evaluate, model, fitted, samples.L, samples.V)
    return FitResult(
        model,
        fitted,
        fit_error(samples, f, metric),
        metric,
        seconds,
        calls,
        len(samples.f),
        history,
    )


def compare(
    table: merl.MerlTable,
    models=FIT_MODELS,
    lobes: int = 1,
    metric: str = "log",
    count: int = 20000,
    evaluate: Evaluate | None = None,
) -> list[FitResult]:
    """Fit several models to the same samples (the comparison of Ngan et al., Fig. 4)."""
    samples = select_samples(table, count)
    return [fit(samples, m, lobes, metric, evaluate=evaluate) for m in models]

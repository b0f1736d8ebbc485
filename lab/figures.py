"""The lecture's figures and the model gallery, rendered from the real shaders."""

from __future__ import annotations

import html
import json
from pathlib import Path

import numpy as np

from lab import describe, diagrams, plots, views
from lab.constants import LUMA
from lab.models import load_model, model_names
from lab.render import Renderer


def _sphere(
    renderer: Renderer,
    out: Path,
    model: str,
    values: dict,
    light=(45.0, 0.0),
    exposure: float = 0.0,
) -> Path:
    plots.save_image(renderer.sphere(model, values, light, size=384), out, exposure)
    diagrams.record_text(out, [])  # a picture: no text to read
    return out


def lecture_figures(outdir: str | Path, renderer: Renderer | None = None) -> list[Path]:
    """Render the lecture's figures into `outdir`; returns the PNG paths."""
    outdir = Path(outdir)
    outdir.mkdir(parents=True, exist_ok=True)
    renderer = renderer or Renderer()
    paths = []
    # Phong exponent: the highlight shrinks as ke grows (lecture: k = 4, 50, 120).
    for ke in (4, 50, 120):
        paths.append(
            _sphere(
                renderer,
                outdir / f"phong_ke_{ke}.png",
                "phong",
                {"kd": (0.25, 0.05, 0.05), "ks": (0.6,) * 3, "ke": float(ke)},
            )
        )
    # Beckmann roughness: m = 0.2 (shiny) and 0.6 (rough).
    for m in (0.2, 0.6):
        paths.append(
            _sphere(
                renderer,
                outdir / f"beckmann_m_{m}.png",
                "cook_torrance",
                {"kd": (0.05, 0.1, 0.3), "m": m, "f0": (0.9,) * 3},
            )
        )
    # Off-specular peak: at grazing incidence Cook-Torrance peaks beyond the mirror angle.
    # Sized for a slide of its own: a wide half disc, the legend beside it, no title (the
    # caption says what is plotted), every text at the slides' size.
    fig, ax = plots.figure(polar=True)
    fig.set_size_inches(13.0, 7.0)
    theta_i = 75.0
    lobes = [
        (renderer.polar(name, values, theta_i, cos_weighted=True), name, color)
        for name, values, color in (
            ("phong", {"kd": (0.0,) * 3, "ks": (0.2,) * 3, "ke": 20.0}, "tab:blue"),
            ("cook_torrance", {"kd": (0.0,) * 3, "m": 0.35, "f0": (0.04,) * 3}, "tab:red"),
        )
    ]
    # F = 1: the microfacet lobe without Fresnel is symmetric about the mirror direction.
    flat = {"kd": (0.0,) * 3, "m": 0.35, "fresnel": "none"}
    flat_lobe = renderer.polar("cook_torrance", flat, theta_i, cos_weighted=True)
    lobes.append((flat_lobe, "cook_torrance, F = 1", "tab:grey"))
    plots.draw_polar(ax, lobes, theta_i, "f_r cos θo", normalize=True, fontsize=diagrams.FONT / 0.9)
    ax.set_title("")
    ax.set_yticks([0.5, 1.0], ["", ""])  # rings at half and full peak; the caption says so
    ax.legend(loc="center left", bbox_to_anchor=(0.98, 0.62), fontsize=diagrams.FONT, frameon=False)
    fig.tight_layout()
    path = diagrams.save(fig, outdir / "off_specular_peak.png")
    paths.append(path)
    # The plot in words for the deck's alt text (slides/build.mjs reads descriptions.json).
    words = describe.describe(
        [describe.Lobe(n, p.theta_o, p.values @ np.asarray(LUMA), None) for p, n, _ in lobes],
        theta_i,
        "f_r cos θo",
    )
    (outdir / "descriptions.json").write_text(
        json.dumps({path.name: words}, ensure_ascii=False), encoding="utf-8"
    )
    # Measuring, and the microfacets' shadowing and masking.
    paths.append(diagrams.gonioreflectometer(renderer, outdir / "gonioreflectometer.png"))
    paths.append(diagrams.vgroove(outdir / "vgroove.png"))
    # Sun and moon: lit from the eye, Lambert darkens to the rim, Lommel-Seeliger stays flat.
    # The moon is exposed 3 stops up so both discs have the same brightness at the centre.
    for name, exposure in (("lambert", 0.0), ("lommel_seeliger", 3.0)):
        paths.append(_sphere(renderer, outdir / f"full_{name}.png", name, {}, (0.0, 0.0), exposure))
    # The reflection equation by Monte Carlo (lab.ibl): equal samples, and the furnace.
    from lab.ibl.figures import ibl_figures

    pictures = ibl_figures(outdir, renderer.ctx)
    for path in pictures:  # rendered spheres: no text to read
        diagrams.record_text(path, [])
    return paths + pictures


def gallery(outdir: str | Path, renderer: Renderer | None = None) -> Path:
    """Every model as a lit sphere and a polar lobe, plus an index.html; returns the index."""
    outdir = Path(outdir)
    outdir.mkdir(parents=True, exist_ok=True)
    renderer = renderer or Renderer()
    rows = []
    for name in model_names():
        model = load_model(name)
        _sphere(renderer, outdir / f"{name}_sphere.png", name, {}, light=(30.0, 0.0))
        polar = views.PlotJob(renderer, model, {}, 30.0, 0.0, outdir / f"{name}_polar.png")
        views.view("polar").plot(polar)
        rows.append(
            f"<tr><td><b>{html.escape(name)}</b><br>{html.escape(model.title)}</td>"
            f"<td><img src='{name}_sphere.png' width=256></td>"
            f"<td><img src='{name}_polar.png' width=340></td></tr>"
        )
    index = outdir / "index.html"
    index.write_text(
        "<!doctype html><meta charset=utf-8><title>brdf-lab gallery</title>"
        "<body style='background:#222;color:#eee;font-family:sans-serif'>"
        "<h1>brdf-lab: every model, light at θi = 30°</h1><table>" + "".join(rows) + "</table>",
        encoding="utf-8",
    )
    return index

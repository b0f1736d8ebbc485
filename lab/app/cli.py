"""`brdf-lab app` (the desktop lab) and `brdf-lab watch FILE` (the students' viewer)."""

from __future__ import annotations

import os
import sys
import time
from pathlib import Path

from lab.models import ModelError

DEFAULT_MODELS = ("phong", "cook_torrance")


def has_display() -> bool:
    """Whether a window can be opened (an X or Wayland display, or a non-Linux desktop)."""
    if not sys.platform.startswith("linux"):
        return True
    if os.environ.get("QT_QPA_PLATFORM", "").startswith("offscreen"):
        return True
    return bool(os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY"))


def register(subparsers) -> None:
    p = subparsers.add_parser("app", help="open the desktop lab (the default command)")
    p.add_argument(
        "models", nargs="*", help="models, .glsl/.brdf files, MERL .binary tables or a preset .toml"
    )
    p.add_argument("--preset", metavar="FILE.toml", help="start from a saved or shipped preset")
    p.add_argument("--presenter", action="store_true", help="large fonts and full screen")
    p.add_argument(
        "--bench", action="store_true", help="print frame times over 200 slider changes and exit"
    )
    p.add_argument(
        "--gallery-dir",
        default="out/gallery",
        help="where to render the gallery when no display is available",
    )
    p.set_defaults(func=cmd_app)

    p = subparsers.add_parser("watch", help="a small window that reloads a shader on save")
    p.add_argument("file", help="a model .glsl (or .brdf) file")
    p.add_argument("--light", default="30,0", metavar="THETA,PHI")
    p.add_argument("--frames", type=int, default=0, help=argparse_hidden())
    p.set_defaults(func=cmd_watch)


def argparse_hidden():
    import argparse

    return argparse.SUPPRESS


def resolve_preset(text: str) -> Path:
    """A preset file, or the name of a shipped one (`phong_exponents`)."""
    from lab.errors import UsageError
    from lab.presets import shipped_presets

    path = Path(text)
    if path.is_file():
        return path
    for shipped in shipped_presets():
        if text in (shipped.stem, shipped.name) or shipped.stem.split("_", 1)[-1] == text:
            return shipped
    names = ", ".join(p.stem for p in shipped_presets())
    raise UsageError(f"no preset file {text!r}; shipped presets: {names}")


def gallery_offscreen(outdir: str) -> int:
    print(
        "brdf-lab: no display is available (DISPLAY is not set); rendering the gallery "
        "offscreen instead."
    )
    from lab import figures

    index = figures.gallery(Path(outdir))
    print(
        f"brdf-lab: the gallery of every model is in {Path(outdir).resolve()} "
        f"(open {index.resolve()})"
    )
    return 0


def cmd_app(args) -> int:
    launched = time.perf_counter()
    if not has_display():
        return gallery_offscreen(args.gallery_dir)
    # A preset given as a file (`brdf-lab app fit.toml`) is the same as --preset.
    presets = [m for m in args.models if m.endswith(".toml")]
    if presets and (args.preset or len(presets) > 1):
        from lab.errors import UsageError

        raise UsageError("give one preset (FILE.toml or --preset FILE.toml)")
    if presets:
        args.preset = presets[0]
        args.models = [m for m in args.models if not m.endswith(".toml")]
    preset = resolve_preset(args.preset) if args.preset else None
    from PyQt6.QtWidgets import QApplication

    from lab.presets import load_any

    models = [load_any(m) for m in args.models]  # fail early, before any window
    app = QApplication.instance() or QApplication(sys.argv[:1])
    app.setApplicationName("brdf-lab")
    if args.bench:
        from lab.app.bench import run_bench

        return run_bench(app, launched)
    from lab.app.window import MainWindow, close_for_exit

    window = MainWindow()
    if preset is not None:
        window.load_preset(preset)
    for name, model in zip(args.models, models, strict=True):
        if name.endswith((".glsl", ".brdf")):
            window.open_file(name)
        else:
            window.lab.add(model)
    if not window.lab.models:
        for name in DEFAULT_MODELS:
            window.lab.add(load_any(name))
    window.show()
    if args.presenter:
        window.toggle_presenter()
    code = app.exec()
    close_for_exit(app, window)
    return code


def cmd_watch(args) -> int:
    from lab.errors import parse_light

    theta, phi = parse_light(args.light)
    if not Path(args.file).is_file():
        raise ModelError("no such file", args.file)
    if not has_display():
        print("brdf-lab: no display is available; 'watch' needs a window.")
        return 2
    from lab.app.watch import watch

    return watch(Path(args.file), (theta, phi), frames=args.frames)

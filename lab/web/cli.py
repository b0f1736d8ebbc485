"""Sub-commands of `brdf-lab` for the web lab and the slides: serve, web-export, web-bench,
slides build / slides pdf."""

from __future__ import annotations

import argparse
import os
import sys
import threading
import webbrowser
from pathlib import Path

DEFAULT_DECK_DIR = "out/slides"


def _usage_error(message: str) -> Exception:
    from lab.errors import UsageError

    return UsageError(message)


def cmd_serve(args) -> int:
    from lab.web.site import make_server

    directory = None
    if args.dir:
        directory = Path(args.dir)
        if not (directory / "index.html").is_file():
            raise _usage_error(
                f"{directory} has no index.html: give a folder written by "
                "'brdf-lab web-export' or 'brdf-lab slides build'"
            )
    try:
        server = make_server(args.port, directory)
    except OSError as err:
        raise _usage_error(
            f"cannot listen on port {args.port}: {err.strerror} (choose another with --port)"
        ) from None
    url = f"http://127.0.0.1:{server.server_address[1]}/"
    print(
        f"serving the {'folder ' + str(directory) if directory else 'BRDF lab'} at {url}"
        "  (Ctrl-C stops)",
        flush=True,
    )
    has_display = bool(
        os.environ.get("DISPLAY")
        or os.environ.get("WAYLAND_DISPLAY")
        or sys.platform in ("darwin", "win32")
    )
    if has_display and not args.no_browser:
        threading.Timer(0.3, webbrowser.open, [url]).start()
    try:
        server.serve_forever()
    except KeyboardInterrupt:
        pass
    finally:
        server.server_close()
    return 0


def cmd_export(args) -> int:
    from lab.web.site import export

    outdir = Path(args.outdir)
    if outdir.exists() and not outdir.is_dir():
        raise _usage_error(f"{outdir} is a file: give a folder for the site")
    try:
        index = export(outdir)
    except OSError as err:
        raise _usage_error(f"cannot write {outdir}: {err.strerror}") from None
    print(
        f"wrote the web lab to {outdir} (open {index.name} through any static web server, "
        f"e.g. 'brdf-lab serve --dir {outdir}')"
    )
    return 0


def cmd_bench(args) -> int:
    from lab.web.bench import BenchError, run
    from lab.web.browser import BrowserMissing

    compare = Path(args.compare) if args.compare else None
    try:
        result = run(
            size=args.size,
            model=args.model,
            loads=args.loads,
            steps=args.steps,
            views=args.views,
            compare=compare,
        )
    except (BrowserMissing, BenchError) as err:
        raise _usage_error(str(err)) from None
    print(result.report())
    return 0


def cmd_slides_build(args) -> int:
    from lab.web import slides

    try:
        index = slides.build(Path(args.outdir), figures=not args.no_figures)
    except slides.SlidesError as err:
        raise _usage_error(str(err)) from None
    print(f"wrote the deck to {index.parent} (view it with 'brdf-lab serve --dir {index.parent}')")
    return 0


def cmd_slides_pdf(args) -> int:
    from lab.web import slides
    from lab.web.browser import BrowserMissing

    deck = Path(args.deck)
    output = Path(args.output) if args.output else deck / "slides.pdf"
    try:
        if not (deck / "index.html").is_file():
            slides.build(deck)
        slides.pdf_or_error(deck, output)
    except (slides.SlidesError, BrowserMissing) as err:
        raise _usage_error(str(err)) from None
    print(f"wrote {output}")
    return 0


def register(subparsers: argparse._SubParsersAction) -> None:
    p = subparsers.add_parser("serve", help="serve the web lab (or a built folder) on localhost")
    p.add_argument("--port", type=int, default=8000, help="port (default 8000; 0 picks one)")
    p.add_argument("--dir", help="serve this folder instead (from web-export or slides build)")
    p.add_argument("--no-browser", action="store_true", help="do not open a browser")
    p.set_defaults(func=cmd_serve)

    p = subparsers.add_parser("web-export", help="write the web lab as a static site")
    p.add_argument("outdir", metavar="DIR")
    p.set_defaults(func=cmd_export)

    p = subparsers.add_parser("web-bench", help="time the web lab in headless Chromium")
    p.add_argument("--size", type=int, default=512, help="sphere size in pixels")
    p.add_argument("--model", default="phong")
    p.add_argument(
        "--loads", type=int, default=7, help="loads of each page to time (in turns, default 7)"
    )
    p.add_argument("--steps", type=int, default=120, help="slider positions to time")
    p.add_argument(
        "--views",
        default=None,
        help="views shown besides sphere and polar (comma-separated; '' for none; "
        "default: every view the page has, from the registry)",
    )
    p.add_argument(
        "--compare",
        metavar="DIR",
        help="a site 'brdf-lab web-export DIR' wrote from another checkout: its page loads "
        "after each of this one's, in the same browser, and both medians are printed "
        "(runs on one machine differ by tens of ms; loads in turn do not)",
    )
    p.set_defaults(func=cmd_bench)

    p = subparsers.add_parser("slides", help="the lecture deck: build it or print it to PDF")
    actions = p.add_subparsers(dest="action", metavar="ACTION", required=True)
    b = actions.add_parser("build", help="build the HTML deck (reveal.js, KaTeX, figures, demos)")
    b.add_argument("outdir", nargs="?", default=DEFAULT_DECK_DIR, metavar="OUTDIR")
    b.add_argument("--no-figures", action="store_true", help="skip rendering the figures")
    b.set_defaults(func=cmd_slides_build)
    d = actions.add_parser("pdf", help="print the deck to a PDF for handouts")
    d.add_argument("deck", nargs="?", default=DEFAULT_DECK_DIR, help="the built deck folder")
    d.add_argument("-o", "--output", metavar="OUT.pdf", help="default: DECK/slides.pdf")
    d.set_defaults(func=cmd_slides_pdf)

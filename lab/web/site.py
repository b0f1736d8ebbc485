"""The web lab as a static site: page assets, the shader files and a manifest of models."""

from __future__ import annotations

import contextlib
import functools
import http.server
import json
import shutil
import threading
from collections.abc import Iterator
from pathlib import Path

from lab import constants, views
from lab.models import SHADER_DIR, ModelError, model_names, parse_model
from lab.presets import read_preset, shipped_presets
from lab.resources import data_dir

STATIC_DIR = Path(__file__).resolve().parent / "static"
MEASURED_MODEL = Path(__file__).resolve().parents[1] / "measured" / "measured.glsl"


def presets() -> list[dict]:
    """The desktop lab's shipped presets (the same TOML files), as the page reads them.

    A preset that does not parse is left out here; the desktop lab reports its error.
    """
    out = []
    for path in shipped_presets():
        try:
            data = read_preset(path)
        except ModelError:
            continue
        out.append({"file": path.name, **data})
    return out


def library_headers() -> dict[str, dict]:
    """Each library model's parsed header (Model.header), or {"error": ...} for a file
    whose header does not parse, labelled as the page labels it."""
    out = {}
    for name in model_names():
        label = f"shaders/brdfs/{name}.glsl"
        try:
            code = (SHADER_DIR / "brdfs" / f"{name}.glsl").read_text(encoding="utf-8")
            out[name] = parse_model(code, label, name).header()
        except ModelError as err:
            out[name] = {"error": str(err)}
    return out


def view_pages() -> dict[str, Path]:
    """Each view's page module, where it has one: NAME.js beside the view's Python module
    (a plug-in's, a test's), else lab/web/static/views/NAME.js. The page loads them from
    views/NAME.js; a view without one (the sphere and the polar plot, which every panel
    draws itself) is left out."""
    found = {}
    for spec in views.all_views():
        for path in (
            Path(views.module_file(spec.name)).with_name(f"{spec.name}.js"),
            STATIC_DIR / "views" / f"{spec.name}.js",
        ):
            if path.is_file():
                found[spec.name] = path
                break
    return found


def views_manifest() -> list[dict]:
    """The registry's views (lab/views), each with the address of its page module."""
    pages = view_pages()
    return [
        {**view, "page": f"views/{view['name']}.js"} if view["name"] in pages else view
        for view in views.manifest()
    ]


def manifest() -> dict:
    """What the page loads: the model names and their parsed headers, every shader file
    (paths under shaders/, and their texts: one request instead of forty at load), the
    lab's constants and the shipped presets."""
    files = sorted(p.relative_to(SHADER_DIR).as_posix() for p in SHADER_DIR.rglob("*.glsl"))
    return {
        "models": model_names(),
        "library": library_headers(),
        "files": files,
        "sources": {f: (SHADER_DIR / f).read_text(encoding="utf-8") for f in files},
        "constants": constants.as_dict(),
        "views": views_manifest(),
        "presets": presets(),
        "exercises": exercise_list(),
        # The measured model's file: a table opened in the page is drawn by it.
        "measured_model": MEASURED_MODEL.read_text(encoding="utf-8"),
        "measured_table": measured_table(),
        "environments": environments(),
    }


def measured_table() -> dict:
    """What the page's measured.js reads a MERL .binary table by: lab/measured/merl.py's
    header size, largest dimension, MERL's own dimensions and channel scales, and the
    texture unit of lab/measured/model.py."""
    from lab.measured import merl
    from lab.measured.model import TABLE_UNIT

    return {
        "header_bytes": merl.HEADER_BYTES,
        "max_dim": merl.MAX_DIM,
        "dims": list(merl.MERL_DIMS),
        "scale": [float(s) for s in merl.SCALE],
        "unit": TABLE_UNIT,
    }


def environments() -> dict:
    """The procedural maps (lab/ibl/environments.py) of the IBL view and the deck's Monte
    Carlo demo, served as environments/NAME.f32: float32 RGB, row 0 the zenith; and the
    strategy "auto" runs under each (lab.ibl.integrator.auto_strategy)."""
    from lab.ibl.environments import DEFAULT_SIZE, PROCEDURAL, contrast, procedural
    from lab.ibl.integrator import auto_strategy

    auto = {name: auto_strategy(contrast(procedural(name, DEFAULT_SIZE))) for name in PROCEDURAL}
    return {
        "names": list(PROCEDURAL),
        "width": DEFAULT_SIZE[0],
        "height": DEFAULT_SIZE[1],
        "auto": auto,
    }


def environment_bytes(name: str) -> bytes | None:
    """One procedural map as the page loads it, or None for an unknown name."""
    from lab.ibl.environments import DEFAULT_SIZE, PROCEDURAL, procedural

    if name not in PROCEDURAL:
        return None
    return procedural(name, DEFAULT_SIZE).astype("<f4").tobytes()


def exercise_list() -> list[dict]:
    """The exercises' folder names and titles, for the page's picker (the checks and
    references load with exercises.json when one is opened)."""
    from lab.grading.exercise import ExerciseError, find_exercises

    try:
        return [{"name": e.name, "title": e.title} for e in find_exercises(data_dir("exercises"))]
    except ExerciseError:
        return []


def export(outdir: str | Path) -> Path:
    """Write a self-contained static site (page, shaders, manifest.json) into `outdir`."""
    outdir = Path(outdir)
    outdir.mkdir(parents=True, exist_ok=True)
    for item in STATIC_DIR.iterdir():
        if item.is_file():
            shutil.copy2(item, outdir / item.name)
    pages = outdir / "views"
    if pages.exists():
        shutil.rmtree(pages)
    pages.mkdir()
    for name, path in view_pages().items():
        shutil.copy2(path, pages / f"{name}.js")
    target = outdir / "shaders"
    if target.exists():
        shutil.rmtree(target)
    shutil.copytree(SHADER_DIR, target, ignore=shutil.ignore_patterns("__pycache__"))
    (outdir / "manifest.json").write_text(json.dumps(manifest(), indent=1) + "\n", encoding="utf-8")
    (outdir / "exercises.json").write_text(json.dumps(exercises_json()), encoding="utf-8")
    maps = outdir / "environments"
    maps.mkdir(exist_ok=True)
    for name in environments()["names"]:
        (maps / f"{name}.f32").write_bytes(environment_bytes(name))
    (outdir / ".nojekyll").write_text("", encoding="utf-8")  # GitHub Pages: serve files as-is
    return outdir / "index.html"


def exercises_json() -> dict:
    from lab.web.exercises import exercises_manifest

    return exercises_manifest()


class LabHandler(http.server.SimpleHTTPRequestHandler):
    """Serves the page from lab/web/static and the live shader files from shaders/.

    Nothing is cached, so an edited model shows up on reload.
    """

    extensions_map = {
        **http.server.SimpleHTTPRequestHandler.extensions_map,
        ".js": "text/javascript",
        ".mjs": "text/javascript",
        ".glsl": "text/plain; charset=utf-8",
        ".md": "text/plain; charset=utf-8",
    }

    def translate_path(self, path: str) -> str:
        clean = path.split("?", 1)[0].split("#", 1)[0]
        if clean.startswith("/views/") and clean.endswith(".js"):
            page = view_pages().get(clean[len("/views/") : -len(".js")])
            if page is not None:
                return str(page)
        if clean == "/shaders" or clean.startswith("/shaders/"):
            base = super().translate_path(clean[len("/shaders") :] or "/")
            relative = Path(base).relative_to(Path(self.directory).resolve())
            return str(SHADER_DIR / relative)
        return super().translate_path(path)

    def do_GET(self) -> None:  # noqa: N802 (http.server's naming)
        made = {"/manifest.json": manifest, "/exercises.json": exercises_json}
        clean = self.path.split("?", 1)[0]
        if clean.startswith("/environments/") and clean.endswith(".f32"):
            self.send_bytes(environment_bytes(clean[len("/environments/") : -len(".f32")]))
            return
        page = made.get(clean)
        if page is not None:
            body = json.dumps(page()).encode()
            self.send_response(200)
            self.send_header("Content-Type", "application/json")
            self.send_header("Content-Length", str(len(body)))
            self.end_headers()
            self.wfile.write(body)
            return
        super().do_GET()

    def send_bytes(self, body: bytes | None) -> None:
        if body is None:
            self.send_error(404, "no such environment")
            return
        self.send_response(200)
        self.send_header("Content-Type", "application/octet-stream")
        self.send_header("Content-Length", str(len(body)))
        self.end_headers()
        self.wfile.write(body)

    def end_headers(self) -> None:
        self.send_header("Cache-Control", "no-store")
        super().end_headers()

    def log_message(self, format: str, *args) -> None:  # noqa: A002
        pass  # quiet: the page's own errors are what matter


class QuietStaticHandler(LabHandler):
    """Serves a directory as it is (an exported site or a built deck)."""

    def translate_path(self, path: str) -> str:
        return http.server.SimpleHTTPRequestHandler.translate_path(self, path)

    def do_GET(self) -> None:  # noqa: N802
        http.server.SimpleHTTPRequestHandler.do_GET(self)


def make_server(port: int = 0, directory: str | Path | None = None) -> http.server.HTTPServer:
    """A localhost server for the live lab, or for `directory` when given."""
    if directory is None:
        handler = functools.partial(LabHandler, directory=str(STATIC_DIR))
    else:
        handler = functools.partial(QuietStaticHandler, directory=str(directory))
    return http.server.ThreadingHTTPServer(("127.0.0.1", port), handler)


@contextlib.contextmanager
def serving(directory: str | Path | None = None) -> Iterator[str]:
    """Serve in a background thread; yields the base URL (ending in '/')."""
    server = make_server(0, directory)
    thread = threading.Thread(target=server.serve_forever, daemon=True)
    thread.start()
    try:
        yield f"http://127.0.0.1:{server.server_address[1]}/"
    finally:
        server.shutdown()
        server.server_close()

"""The web lab's JavaScript held to the project's standard: ESLint (flat config in
lab/web/lint/, installed by `npm ci` from its committed lockfile), the 500-line cap, and
the modules' import graph (no cycles; layers import only downward)."""

from __future__ import annotations

import re
import subprocess
from pathlib import Path

WEB = Path(__file__).resolve().parent
LINT = WEB / "lint"
STATIC = WEB / "static"
MAX_LINES = 500
BUNDLES = {"editor.js"}  # built by esbuild from npm packages (lab/web/editor): not ours
IMPORT = re.compile(r'^\s*(?:import|export)\s[^;]*?\sfrom\s+"(\.{1,2}/[\w./-]+\.js)"', re.M)

# The page's layers, lowest first: a module imports only from its own layer or one below.
# base: parsing, assembly, mirrors of Python rules, DOM and GL helpers, the state; views:
# one page module per registered view (loaded by name from the manifest, never imported by
# the page); page: what puts the page together (panels, address, scheduling, start-up).
BASE = {
    "header.js",
    "values.js",
    "geometry.js",
    "assemble.js",
    "plotscale.js",
    "explorer.js",
    "measured.js",
    "flip.js",
    "diagnosis.js",
    "sampling.js",
    "sh.js",
    "iblsource.js",
    "store.js",
    "dom.js",
    "glkit.js",
    "deck.js",
    "viewkit.js",
    "submission.js",
    "state.js",
    "controls.js",
    "editor.js",
    "ibl_demo.js",
}


class LintError(RuntimeError):
    """ESLint could not run (one line, says what to do)."""


def modules() -> list[Path]:
    """Every JavaScript module of ours under lab/web (the page's, the views', the checks')."""
    found = (
        sorted(STATIC.glob("*.js")) + sorted(STATIC.glob("views/*.js")) + sorted(WEB.glob("*.mjs"))
    )
    return [p for p in found if p.name not in BUNDLES]


def layer(path: Path) -> int:
    """0 base, 1 views, 2 page."""
    if path.parent.name == "views":
        return 1
    return 0 if path.name in BASE else 2


def imports(path: Path) -> list[Path]:
    """The modules `path` imports statically (import ... from / export ... from)."""
    text = path.read_text(encoding="utf-8")
    return [(path.parent / name).resolve() for name in IMPORT.findall(text)]


def _run(command: list[str], what: str, timeout: float = 300) -> subprocess.CompletedProcess:
    try:
        return subprocess.run(
            command, cwd=WEB, capture_output=True, text=True, timeout=timeout, check=False
        )
    except FileNotFoundError:
        raise LintError(f"{command[0]} is not installed: apt-get install nodejs npm") from None
    except subprocess.TimeoutExpired:
        raise LintError(f"{what} took longer than {timeout:.0f} s") from None


def install() -> None:
    """`npm ci` in lab/web/lint unless node_modules already matches the lockfile."""
    lock = LINT / "package-lock.json"
    installed = LINT / "node_modules" / ".package-lock.json"
    if installed.is_file() and installed.stat().st_mtime >= lock.stat().st_mtime:
        return
    npm = ["npm", "ci", "--prefix", str(LINT), "--prefer-offline", "--no-audit", "--no-fund"]
    result = _run(npm, "npm ci in lab/web/lint")
    if result.returncode != 0:
        lines = [ln for ln in (result.stderr or result.stdout).splitlines() if ln.strip()]
        raise LintError(
            f"npm ci in lab/web/lint failed: {lines[-1] if lines else result.returncode}"
        )


def eslint() -> str:
    """ESLint's findings on lab/web ("" when clean)."""
    install()
    binary = LINT / "node_modules" / ".bin" / "eslint"
    command = [str(binary), "--config", "lint/eslint.config.js", "--max-warnings", "0", "."]
    result = _run(command, "eslint")
    if result.returncode not in (0, 1):
        raise LintError(f"eslint did not run: {(result.stderr or result.stdout).strip()}")
    return result.stdout.strip() if result.returncode else ""

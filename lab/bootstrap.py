"""Set-up on a fresh machine, with the standard library only: `python3 -m lab [test|ARGS]`.

Creates (or reuses) the virtual environment `.venv`, installs what is missing there and,
when running as root on Debian/Ubuntu, the system packages; then runs the lab or the
test suite inside it.
"""

from __future__ import annotations

import hashlib
import os
import shutil
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
VENV = ROOT / ".venv"
VENV_BIN = VENV / ("Scripts" if os.name == "nt" else "bin")  # Windows names it Scripts
STAMP = VENV / ".brdf-lab-installed"

# Debian package -> a command that, when found on PATH, makes the package unnecessary.
RUN_PACKAGES = {
    "python3-venv": None,
    "libegl1": None,
    "libgl1-mesa-dri": None,
    "libgles2": None,
    "libxkbcommon-x11-0": None,
    "libxcb-cursor0": None,
    "libxcb-icccm4": None,
    "libxcb-image0": None,
    "libxcb-keysyms1": None,
    "libxcb-render-util0": None,
    "libxcb-shape0": None,
    "libxcb-xinerama0": None,
    "libxcb-xkb1": None,
    "libxcb-randr0": None,
    "libdbus-1-3": None,
    "libfontconfig1": None,
    "libglib2.0-0": None,
    "fonts-dejavu-core": None,
    "glslang-tools": "glslangValidator",  # the grader preprocesses submissions with it
    "spirv-tools": "spirv-opt",  # the similarity report compares optimised SPIR-V
}
TEST_PACKAGES = {
    "xvfb": "Xvfb",
    "xauth": "xauth",
    "chromium": "chromium",
    "nodejs": "node",
    "npm": "npm",
    "golang-go": "go",  # builds actionlint, which checks the Classroom workflow
    "shellcheck": "shellcheck",  # actionlint checks the workflows' scripts with it
}
# The Go module of the workflow linter the course tests run (built into .venv/bin).
ACTIONLINT = "github.com/rhysd/actionlint/cmd/actionlint@v1.7.12"


def say(message: str) -> None:
    print(f"[brdf-lab setup] {message}", flush=True)


def missing_debian_packages(packages: dict[str, str | None]) -> list[str]:
    if not shutil.which("dpkg-query"):
        return []
    missing = []
    for package, command in packages.items():
        if command and shutil.which(command):
            continue
        result = subprocess.run(
            ["dpkg-query", "-W", "-f=${Status}", package], capture_output=True, text=True
        )
        if "install ok installed" not in result.stdout:
            missing.append(package)
    return missing


def ensure_system_packages(packages: dict[str, str | None]) -> None:
    missing = missing_debian_packages(packages)
    if not missing:
        return
    command = ["apt-get", "install", "-y", "--no-install-recommends", *missing]
    if os.geteuid() != 0:
        say("some system packages are missing; install them with:")
        print("    sudo apt-get update && sudo " + " ".join(command), flush=True)
        return
    say("installing system packages: " + " ".join(missing))
    env = {**os.environ, "DEBIAN_FRONTEND": "noninteractive"}
    subprocess.run(["apt-get", "update", "-q"], check=False, env=env, stdout=subprocess.DEVNULL)
    subprocess.run(command, check=True, env=env, stdout=subprocess.DEVNULL)


def venv_python() -> Path:
    return VENV_BIN / ("python.exe" if os.name == "nt" else "python")


def ensure_venv(with_tests: bool) -> None:
    if not venv_python().exists():
        say(f"creating the virtual environment {VENV}")
        subprocess.run([sys.executable, "-m", "venv", str(VENV)], check=True)
    # The stamp records which pyproject.toml and requirement lists were installed, and
    # whether with test extras: a dependency added to a list reinstalls too.
    sources = [ROOT / "pyproject.toml", *sorted((ROOT / "lab").glob("requirements-*.txt"))]
    digest = hashlib.sha256(b"".join(p.read_bytes() for p in sources)).hexdigest()
    have = STAMP.read_text().split() if STAMP.exists() else []
    if have and have[0] == digest and (not with_tests or "test" in have):
        return
    say("installing Python packages into .venv (first run only)")
    pip = [str(venv_python()), "-m", "pip", "install", "-q", "--disable-pip-version-check"]
    subprocess.run([*pip, "--upgrade", "pip"], check=True)
    target = ".[test]" if with_tests else "."
    subprocess.run([*pip, "-e", target], check=True, cwd=ROOT)
    STAMP.write_text(digest + (" test" if with_tests else ""))


def ensure_actionlint() -> None:
    """actionlint in .venv/bin, built with Go from the module proxy (once)."""
    if (VENV_BIN / "actionlint").exists():
        return
    # A Go from go.dev (/usr/local/go) before the distribution's, which may be too old.
    local = Path("/usr/local/go/bin/go")
    go = str(local) if local.exists() else shutil.which("go")
    if go is None:
        say("Go is missing: the Classroom workflow's actionlint test cannot run")
        return
    say(f"building actionlint into {VENV_BIN} (first run only)")
    env = {**os.environ, "GOBIN": str(VENV_BIN), "GOTOOLCHAIN": "auto"}
    subprocess.run([go, "install", ACTIONLINT], check=False, env=env)


def main(argv: list[str]) -> int:
    testing = bool(argv) and argv[0] == "test"
    ensure_system_packages({**RUN_PACKAGES, **(TEST_PACKAGES if testing else {})})
    ensure_venv(with_tests=testing)
    if testing:
        ensure_actionlint()
    env = {**os.environ, "PYTHONUNBUFFERED": "1"}
    if testing:
        env["BRDF_LAB_STRICT"] = "1"  # a skipped test would hide a missing install
        command = [str(venv_python()), "-m", "pytest", *argv[1:]]
        if not os.environ.get("DISPLAY") and shutil.which("xvfb-run"):
            command = ["xvfb-run", "-a", "-s", "-screen 0 1920x1080x24", *command]
    else:
        command = [str(VENV_BIN / "brdf-lab"), *argv]
    return subprocess.run(command, cwd=ROOT, env=env).returncode


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))

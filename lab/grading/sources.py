"""Where a course's grader and definitions come from: the install line and the archive.

`install_line` turns what an instructor gives `course init --install` (a PyPI version, a
wheel URL, a git URL pinned to a tag or commit) into the one pip requirement every
generated file uses; `fetch` downloads a definitions archive, with the token of a private
repository; `install_problem` and `placeholder` are what `course check` asks of them.
"""

from __future__ import annotations

import re
import subprocess
import urllib.error
import urllib.parse
import urllib.request
from pathlib import Path

from lab import __version__
from lab.errors import UsageError
from lab.resources import REPOSITORY
from lab.resources import install_line as release_line

TOKEN_SECRET = "BRDF_LAB_DEFINITIONS_TOKEN"  # the Actions secret, and the variable init reads
VERSION = re.compile(r"\d+(\.\d+)*((a|b|rc|\.post|\.dev)\d+)?")
PLACEHOLDERS = (
    re.compile(r"X\.Y\.Z|\bOWNER\b|\bORG\b|<[^<>]*>|__[A-Z0-9_]+__"),  # written in capitals
    re.compile(r"example\.(com|org)|github\.com/example/", re.I),
)


def default_install() -> str:
    """The install line that works today: this release's tag of the lab's repository."""
    return release_line()


def install_line(spec: str | None) -> str:
    """A pip requirement for the grader from --install (None: default_install())."""
    if spec is None:
        return default_install()
    spec = spec.strip()
    if VERSION.fullmatch(spec):
        return f"brdf-lab=={spec}"
    if spec.startswith("brdf-lab"):
        return spec
    if spec.startswith(("https://", "http://")) and spec.endswith(".whl"):
        return f"brdf-lab @ {spec}"
    if spec.startswith("git+"):
        if not re.search(r"@[^/@]+$", spec.split("://", 1)[-1]):
            raise UsageError(
                f"--install {spec}: pin a tag or commit, e.g. {spec}@v{__version__}: an "
                "unpinned branch changes the grader under the students"
            )
        return f"brdf-lab @ {spec}"
    raise UsageError(
        f"--install {spec!r}: give a released version ({__version__}), a wheel URL "
        f"(https://.../brdf_lab-{__version__}-py3-none-any.whl) or a pinned git URL "
        f"(git+{REPOSITORY}@v{__version__})"
    )


def placeholder(text: str) -> str:
    """The placeholder in `text` ('' when there is none)."""
    found = [m.group(0) for pattern in PLACEHOLDERS if (m := pattern.search(text))]
    return found[0] if found else ""


class _KeepTokenHome(urllib.request.HTTPRedirectHandler):
    """Redirects without the token to another host: GitHub sends a private release asset
    from a signed storage URL, which refuses a second credential (curl -L does the same)."""

    def redirect_request(self, req, fp, code, msg, headers, newurl):
        new = super().redirect_request(req, fp, code, msg, headers, newurl)
        here, there = urllib.parse.urlsplit(req.full_url), urllib.parse.urlsplit(newurl)
        if new is not None and here.netloc != there.netloc:
            new.remove_header("Authorization")
        return new


def _open(url: str, token: str | None = None, method: str = "GET"):
    headers = {"User-Agent": "brdf-lab"}
    if token:
        headers["Authorization"] = f"Bearer {token}"
        headers["Accept"] = "application/octet-stream"  # a release asset's bytes, not JSON
    request = urllib.request.Request(url, headers=headers, method=method)
    return urllib.request.build_opener(_KeepTokenHome).open(request, timeout=60)


def fetch(source: str, token: str | None = None) -> tuple[str, bytes]:
    """(URL for the workflow, bytes) of a definitions archive given as a URL or a path."""
    if "://" not in source:
        path = Path(source).resolve()
        if not path.is_file():
            raise UsageError(f"--definitions {source}: no such file")
        return path.as_uri(), path.read_bytes()
    try:
        with _open(source, token) as answer:
            return source, answer.read()
    except (urllib.error.URLError, OSError, ValueError) as err:
        why = "no token given: set " + TOKEN_SECRET if not token else "with the token given"
        raise UsageError(
            f"cannot download the definitions {source} ({err}; {why}): pass --definitions "
            "with the URL or path of an archive (.tar.gz) holding exercises/ and solutions/"
        ) from None


def readable_without_token(url: str) -> bool:
    """Can anyone download `url`? (Then the solutions in it are public.)"""
    try:
        with _open(url) as answer:
            return answer.status == 200 and bool(answer.read(1))
    except (urllib.error.URLError, OSError, ValueError):
        return False


def install_problem(line: str) -> str:
    """Why `line` cannot be installed from where it points ('' when it can)."""
    name, _, where = line.partition(" @ ")
    try:
        if not where:
            version = line.split("==", 1)[1] if "==" in line else ""
            if not version:
                return f"'{line}' pins no version: write brdf-lab=={__version__}"
            with _open(f"https://pypi.org/pypi/brdf-lab/{version}/json"):
                return ""
        if where.startswith("git+"):
            url, _, ref = where[4:].rpartition("@")
            done = subprocess.run(
                ["git", "ls-remote", url, ref, f"{ref}^{{}}"],
                capture_output=True,
                text=True,
                timeout=60,
            )
            if done.returncode != 0:
                return f"git cannot read {url}: {done.stderr.strip()[:200]}"
            if not done.stdout.strip() and not re.fullmatch(r"[0-9a-f]{7,40}", ref):
                return f"{url} has no tag or branch {ref!r}"
            return ""
        with _open(where, method="HEAD"):
            return ""
    except (urllib.error.URLError, OSError, ValueError, subprocess.SubprocessError) as err:
        return f"'{line}' cannot be downloaded ({err})"

"""What a submission is allowed to be: its own files, its own code, read by a real preprocessor.

A student's file may not pull in the lab's code (`@include` beyond the stub's own lines,
`#include`), may not steer the compiler (`#version`, `#extension`) or the error
locations (`#line`), and may not reach outside its folder through links. What the file
defines is decided on the text after glslang's preprocessor has run, so code inside
`#if 0` or hidden behind macros neither counts nor escapes the loop guard.
"""

from __future__ import annotations

import os
import re
import selectors
import shutil
import subprocess
import tempfile
import time
from pathlib import Path

from lab.constants import glsl_defines

# Directives the host owns; a submission containing one gets a message naming the line.
FORBIDDEN = {
    "version": "the lab writes the #version line itself",
    "extension": "extensions are not available in the lab (the web lab and GPUs differ)",
    "line": "#line would make errors point at the wrong file and line",
    "include": "GLSL has no #include; a submission must contain all of its own code",
}
COMMENT = re.compile(r"//[^\n]*|/\*.*?(?:\*/|\Z)", re.S)
DIRECTIVE = re.compile(r"^\s*#\s*([A-Za-z_]\w*)")
AT_INCLUDE = re.compile(r"@\s*include\b\s*(\S*)")

PREPROCESS_SECONDS = 5.0  # below the grader's 10 s per check, so this message wins
PREPROCESS_MEMORY = 1 << 30  # bytes of address space for glslangValidator
MAX_EXPANDED = 1 << 20  # characters of preprocessed text: more is a macro bomb


class SourceError(ValueError):
    """A submission's text breaks a rule; `line` is 1-based in the student's file."""

    def __init__(self, message: str, line: int | None = None):
        self.line = line
        super().__init__(message)


def logical_lines(code: str) -> list[tuple[int, str]]:
    """(first physical line, text) of each logical line, continuations spliced and comments
    blanked, in the order the GLSL preprocessor applies them (so `/**/#extension` and
    `#\\`+newline+`extension` are seen as the directives they are)."""
    spliced: list[tuple[int, str]] = []
    buffer, start = "", 0
    for number, line in enumerate(code.split("\n"), start=1):
        line = line.removesuffix("\r")
        if not buffer and not start:
            start = number
        if line.endswith("\\"):
            buffer += line[:-1]
            continue
        spliced.append((start, buffer + line))
        buffer, start = "", 0
    if start:
        spliced.append((start, buffer))
    text = "\n".join(line for _, line in spliced)
    text = COMMENT.sub(lambda m: "\n" * m.group(0).count("\n") + " ", text)
    return [(spliced[i][0], line) for i, line in enumerate(text.split("\n"))]


def check_directives(code: str, label: str, allowed_includes: list[str]) -> None:
    """Reject host-owned directives and `@include` lines the stub does not have."""
    for line, text in logical_lines(code):
        match = DIRECTIVE.match(text)
        if match and match.group(1) in FORBIDDEN:
            name = match.group(1)
            raise SourceError(f"{label}:{line}: remove the '#{name}' line: {FORBIDDEN[name]}", line)
    for line, text in enumerate(code.splitlines(), start=1):
        match = AT_INCLUDE.search(text)
        if match and match.group(1) not in allowed_includes:
            allowed = ", ".join(allowed_includes) or "none"
            raise SourceError(
                f"{label}:{line}: remove '@include {match.group(1)}': a submission contains "
                f"its own code; the includes the stub has ({allowed}) are the only ones allowed",
                line,
            )


def glslang() -> str:
    """The path of glslangValidator, or SourceError saying how to install it."""
    path = shutil.which("glslangValidator")
    if path is None:
        raise SourceError(
            "the grader needs glslangValidator to read submissions and it is not installed: "
            "run 'sudo apt-get install glslang-tools' (Debian/Ubuntu) or 'python3 -m lab' "
            "as root, then grade again (ask your instructor)"
        )
    return path


def _limit_memory() -> None:  # runs in the child, before exec
    import resource

    hard = resource.getrlimit(resource.RLIMIT_AS)[1]
    soft = PREPROCESS_MEMORY if hard == resource.RLIM_INFINITY else min(PREPROCESS_MEMORY, hard)
    resource.setrlimit(resource.RLIMIT_AS, (soft, hard))


def capped(command: list[str]) -> tuple[list[str], object]:
    """(command, preexec_fn) that run `command` with at most PREPROCESS_MEMORY of address
    space. util-linux's prlimit sets the cap before the exec, and lets Python start the
    child with vfork; a function run in a fork of this (large) process is the fallback."""
    import resource

    prlimit = shutil.which("prlimit")
    hard = resource.getrlimit(resource.RLIMIT_AS)[1]
    if prlimit and hard == resource.RLIM_INFINITY:
        return [prlimit, f"--as={PREPROCESS_MEMORY}:", "--", *command], None
    return command, _limit_memory


def _run_capped(command: list[str], what: str, label: str) -> tuple[int, bytes, str]:
    """Run glslangValidator with a memory cap, a time limit and a cap on its output, so a
    macro bomb ends in a second with a message instead of filling memory or the disk."""
    command, preexec = capped(command)
    with tempfile.TemporaryFile() as log:
        process = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=log, preexec_fn=preexec)
        chunks, size = [], 0
        deadline = time.monotonic() + PREPROCESS_SECONDS
        with selectors.DefaultSelector() as selector:
            selector.register(process.stdout, selectors.EVENT_READ)
            while True:
                left = deadline - time.monotonic()
                if left <= 0 or size > MAX_EXPANDED:
                    process.kill()
                    process.wait()
                    if size > MAX_EXPANDED:
                        raise SourceError(
                            f"{label}: macros expand the file to over {MAX_EXPANDED // 1024} KB "
                            "of code (a macro bomb?): write the code out instead of generating it"
                        )
                    raise SourceError(
                        f"{label}: {what} did not finish within {PREPROCESS_SECONDS:g} s: "
                        "a macro expands too far (a macro bomb?)"
                    )
                if not selector.select(left):
                    continue
                chunk = os.read(process.stdout.fileno(), 1 << 16)
                if not chunk:
                    break
                chunks.append(chunk)
                size += len(chunk)
        process.stdout.close()
        code = process.wait()
        log.seek(0)
        return code, b"".join(chunks), log.read().decode("utf-8", "replace")


def preprocess(code: str, label: str) -> str:
    """The submission after the GLSL preprocessor, line for line (glslang keeps the line
    structure: directives and comments become blank lines). Raises SourceError."""
    prelude = "#version 330 core\n" + glsl_defines().rstrip("\n") + "\n"
    skip = prelude.count("\n")
    with tempfile.NamedTemporaryFile(
        "w", suffix=".frag", prefix="brdf-lab-", encoding="utf-8"
    ) as f:
        f.write(prelude + code)
        f.flush()
        status, raw, log = _run_capped([glslang(), "-E", f.name], "the preprocessor", label)
    out = raw.decode("utf-8", "replace")
    if status != 0:
        for line_text in (log + out).splitlines():
            match = re.match(r"^ERROR:\s*[^:]*:(\d+):\s*(.*)$", line_text)
            if match:
                line = int(match.group(1)) - skip
                raise SourceError(f"{label}:{line}: {match.group(2).strip()}", line)
        why = "it ran out of memory" if status < 0 else (log + out).strip()[-300:]
        raise SourceError(
            f"{label}: the GLSL preprocessor rejected the file ({why}); "
            "a macro that expands too far?"
        )
    lines = out.split("\n")
    body = lines[skip:] if len(lines) > skip else []
    return "\n".join(body).rstrip("\n") + "\n"


def linked_part(root: Path, path: Path) -> Path | None:
    """The first symbolic link on the way from `root` (included) down to `path`, or None.

    Links are refused rather than followed: a link could name the solutions, another
    student's folder or a file outside the submission."""
    try:
        relative = path.relative_to(root)
    except ValueError:
        return path if path.is_symlink() else None
    current = root
    if current.is_symlink():
        return current
    for part in relative.parts:
        current = current / part
        if current.is_symlink():
            return current
    return None


def portability_warnings(model, label: str) -> list[str]:
    """Compile the model as GLSL ES 3.00, as the web lab does; each error there (code only
    desktop GLSL accepts, such as pow(x, 5) or max(v, 0) with an int) becomes a warning
    naming the student's line. Empty when the file is portable or glslang is missing."""
    from lab.glsl import assemble_fragment

    path = shutil.which("glslangValidator")
    if path is None:
        return []
    try:
        source = assemble_fragment(model, "probe", target="300es")
        command, preexec = capped([path, "--stdin", "-S", "frag"])
        result = subprocess.run(
            command,
            input=source.text.encode("utf-8"),
            capture_output=True,
            timeout=PREPROCESS_SECONDS,
            preexec_fn=preexec,
        )
    except (OSError, ValueError, subprocess.TimeoutExpired):
        return []
    if result.returncode == 0:
        return []
    warnings = []
    log = (result.stdout + result.stderr).decode("utf-8", "replace")
    for raw in log.splitlines():
        match = re.match(r"^ERROR:\s*\d+:(\d+):\s*(.*)$", raw)
        if not match:
            continue
        file, line = source.origin(int(match.group(1)))
        if file != label or "compilation terminated" in raw:
            continue  # only the student's own lines; the lab's code is portable
        warnings.append(
            f"{file}:{line}: the web lab (WebGL, GLSL ES 3.00) will reject this line: "
            f"{match.group(2).strip()}; write float constants such as 5.0 to fix it"
        )
    return list(dict.fromkeys(warnings))

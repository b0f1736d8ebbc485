"""The one place that creates OpenGL contexts."""

from __future__ import annotations

import sys

import moderngl

_offscreen: moderngl.Context | None = None


INSTALL_HINTS = {  # what to do without OpenGL 3.3; the README's "macOS and Windows" says more
    "linux": "On Debian/Ubuntu install Mesa's drivers: apt-get install libegl1 libgl1-mesa-dri",
    "win32": "Install your graphics card's driver from NVIDIA, AMD or Intel (Windows' basic "
    "display driver has no OpenGL 3.3); in a VM use Mesa's opengl32.dll next to python.exe, "
    "or the web lab ('brdf-lab serve')",
    "darwin": "macOS provides OpenGL 4.1 itself: run from a logged-in desktop session "
    "(not over plain ssh), or use the web lab ('brdf-lab serve')",
}


class GLUnavailable(RuntimeError):
    """No OpenGL 3.3 context could be made; the message says what to install."""


def get_context(window: bool = False) -> moderngl.Context:
    """An OpenGL >= 3.3 context.

    `window=True` wraps the context a Qt or GLFW window has made current; otherwise a
    standalone EGL context is created once per process and shared (no display needed).
    """
    global _offscreen
    if window:
        return moderngl.create_context(require=330)
    if _offscreen is None:
        errors = []
        # EGL needs no display (servers, CI); elsewhere the platform's own standalone
        # context (WGL on Windows, CGL on macOS, GLX on Linux desktops) is the fallback.
        backends = ["egl", None] if sys.platform.startswith("linux") else [None]
        for backend in backends:
            options = {"backend": backend} if backend else {}
            try:
                _offscreen = moderngl.create_context(standalone=True, require=330, **options)
                break
            except Exception as err:  # glcontext raises plain Exceptions with the cause
                errors.append(f"{backend or 'default'}: {err}")
        else:
            raise GLUnavailable(
                f"cannot create an offscreen OpenGL 3.3 context ({'; '.join(errors)}). "
                + INSTALL_HINTS.get(sys.platform, INSTALL_HINTS["linux"])
            )
    return _offscreen


def has_offscreen_context() -> bool:
    """Whether this process has made its offscreen context (a forked child would share it)."""
    return _offscreen is not None


def describe(ctx: moderngl.Context) -> str:
    """Renderer and version, e.g. 'llvmpipe (LLVM 15.0.6, 256 bits), OpenGL 4.5'."""
    major, minor = divmod(ctx.version_code // 10, 10)
    return f"{ctx.info['GL_RENDERER']}, OpenGL {major}.{minor}"


def table_texture(ctx: moderngl.Context, array) -> moderngl.Texture:
    """A float32 table (rows, columns[, components]) as a texture read texel by texel
    (NEAREST): a lookup table or a sampling distribution, never filtered."""
    import numpy as np

    data = np.ascontiguousarray(array, dtype=np.float32)
    rows, columns = data.shape[:2]
    components = 1 if data.ndim == 2 else data.shape[2]
    texture = ctx.texture((columns, rows), components, data, dtype="f4")
    texture.filter = (moderngl.NEAREST, moderngl.NEAREST)
    return texture

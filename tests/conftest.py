"""Shared fixtures: one offscreen GL context for the whole session, checked for GL errors."""

from __future__ import annotations

from pathlib import Path

import pytest

OUTPUT = Path(__file__).parent / "output"


@pytest.fixture(scope="session")
def ctx():
    from lab.gl import get_context

    return get_context()


@pytest.fixture(scope="session")
def renderer(ctx):
    from lab.render import Renderer

    return Renderer(ctx)


@pytest.fixture
def gl_clean(ctx):
    """Fail a test that leaves an OpenGL error behind."""
    assert ctx.error == "GL_NO_ERROR"
    yield ctx
    assert ctx.error == "GL_NO_ERROR"


@pytest.fixture(scope="session")
def output_dir() -> Path:
    OUTPUT.mkdir(exist_ok=True)
    return OUTPUT

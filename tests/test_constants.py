"""The lab's shared constants live once (lab/constants.py) and reach GLSL and the page."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np

from lab import constants, glsl
from lab.gl import get_context
from lab.web.site import manifest

ROOT = Path(__file__).resolve().parent.parent


def test_glsl_sees_the_python_values() -> None:
    ctx = get_context()
    fragment = glsl.header() + (
        "out vec4 color;\n"
        "void main() { color = vec4(LAB_LUMA, float(LAB_MAX_LIGHTS) + LAB_GRAZING_DEG); }\n"
    )
    program = ctx.program(vertex_shader=glsl.vertex_source(), fragment_shader=fragment)
    target = ctx.simple_framebuffer((1, 1), components=4, dtype="f4")
    target.use()
    ctx.vertex_array(program, []).render(vertices=3)
    got = np.frombuffer(target.read(components=4, dtype="f4"), dtype=np.float32)
    want = [*constants.LUMA, constants.MAX_LIGHTS + constants.GRAZING_DEG]
    np.testing.assert_allclose(got, want, rtol=1e-6)


def test_page_manifest_carries_the_constants() -> None:
    assert manifest()["constants"] == constants.as_dict()


def test_luminance_weights_are_written_once() -> None:
    """A second copy of the weights (Python, GLSL or JavaScript) would drift apart."""
    pattern = re.compile(r"0\.2126\b")
    copies = [
        path.relative_to(ROOT).as_posix()
        for folder in ("lab", "shaders")
        for path in (ROOT / folder).rglob("*")
        if path.suffix in (".py", ".glsl", ".js", ".mjs")
        and "node_modules" not in path.parts
        and pattern.search(path.read_text(encoding="utf-8", errors="replace"))
    ]
    assert copies == ["lab/constants.py"], copies

"""`brdf-lab watch FILE.glsl`: a small GLFW window for students editing a shader.

Shows the lit sphere and the polar lobe of their model, reloads on save, prints compile
errors with the file's line numbers (the last good version stays on screen). When the file
is an exercise's student file, it is rendered exactly as the grader renders the exercise's
sphere check (its parameters, lights and tone mapping; term exercises inside their library
model) and shown beside the reference image and a difference image. A sampling exercise's
file is judged by the grader's sampling checks instead (watch_sampler.py).
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

import numpy as np

from lab.app.student_file import StudentFile
from lab.glsl import ShaderCompileError, loop_warning
from lab.models import ModelError

PANEL = 320
QUAD = """
#version 330 core
uniform sampler2D u_image;
uniform vec4 u_rect;  // x, y, width, height in normalised device coordinates
out vec2 uv;
void main() {
    vec2 corner = vec2(float(gl_VertexID & 1), float((gl_VertexID >> 1) & 1));
    uv = vec2(corner.x, 1.0 - corner.y);
    gl_Position = vec4(u_rect.xy + corner * u_rect.zw, 0.0, 1.0);
}
"""
QUAD_FRAGMENT = """
#version 330 core
uniform sampler2D u_image;
in vec2 uv;
out vec4 color;
void main() { color = texture(u_image, uv); }
"""


class ExerciseView(StudentFile):
    """How the grader sees a student's file: its exercise, first sphere check, reference."""

    def __init__(self, path: Path):
        super().__init__(path)
        self.check = next(c for c in self.exercise.checks if c.kind == "sphere")
        self.reference_path = self.exercise.references / f"{self.check.name}.png"

    def shows(self) -> bool:
        return self.reference_path.is_file()

    def sphere(self, renderer, model) -> np.ndarray:
        """The sphere check's render, tone-mapped to 8-bit RGBA as its reference is."""
        from lab.grading.checks import expected_value, render

        return expected_value(render(renderer, model, self.check), self.check)


def polar_image(renderer, model, values, theta: float, phi: float) -> np.ndarray:
    """The polar lobe as an RGBA uint8 image (matplotlib), PANEL x PANEL."""
    from lab import plots

    fig, ax = plots.figure(polar=True)
    fig.set_size_inches(PANEL / 100, PANEL / 100)
    fig.set_dpi(100)
    lobe = renderer.polar(model, values, theta, phi)
    plots.draw_polar(ax, [(lobe, model.name, "tab:red")], theta, "f_r", fontsize=8)
    fig.tight_layout()
    fig.canvas.draw()
    image = np.asarray(fig.canvas.buffer_rgba()).copy()
    import matplotlib.pyplot as plt

    plt.close(fig)
    return image


def load_rgba(path: Path, size: int) -> np.ndarray:
    from PIL import Image

    return np.asarray(Image.open(path).convert("RGBA").resize((size, size), Image.NEAREST))


def load_rgba_array(image: np.ndarray, size: int) -> np.ndarray:
    """An 8-bit RGBA array scaled like the reference (nearest, so pixels stay comparable)."""
    from PIL import Image

    return np.asarray(Image.fromarray(image, "RGBA").resize((size, size), Image.NEAREST))


def model_panels(renderer, path: Path, exercise, reference, light) -> tuple[list, str]:
    """The sphere and polar lobe of the file (as the grader renders the exercise's sphere
    check, beside its reference and a difference image), and the status line."""
    from lab import plots
    from lab.app.state import load_any
    from lab.nonfinite import sphere_report
    from lab.render import direction

    if exercise:
        model = exercise.load(path)
        values = model.resolve(exercise.check.params)
        theirs = load_rgba_array(exercise.sphere(renderer, model), PANEL)
    else:
        model = load_any(path)
        values = model.defaults()
        sphere = renderer.sphere(model, values, light, size=PANEL)
        theirs = np.dstack(
            [plots.to_srgb8(sphere[..., :3]), (sphere[..., 3:] * 255).astype(np.uint8)]
        )
    images = [theirs, polar_image(renderer, model, values, *light)]
    if reference is not None:
        diff = np.abs(theirs[..., :3].astype(int) - reference[..., :3].astype(int))
        diff = np.clip(diff * 4, 0, 255).astype(np.uint8)
        images += [reference, np.dstack([diff, np.full(diff.shape[:2], 255, np.uint8)])]
    stop = renderer.loop_stop()
    if stop is not None:
        print(f"{time.strftime('%H:%M:%S')} warning: {loop_warning(model, stop[0])}")
    # Tone mapping hides NaN and Inf as black: look at the floats.
    floats = renderer.sphere(model, values, light, size=PANEL)
    problem = sphere_report(floats, direction(*light))
    return images, f"compiled, but {problem}" if problem else "OK"


def replace_textures(ctx, textures: list, images: list[np.ndarray]) -> list:
    """Textures of `images` (RGBA uint8), the previous ones released."""
    for texture in textures:
        texture.release()
    out = []
    for image in images:
        rgba = np.ascontiguousarray(image[..., :4])
        out.append(ctx.texture((rgba.shape[1], rgba.shape[0]), 4, rgba.tobytes()))
    return out


def watch(path: Path, light: tuple[float, float], frames: int = 0) -> int:
    """Run the viewer until the window closes (or `frames` frames, for tests)."""
    import glfw

    from lab.app.watch_sampler import SamplerView
    from lab.gl import get_context
    from lab.render import Renderer

    if not glfw.init():
        print("brdf-lab: cannot open a GLFW window (no display?)", file=sys.stderr)
        return 2
    exercise = ExerciseView.find(path.resolve())
    sampler = None if exercise else SamplerView.find(path.resolve())
    panels = 4 if exercise else 3 if sampler else 2
    glfw.window_hint(glfw.CONTEXT_VERSION_MAJOR, 3)
    glfw.window_hint(glfw.CONTEXT_VERSION_MINOR, 3)
    glfw.window_hint(glfw.OPENGL_PROFILE, glfw.OPENGL_CORE_PROFILE)
    glfw.window_hint(glfw.OPENGL_FORWARD_COMPAT, True)
    window = glfw.create_window(PANEL * panels, PANEL, f"brdf-lab watch {path.name}", None, None)
    if not window:
        glfw.terminate()
        print("brdf-lab: cannot open a GLFW window with OpenGL 3.3", file=sys.stderr)
        return 2
    glfw.make_context_current(window)
    ctx = get_context(window=True)
    renderer = Renderer(ctx)
    quad = ctx.program(vertex_shader=QUAD.strip(), fragment_shader=QUAD_FRAGMENT.strip())
    vao = ctx.vertex_array(quad, [])
    textures: list = []
    reference = load_rgba(exercise.reference_path, PANEL) if exercise else None
    mtime = -1.0
    shown = 0
    print(f"watching {path} (save the file to reload; close the window to stop)")
    if exercise:
        print(
            f"exercise {exercise.exercise.name}: showing check {exercise.check.name} beside "
            f"its reference image {exercise.reference_path}"
        )
    if sampler:
        print(
            f"exercise {sampler.exercise.name}: your "
            f"{'estimator' if sampler.exercise.estimator else 'sampler'}, judged by the checks "
            f"{', '.join(c.name for c in sampler.checks)} at each save"
        )
    while not glfw.window_should_close(window):
        stamp = path.stat().st_mtime if path.exists() else mtime
        if stamp != mtime:
            mtime = stamp
            try:
                if sampler:
                    lines, images = sampler.judge(renderer, sampler.load(path))
                    textures = replace_textures(ctx, textures, images)
                    status = "\n".join(["judged by the grader's checks:", *lines])
                else:
                    images, status = model_panels(renderer, path, exercise, reference, light)
                    textures = replace_textures(ctx, textures, images)
                print(f"{time.strftime('%H:%M:%S')} compiled {path.name}: {status}", flush=True)
            except (ModelError, ShaderCompileError) as err:
                print(
                    f"{time.strftime('%H:%M:%S')} {path.name} does not compile; "
                    f"showing the last good version:\n{err}",
                    flush=True,
                )
        ctx.screen.use()
        ctx.clear(0.16, 0.16, 0.17)
        width = 2.0 / panels
        for index, texture in enumerate(textures):
            texture.use(0)
            quad["u_rect"].value = (-1.0 + index * width, -1.0, width, 2.0)
            vao.render(mode=5, vertices=4)  # triangle strip
        glfw.swap_buffers(window)
        glfw.wait_events_timeout(0.25)
        shown += 1
        if frames and shown >= frames:
            break
    glfw.terminate()
    return 0

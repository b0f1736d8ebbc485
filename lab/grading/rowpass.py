"""A view of one row of inputs per pixel, each row shaded alone in its block of pixels.

Mesa's llvmpipe shades a 4 x 4 block of pixels as SIMD lanes that run every loop until all
of them are done, and it ends every loop of the block once the loops together have run
65,535 passes. Rows with other inputs in one block (another harmonic, another angle) so
add up each loop's longest lane: a student's program that stays within the budget row by
row is cut without a word. Repeating each row over its own block makes the lanes agree,
so a row costs what the loop guard counts for it (the guard names the rest).
"""

from __future__ import annotations

import numpy as np

BLOCK = 4  # llvmpipe's block of pixels shaded together (it rasterizes 4 x 4 blocks)
ROW_WIDTH = 1024  # rows per line of the input texture, before the blocks


def run_rows(renderer, model, view: str, params, rows: np.ndarray, uniforms: dict):
    """The view's RGBA output (n, 4) for `rows` (n, 4 floats), bound as texture unit 0."""
    import moderngl

    n = len(rows)
    width = min(n, ROW_WIDTH)
    height = -(-n // width)
    grid = np.zeros((height * width, 4), np.float32)
    grid[:n] = rows
    blocks = grid.reshape(height, width, 4).repeat(BLOCK, axis=0).repeat(BLOCK, axis=1)
    size = (width * BLOCK, height * BLOCK)
    texture = renderer.ctx.texture(size, 4, np.ascontiguousarray(blocks), dtype="f4")
    texture.filter = (moderngl.NEAREST, moderngl.NEAREST)
    texture.use(0)
    try:
        fbo = renderer._run(model, view, params, size, uniforms)
        return renderer._read(fbo)[::BLOCK, ::BLOCK].reshape(-1, 4)[:n]
    finally:
        texture.release()


def row_at(x: int, y: int) -> int:
    """The row shaded at pixel (x, y) of run_rows's output (where the guard stopped)."""
    return (y // BLOCK) * ROW_WIDTH + x // BLOCK

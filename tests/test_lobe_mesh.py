"""The 3D lobe drawn on the GPU by each model's own GLSL (Renderer.lobe_mesh), real GL."""

from __future__ import annotations

import numpy as np
import pytest

from lab.glsl import ShaderCompileError
from lab.models import MODEL_DIR, load_model, parse_model
from lab.plots import save_image
from lab.render import LobeCamera, direction

SIZE = (400, 320)
RED, BLUE = (1.0, 0.1, 0.1), (0.1, 0.3, 1.0)
ORIGIN = np.zeros(3)


def mask(image: np.ndarray) -> np.ndarray:
    return image[..., 3] > 0.5


def farthest(image: np.ndarray, camera: LobeCamera, where=None) -> np.ndarray:
    """The lit pixel farthest on screen from the projected origin, as (x, y)."""
    on = mask(image) if where is None else where
    rows, cols = np.nonzero(on)
    centre = camera.project(ORIGIN, SIZE)[0]
    d2 = (cols + 0.5 - centre[0]) ** 2 + (rows + 0.5 - centre[1]) ** 2
    k = int(np.argmax(d2))
    return np.array([cols[k] + 0.5, rows[k] + 0.5])


def save(image: np.ndarray, path) -> None:
    """Display values as they are (save_image would apply the sRGB curve on top)."""
    save_image(np.dstack([np.clip(image[..., :3], 0, 1) ** 2.2, image[..., 3:]]), path)


@pytest.mark.parametrize("perspective", [True, False])
def test_phong_lobe_reaches_farthest_in_the_mirror_direction(
    renderer, gl_clean, output_dir, perspective
):
    camera = LobeCamera(yaw=-0.6, pitch=0.35, perspective=perspective)
    phong = load_model("phong")
    image = renderer.lobe_mesh([(phong, {"ke": 50.0}, RED)], 45.0, 0.0, SIZE, camera, marks=False)
    assert image.shape == (SIZE[1], SIZE[0], 4) and image.dtype == np.float32
    # The peak f_r is in the mirror direction and is drawn at radius 1.
    tip = camera.project(direction(45.0, 180.0), SIZE)[0]
    assert np.linalg.norm(farthest(image, camera) - tip) < 3.0
    # Lit: shaded in the model's colour (red), not black.
    lobe = image[mask(image)]
    assert lobe[:, 0].mean() > 0.3 and (lobe[:, 0] > lobe[:, 2]).mean() > 0.9
    save(image, output_dir / f"lobe_mesh_phong{'_perspective' if perspective else ''}.png")


def test_higher_phong_exponent_draws_a_smaller_lobe(renderer, gl_clean):
    phong = load_model("phong")
    areas = [
        mask(renderer.lobe_mesh([(phong, {"ke": ke}, RED)], 30.0, 0.0, SIZE, marks=False)).sum()
        for ke in (5.0, 50.0, 500.0)
    ]
    assert areas[0] > areas[1] > areas[2] > 100


def test_two_models_overlay_in_their_colours(renderer, gl_clean, output_dir):
    phong, lambert = load_model("phong"), load_model("lambert")
    layers = [(phong, {"ke": 20.0}, RED), (lambert, {}, BLUE)]
    both = renderer.lobe_mesh(layers, 40.0, 30.0, SIZE, marks=False)
    peak = max(p for m, v, _ in layers for p in renderer.lobe_peak(m, v, 40.0, 30.0))
    alone = [
        renderer.lobe_mesh([layer], 40.0, 30.0, SIZE, marks=False, peak=peak) for layer in layers
    ]
    on = mask(both)
    red = on & (both[..., 0] > both[..., 2])
    blue = on & (both[..., 2] > both[..., 0])
    assert red.sum() > 500 and blue.sum() > 500
    # One picture holds both lobes: its outline is the union of theirs (edges aside).
    union = mask(alone[0]) | mask(alone[1])
    assert (on != union).sum() < 0.01 * union.sum()
    # Each lobe is where it is drawn alone, in its own colour.
    assert (red & mask(alone[0])).sum() > 0.9 * red.sum()
    assert (blue & mask(alone[1])).sum() > 0.9 * blue.sum()
    save(
        renderer.lobe_mesh(
            layers, 40.0, 30.0, SIZE, supersample=2, background=(0.16, 0.16, 0.17, 1.0)
        ),
        output_dir / "lobe_mesh_overlay.png",
    )
    save(
        renderer.lobe_mesh(
            layers,
            40.0,
            30.0,
            SIZE,
            style="wire",
            supersample=2,
            background=(0.16, 0.16, 0.17, 1.0),
        ),
        output_dir / "lobe_mesh_overlay_wire.png",
    )


def test_delta_model_draws_its_spike(renderer, gl_clean, output_dir):
    mirror = load_model("mirror")
    camera = LobeCamera()
    peak, spike = renderer.lobe_peak(mirror, {"rho_s": (0.5, 0.5, 0.5)}, 30.0, 90.0)
    assert peak == 0.0 and spike == pytest.approx(0.5, rel=1e-4)
    # Scaled to 1: the spike is a line from the origin to half way along the mirror direction.
    image = renderer.lobe_mesh(
        [(mirror, {"rho_s": (0.5, 0.5, 0.5)}, BLUE)],
        30.0,
        90.0,
        SIZE,
        camera,
        marks=False,
        peak=1.0,
    )
    end = camera.project(0.5 * direction(30.0, 270.0), SIZE)[0]
    assert np.linalg.norm(farthest(image, camera) - end) < 4.0
    start = camera.project(ORIGIN, SIZE)[0]
    for t in (0.2, 0.5, 0.8):  # lit along the way, in the model's colour
        x, y = (start + t * (end - start)).astype(int)
        patch = image[y - 2 : y + 3, x - 2 : x + 3]
        assert patch[..., 3].max() > 0.9 and patch[..., 2].max() > 0.5
    # With a diffuse model beside it the spike sets the scale: it reaches radius 1.
    lambert = load_model("lambert")
    image = renderer.lobe_mesh(
        [(mirror, {}, BLUE), (lambert, {}, RED)], 30.0, 90.0, SIZE, camera, marks=False
    )
    tip = camera.project(direction(30.0, 270.0), SIZE)[0]
    assert np.linalg.norm(farthest(image, camera) - tip) < 4.0
    save(
        renderer.lobe_mesh(
            [(mirror, {}, BLUE), (lambert, {}, RED)],
            30.0,
            90.0,
            SIZE,
            camera,
            background=(0.16, 0.16, 0.17, 1.0),
            supersample=2,
        ),
        output_dir / "lobe_mesh_mirror.png",
    )


def test_log_scale_and_cosine_follow_the_formula(renderer, gl_clean):
    """Lambert's f_r is constant: a hemisphere (radius 1 everywhere); with the cosine, a
    sphere through the origin (radius cos theta_o), so its top at height 1 is the same
    but it is narrower; on a log scale a constant lobe is still the hemisphere."""
    lambert = load_model("lambert")
    camera = LobeCamera(yaw=0.0, pitch=0.0, perspective=False)  # side view: z is up
    flat = {}
    for cos in (False, True):
        for log in (False, True):
            image = renderer.lobe_mesh(
                [(lambert, {}, RED)],
                20.0,
                0.0,
                SIZE,
                camera,
                cos_weighted=cos,
                log=log,
                marks=False,
            )
            rows, cols = np.nonzero(mask(image))
            flat[cos, log] = (rows.min(), cols.max() - cols.min())
    top = camera.project([0.0, 0.0, 1.0], SIZE)[0][1]
    side = camera.project([[-1.0, 0.0, 0.0], [1.0, 0.0, 0.0]], SIZE)[:, 0]
    for key, (row, _) in flat.items():
        assert abs(row - top) < 2.5, key
    assert abs(flat[False, False][1] - (side[1] - side[0])) < 3.0
    assert flat[True, False][1] < 0.6 * flat[False, False][1]  # a sphere of diameter 1
    assert abs(flat[False, True][1] - flat[False, False][1]) < 3.0


def test_lobe_leaves_gl_state_as_it_found_it(renderer, gl_clean):
    before = renderer.sphere("phong", {}, (30.0, 0.0), size=64)
    renderer.lobe_mesh([("phong", {}, RED)], 30.0, 0.0, (64, 64))
    assert np.array_equal(renderer.sphere("phong", {}, (30.0, 0.0), size=64), before)


def test_compile_error_in_the_vertex_stage_names_the_model_line(renderer, tmp_path):
    code = (MODEL_DIR / "phong.glsl").read_text().replace("@model phong", "@model bad_lobe")
    lines = code.splitlines()
    broken = next(i for i, text in enumerate(lines, 1) if "vec3 R =" in text)
    lines[broken - 1] = lines[broken - 1].replace(";", "")
    path = tmp_path / "bad_lobe.glsl"
    path.write_text("\n".join(lines) + "\n")
    model = parse_model(path.read_text(), path)
    with pytest.raises(ShaderCompileError) as caught:
        renderer.lobe_mesh([(model, {}, RED)], 30.0, 0.0, (64, 64))
    assert any(
        e.file.endswith("bad_lobe.glsl") and e.line in (broken, broken + 1)
        for e in caught.value.errors
    ), caught.value.errors


def test_bad_style_is_a_clear_error(renderer):
    with pytest.raises(ValueError, match="unknown lobe style"):
        renderer.lobe_mesh([("phong", {}, RED)], 30.0, style="glass")

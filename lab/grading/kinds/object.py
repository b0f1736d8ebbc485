"""`kind = "object"`: a spatially varying BRDF on the lab's lit object, textures bound.

The student's file defines `vec3 SVBRDF(vec2 uv, vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y)`
and declares the `uniform sampler2D` names it reads; `textures` binds a PNG of the exercise
folder to each (`{ albedo_map = "textures/albedo.png" }`: linear values, filtered bilinearly,
repeating). shaders/views/grade_object.glsl draws the object view's `shape`, turned by `yaw`
and `pitch` (degrees), with the object view's texture coordinates and tangent frame (X along
u), lit by `lights`. The image is compared as a sphere check's is (tone-mapped, `threshold`,
`max_fraction`), so the reports, references and explanations are the sphere kind's.

Hidden mode (where `seed` is drawn anew) replaces every texture by one generated from the drawn
seed, of the same size and character: smooth periodic fields with soft or sharp edges, within
the committed texture's range of values (a grey texture stays grey, a colour one gets random
colours), and turns the object to a random yaw; a file that hard-codes what the committed
textures hold fails there.

The page's practice mode draws the same view with the committed textures (`practice`:
their bytes, the shape and the turn; lab/web/static/objectcheck.js binds them).
"""

from __future__ import annotations

import base64
import math
import re
import zlib
from pathlib import Path

import numpy as np

from lab.grading.kinds.sphere import SphereKind
from lab.grading.spec import Check, ExerciseError
from lab.render import light_uniforms
from lab.views.object import SHAPES

VIEW = "grade_object"
FUNCTION = "vec3 SVBRDF(vec2 uv, vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y)"
SAMPLER_NAME = re.compile(r"^[A-Za-z_]\w*$")
# What explain() says of samplers the program never reads (a str.format template: the page
# fills it from exercises.json, lab/web/static/objectcheck.js).
UNREAD = (
    "your file never reads {names}: each texture holds a parameter of the material (the "
    "handout's table), read it with texture(sampler, uv)"
)
FIRST_UNIT = 1  # texture units from here on: unit 0 is left to models that bind data
_FILES: dict[tuple[str, float], np.ndarray] = {}  # committed textures, by path and mtime
_GENERATED: dict[tuple, dict[str, np.ndarray]] = {}  # hidden mode's, by seed and files


def read_texture(path: str) -> np.ndarray:
    """(h, w, 4) uint8 RGBA of a PNG (grey and RGB files widened; alpha set to 255)."""
    from PIL import Image

    key = (path, Path(path).stat().st_mtime)
    if key not in _FILES:
        with Image.open(path) as image:
            rgb = np.asarray(image.convert("RGB"), np.uint8)
        rgba = np.concatenate([rgb, np.full(rgb.shape[:2] + (1,), 255, np.uint8)], axis=-1)
        if len(_FILES) > 32:
            _FILES.clear()
        _FILES[key] = rgba
    return _FILES[key]


def periodic_field(rng: np.random.Generator, height: int, width: int) -> np.ndarray:
    """A smooth random field in [0, 1] that repeats across u and v (integer frequencies),
    pushed towards 0 and 1 by a random edge width: soft blends or sharp-edged regions."""
    v, u = np.meshgrid(
        (np.arange(height) + 0.5) / height, (np.arange(width) + 0.5) / width, indexing="ij"
    )
    field = np.zeros((height, width))
    for _ in range(5):
        ku, kv = rng.integers(1, 6), rng.integers(-3, 4)
        field += rng.uniform(0.4, 1.0) * np.cos(2 * np.pi * (ku * u + kv * v) + rng.uniform(0, 6.3))
    field = (field - field.min()) / max(float(np.ptp(field)), 1e-9)
    edge = rng.uniform(0.03, 0.5)
    t = np.clip((field - 0.5) / (2 * edge) + 0.5, 0.0, 1.0)
    return t * t * (3.0 - 2.0 * t)


def generated_texture(seed: int, index: int, like: np.ndarray) -> np.ndarray:
    """A random texture with `like`'s size and character, from `seed` (hidden mode)."""
    rng = np.random.default_rng([seed, 1013, index])
    height, width = like.shape[:2]
    values = like[..., :3].astype(np.float64) / 255.0
    low, high = float(values.min()), float(values.max())
    field = periodic_field(rng, height, width)[..., None]
    grey = bool(np.all(like[..., 0] == like[..., 1]) and np.all(like[..., 1] == like[..., 2]))
    if grey:
        out = low + (high - low) * np.repeat(field, 3, axis=-1)
    else:  # two random colours, blended by the field, and a little of a second field
        a, b = rng.uniform(low, high, 3), rng.uniform(low, high, 3)
        out = a + (b - a) * field
        out += (
            (rng.uniform(low, high, 3) - out) * 0.5 * periodic_field(rng, height, width)[..., None]
        )
    rgba = np.full((height, width, 4), 255, np.uint8)
    rgba[..., :3] = np.clip(np.round(out * 255.0), 0, 255).astype(np.uint8)
    return rgba


class ObjectKind(SphereKind):
    name = "object"
    order = 70
    fields = {"shape": "torus", "yaw": 35.0, "pitch": 30.0, "textures": {}}
    captions = {**SphereKind.captions}
    alts = {
        "reference": "the solution's render of the lit, textured object",
        "student": "your render of the lit, textured object, from the same settings",
        "difference": "your render minus the solution's: red where yours is too bright, "
        "blue where too dark, pale where they agree",
        "failing pixels": "the solution's render in grey with the pixels that fail in orange",
    }

    # -- inputs ------------------------------------------------------------------------------
    def validate(self, check: Check, where: str) -> None:
        o, here = check.options, f"{where}: check {check.name}"
        if o["shape"] not in SHAPES:
            raise ExerciseError(f"{here}: shape {o['shape']!r} is not one of {', '.join(SHAPES)}")
        if not 1 <= len(check.lights) <= 4:
            raise ExerciseError(f"{here}: give 1 to 4 lights")
        files = {}
        for sampler, file in o["textures"].items():
            if not SAMPLER_NAME.match(sampler) or sampler.lower().startswith("lab_"):
                raise ExerciseError(
                    f"{here}: textures.{sampler}: a texture is named by the GLSL sampler2D "
                    "uniform it is bound to (letters, digits, _; not starting with lab_)"
                )
            path = (Path(where).parent / str(file)).resolve()
            if not isinstance(file, str) or path.suffix.lower() != ".png" or not path.is_file():
                raise ExerciseError(
                    f"{here}: textures.{sampler} = {file!r}: give a .png file of the exercise "
                    'folder, relative to exercise.toml (for example "textures/albedo.png")'
                )
            try:
                size = read_texture(str(path)).shape[:2]
            except (OSError, ValueError) as err:  # PIL's UnidentifiedImageError is an OSError
                raise ExerciseError(
                    f"{here}: textures.{sampler} = {file!r}: cannot be read as a PNG ({err}); "
                    "save it again as an 8-bit grey or RGB PNG"
                ) from None
            if max(size) > 4096:
                raise ExerciseError(f"{here}: textures.{sampler}: at most 4096 texels a side")
            files[sampler] = str(path)
        o["textures"] = files
        o["committed_seed"] = int(check.seed)  # a different seed: hidden mode, new textures

    def hidden(self, check: Check) -> bool:
        return int(check.seed) != check.options.get("committed_seed", int(check.seed))

    def images(self, check: Check) -> dict[str, np.ndarray]:
        """The RGBA uint8 texture bound to each sampler: the files, or hidden mode's own
        (made once per seed and process: the solution and the student's render share them)."""
        files = sorted(check.options["textures"].items())
        if not self.hidden(check):
            return {sampler: read_texture(path) for sampler, path in files}
        key = (int(check.seed), tuple(files))
        if key not in _GENERATED:
            if len(_GENERATED) > 16:
                _GENERATED.clear()
            _GENERATED[key] = {
                sampler: generated_texture(int(check.seed), index, read_texture(path))
                for index, (sampler, path) in enumerate(files)
            }
        return _GENERATED[key]

    def turn(self, check: Check) -> tuple[float, float]:
        """yaw and pitch in radians; hidden mode draws the yaw from the seed."""
        yaw = float(check.options["yaw"])
        if self.hidden(check):
            yaw = float(np.random.default_rng([int(check.seed), 1014]).uniform(0.0, 360.0))
        return math.radians(yaw), math.radians(float(check.options["pitch"]))

    # -- render --------------------------------------------------------------------------
    def render(self, renderer, model, check: Check) -> np.ndarray:
        import moderngl

        yaw, pitch = self.turn(check)
        uniforms = {
            **light_uniforms(check.lights),
            "u_resolution": (float(check.size), float(check.size)),
            "u_shape": SHAPES.index(check.options["shape"]),
            "u_yaw": yaw,
            "u_pitch": pitch,
        }
        bound = []
        try:
            for unit, (sampler, image) in enumerate(self.images(check).items(), FIRST_UNIT):
                height, width = image.shape[:2]
                texture = renderer.ctx.texture((width, height), 4, np.ascontiguousarray(image))
                texture.filter = (moderngl.LINEAR, moderngl.LINEAR)
                texture.repeat_x = texture.repeat_y = True
                texture.use(unit)
                bound.append(texture)
                uniforms[sampler] = unit
            preamble = f"const int LIGHT_COUNT = {len(check.lights)};"
            return renderer.image(model, VIEW, check.params, check.size, uniforms, preamble)
        finally:
            for texture in bound:
                texture.release()

    def where(self, check: Check, x: int, y: int) -> str:
        return f"pixel ({x}, {check.size - 1 - y}) of the object"

    def explain(self, explainer, exercise, check: Check, model, expected, got, live) -> str:
        """Where no known mistake matched: the textures the program never reads (the
        driver drops a sampler uniform no path of the code samples)."""
        renderer = explainer.grader.renderer
        resolved = model.resolve(check.params)
        enums = {k: v for k, v in resolved.items() if model.params[k].kind == "enum"}
        preamble = f"const int LIGHT_COUNT = {len(check.lights)};"
        try:
            program = renderer.program(model, VIEW, enums, preamble)
        except Exception:  # noqa: BLE001 - a compile error is reported by the check itself
            return ""
        unread = [name for name in sorted(check.options["textures"]) if name not in program]
        if not unread:
            return ""
        return UNREAD.format(names=", ".join(unread))

    def practice(self, exercise, check: Check, values) -> dict:
        """The sphere kind's reference image, and what the page binds and sets to draw the
        grader's view: each sampler's texture (RGBA bytes, first row at v = 0, zlib, base64) and
        the shape's index and the turn in radians (committed mode: the files, the yaw)."""
        yaw, pitch = self.turn(check)
        textures = {
            sampler: {
                "width": int(image.shape[1]),
                "height": int(image.shape[0]),
                # zlib's deflate (the page inflates it): smooth fields pack 30 to 60 times
                "data": base64.b64encode(zlib.compress(image.tobytes(), 9)).decode(),
            }
            for sampler, image in self.images(check).items()
        }
        return {
            **super().practice(exercise, check, values),
            "textures": textures,
            "first_unit": FIRST_UNIT,
            "unread_words": UNREAD,
            "view": VIEW,
            "shape_index": SHAPES.index(check.options["shape"]),
            "yaw_rad": yaw,
            "pitch_rad": pitch,
            # the files' paths (absolute here) stay out of exercises.json
            "options": {k: check.options[k] for k in ("shape", "yaw", "pitch")},
        }


KIND = ObjectKind()

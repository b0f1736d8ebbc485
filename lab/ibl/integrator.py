"""Monte Carlo integration of the reflection equation on the GPU, accumulated progressively.

`IBLRenderer` draws the lit sphere of shaders/views/ibl.glsl under an environment map with
one of STRATEGIES and one of SEQUENCES. A model's BRDF sampler is the file
shaders/samplers/<model>.glsl (it defines HAS_SAMPLER, SAMPLE_BRDF and PDF_BRDF); a model
without one (a .brdf file, a measured table, a user's shader) is sampled from a table of
its own f_r cos built on the GPU (lab.ibl.table, terms/sampling_table.glsl), and
`fallback` says so.
"""

from __future__ import annotations

import hashlib
import math

import moderngl
import numpy as np

from lab import glsl
from lab.constants import LUMA
from lab.ibl.environments import Environment
from lab.ibl.table import GLSL as TABLE_SAMPLER
from lab.ibl.table import TableCache
from lab.models import SHADER_DIR, Model, Value
from lab.render import Renderer, as_model
from lab.views.object import SHAPES  # the object view's shapes (u_shape); "sphere": the lit sphere

STRATEGIES = ("uniform", "cosine", "environment", "brdf", "mis_balance", "mis_power", "auto")
STRATEGY_TITLES = {
    "uniform": "uniform hemisphere",
    "cosine": "cosine-weighted",
    "environment": "environment (CDF over the map)",
    "brdf": "BRDF importance",
    "mis_balance": "MIS, balance heuristic",
    "mis_power": "MIS, power heuristic",
    "auto": "auto: BRDF under uniform light, else MIS (power)",
}
# "auto" under a map whose contrast (environments.contrast) is at most this: BRDF sampling
# alone, as the map's samples would only follow sin theta there; above it, MIS.
UNIFORM_CONTRAST = 0.01
# "random": PCG numbers, independent per pass (the grader's variance needs that);
# "sobol": each pixel's own Owen-scrambled Sobol' sequence (terms/sampling.glsl).
SEQUENCES = ("random", "sobol")
SAMPLER_DIR = SHADER_DIR / "samplers"
SAMPLING_TERMS = SHADER_DIR / "terms" / "sampling.glsl"
ENVIRONMENT_TERMS = SHADER_DIR / "terms" / "environment.glsl"
RENDER_VIEWS = ("ibl", "ibl_object")  # the sphere, and the lab's object (SHAPES)
IBL_VIEWS = (*RENDER_VIEWS, "ibl_sample", "ibl_pdf")
TABLE_VIEW = "ibl_table"  # the data-driven sampler's masses (lab.ibl.table)
NO_SAMPLER = """const bool HAS_SAMPLER = false;
vec3 SAMPLE_BRDF(vec3 V, vec3 N, vec3 X, vec3 Y, vec3 u) { return N; }
float PDF_BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) { return 0.0; }"""
# An exercise's sampler file defines sample_lobe and pdf_lobe; these lines make it the
# model's sampler (lab.grading.exercise appends them to the student's code).
LOBE_SAMPLER = """
const bool HAS_SAMPLER = true;
vec3 SAMPLE_BRDF(vec3 V, vec3 N, vec3 X, vec3 Y, vec3 u) { return sample_lobe(u.xy, V, N, X, Y); }
float PDF_BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) { return pdf_lobe(L, V, N, X, Y); }
"""

# An estimator exercise's file (lab.grading.exercise, `estimator = true`) is the estimate
# itself: estimate_radiance(n, V, N, X, Y), the mean of n samples, which pass_sum
# (terms/environment.glsl) calls instead of its own loop. The line goes in front of the
# file, on its first line (its line numbers stay its own): what the handout gives it, the
# map's radiance (defined later, with the environment), the BRDF (defined before it here,
# after it on the page: lab/web/static/submission.js) and two uniform numbers per call.
ESTIMATOR_LINE = (
    "vec3 environment(vec3 d); vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y); "
    "vec2 random2() { return vec2(lab_random(), lab_random()); } "
)
ESTIMATOR_HOST = NO_SAMPLER + "\n#define LAB_ESTIMATOR estimate_radiance\n"


def sampler_path(model: Model):
    """The model's BRDF sampler file, or None (BRDF Explorer files and models without one)."""
    path = SAMPLER_DIR / f"{model.name}.glsl"
    own = getattr(model, "sampler_path", None)  # an exercise's model brings its own
    if own is not None:
        return own
    if hasattr(model, "shader_line") or not path.is_file():
        return None
    return path if model.path.parent.resolve() == (SHADER_DIR / "brdfs").resolve() else None


def sampler_text(model: Model) -> str | None:
    """The sampler's GLSL: an exercise's model carries it (`sampler_code`), else its file."""
    code = getattr(model, "sampler_code", None)
    if code is not None:
        return code
    path = sampler_path(model)
    return path.read_text(encoding="utf-8") if path is not None else None


def tabulated(model: Model) -> bool:
    """Whether the model is sampled from its table (no analytic sampler, not a mirror)."""
    return sampler_text(model) is None and not model.delta


def sampler_source(model: Model) -> tuple[str, str]:
    """The sampler's GLSL and the label its lines are reported under."""
    text = sampler_text(model)
    if text is not None:
        path = sampler_path(model)
        return text, glsl.label_of(path) if path is not None else "<sampler>"
    if tabulated(model):
        return TABLE_SAMPLER.read_text(encoding="utf-8"), glsl.label_of(TABLE_SAMPLER)
    return NO_SAMPLER, "<no sampler>"


def guarded(model: Model) -> bool:
    """Whether the model's sampler is an exercise's, with its loops guarded."""
    return getattr(model, "sampler_code", None) is not None and model.loop_limit > 0


def sampler_key(model: Model) -> str:
    """A comment line naming the sampler's text, so the program cache tells samplers apart."""
    text = sampler_source(model)[0]
    return f"// sampler {sampler_path(model)} {hashlib.sha1(text.encode()).hexdigest()[:12]}"


def fallback(model: Model, strategy: str) -> str | None:
    """What the view says when `strategy` needs a sampler the model lacks (else None)."""
    if strategy not in ("brdf", "mis_balance", "mis_power", "auto") or not tabulated(model):
        return None
    return (
        f"{model.name} has no BRDF sampler of its own: it is sampled from a table of its "
        "f_r cos (data-driven, exact pdf)"
    )


def chosen_strategy(strategy: str, environment: Environment) -> str:
    """The strategy a pass runs: "auto" resolved for the environment."""
    return strategy if strategy != "auto" else auto_strategy(environment.contrast)


def auto_strategy(contrast: float) -> str:
    """What "auto" runs under a map of this contrast (environments.contrast); the page gets
    it per map through its manifest (lab/web/site.py)."""
    return "brdf" if contrast <= UNIFORM_CONTRAST else "mis_power"


def insert_before_view(source: glsl.Source, view: str, text: str, label: str) -> glsl.Source:
    """Put `text` (sampling code) between the model and the view template."""
    view_label = glsl.label_of(glsl.VIEW_DIR / f"{view}.glsl")
    start = next(i for i, (file, _) in enumerate(source.origins) if file == view_label)
    extra = glsl.Source()
    extra.add(text, label)
    source.lines[start:start] = extra.lines
    source.origins[start:start] = extra.origins
    return source


def frame_uniforms(frame=None) -> dict:
    """u_X, u_Y, u_N of the sample and pdf views from a 3x3 frame (rows X, Y, N)."""
    rows = np.eye(3) if frame is None else np.asarray(frame, np.float64).reshape(3, 3)
    return {
        name: tuple(float(c) for c in row)
        for name, row in zip(("u_X", "u_Y", "u_N"), rows, strict=True)
    }


class IBLRenderer(Renderer):
    """A Renderer that also knows the IBL views (it inserts each model's sampler).

    `loop_stopped` keeps the first (line, x, y) where the loop guard stopped a loop of an
    exercise's sampler over many passes, until the grader takes it (lab.grading.checks)."""

    loop_stopped: tuple[int, int, int] | None = None
    # The estimator's GLSL (terms/sampling.glsl, terms/environment.glsl): `ibl-bench
    # --against` points these at an older checkout's to time its pass beside this one's.
    sampling_terms = SAMPLING_TERMS
    environment_terms = ENVIRONMENT_TERMS

    @property
    def tables(self) -> TableCache:
        """The data-driven samplers' tables of this renderer's context."""
        cache = self.__dict__.get("_tables")
        if cache is None:
            cache = self.__dict__["_tables"] = TableCache()
        return cache

    def table_uniforms(self, model: Model, values) -> dict:
        """Build (or find) and bind the model's sampling table; {} for a model with an
        analytic sampler."""
        if not tabulated(model):
            return {}
        return self.tables.get(self, model, values).bind(self.ctx)

    def _assemble(self, model: Model, view: str, enums: dict, preamble: str):
        """The view's program with the sampling terms, the model's sampler and (for the
        render views) the environment terms between the model and the view template."""
        vertex, source = super()._assemble(model, view, enums, preamble)
        terms = self.sampling_terms
        sampling = (terms.read_text(encoding="utf-8"), glsl.label_of(terms))
        if view == TABLE_VIEW:
            insert_before_view(source, view, *sampling)
        if view in IBL_VIEWS:
            chunks = [sampling, sampler_source(model)]
            if view in RENDER_VIEWS:
                chunks.append(
                    (
                        self.environment_terms.read_text(encoding="utf-8"),
                        glsl.label_of(self.environment_terms),
                    )
                )
            for text, label in chunks:  # each goes just before the view: in order
                insert_before_view(source, view, text, label)
        return vertex, source

    def set_uniforms(self, program, model: Model, values, uniforms: dict) -> None:
        resolved = model.resolve(values)
        bind = getattr(model, "bind", None)
        data_uniforms = bind(self.ctx) if bind is not None else {}
        for name, value in {
            **glsl.uniform_values(model, resolved),
            **data_uniforms,
            **self.table_uniforms(model, values),
            **uniforms,
        }.items():
            if name in program:
                program[name].value = value

    def compiled(
        self, model: Model, values, view: str, strategy: str | None = None, sequence="random"
    ) -> moderngl.Program:
        """The view's program; a render view's with its strategy and sequence compiled in
        (no per-sample branches on them)."""
        resolved = model.resolve(values)
        enums = {k: v for k, v in resolved.items() if model.params[k].kind == "enum"}
        preamble = sampler_key(model)
        if strategy is not None:  # (not "auto": chosen_strategy resolves it)
            preamble += f"\n#define LAB_STRATEGY {STRATEGIES.index(strategy)}"
        if sequence == "sobol":
            preamble += "\n#define LAB_SOBOL"
        return self.program(model, view, enums, preamble)

    # -- BRDF samples, for the chi-square tests and the grader ---------------------------
    def brdf_samples(self, model, values, V, seed: int = 1, frame=None) -> np.ndarray:
        """One BRDF sample per row of V (n, 3), local coordinates (N = z): (n, 4) = L in
        local coordinates and its pdf. `frame` (3x3 rows X, Y, N) is the shading frame the
        sampler sees (default the axes)."""
        model = as_model(model)
        V = np.asarray(V, np.float32).reshape(-1, 3)
        uniforms = {"u_V": 0, "u_seed": seed, **frame_uniforms(frame)}
        return self._texel_pass(model, values, "ibl_sample", [V], uniforms)

    def brdf_pdf(self, model, values, L, V, frame=None) -> np.ndarray:
        """PDF_BRDF (n,) for direction pairs in local coordinates (N = z)."""
        model = as_model(model)
        L = np.asarray(L, np.float32).reshape(-1, 3)
        V = np.broadcast_to(np.asarray(V, np.float32).reshape(-1, 3), L.shape)
        uniforms = {"u_L": 0, "u_V": 1, **frame_uniforms(frame)}
        return self._texel_pass(model, values, "ibl_pdf", [L, V], uniforms)[:, 0]

    def _texel_pass(self, model: Model, values, view: str, inputs, uniforms) -> np.ndarray:
        n = len(inputs[0])
        width = min(max(n, 1), 1024)
        height = max(math.ceil(n / width), 1)
        uniforms = {**self.table_uniforms(model, values), **uniforms}
        textures = []
        for unit, data in enumerate(inputs):
            padded = np.zeros((width * height, 4), np.float32)
            padded[:n, :3] = data
            texture = self.ctx.texture((width, height), 4, padded, dtype="f4")
            texture.filter = (moderngl.NEAREST, moderngl.NEAREST)
            texture.use(unit)
            textures.append(texture)
        try:
            fbo = self._run(model, view, values, (width, height), uniforms, sampler_key(model))
            if guarded(model) and self.loop_stopped is None:
                self.loop_stopped = self.loop_stop()
            return self._read(fbo).reshape(-1, 4)[:n].astype(np.float64)
        finally:
            for texture in textures:
                texture.release()


class Progressive:
    """One progressive IBL render: passes of samples summed into a float target.

    `add(spp)` runs a pass; `image()` is the running mean (size, size, 4), alpha 1 on the
    sphere; `reset()` starts again (a slider moved). Samples are counted per pixel.
    `shape` lights one of the object view's SHAPES instead of the sphere (turned by `yaw`
    and `pitch` in radians, as that view's settings); alpha is then 1 on the object.
    `sequence` is one of SEQUENCES: "sobol" continues each pixel's sequence from pass to
    pass, so every prefix of it is stratified.
    """

    def __init__(
        self,
        renderer: IBLRenderer,
        model: Model | str,
        values: dict[str, Value] | None,
        environment: Environment,
        strategy: str = "mis_power",
        size: int = 256,
        rotation: float = 0.0,
        seed: int = 0,
        shape: str | None = None,
        yaw: float = 0.6,
        pitch: float = 0.5,
        sequence: str = "random",
    ):
        if strategy not in STRATEGIES:
            raise ValueError(f"unknown strategy {strategy!r}: use one of {', '.join(STRATEGIES)}")
        if sequence not in SEQUENCES:
            raise ValueError(f"unknown sequence {sequence!r}: use one of {', '.join(SEQUENCES)}")
        self.sequence = sequence
        self.renderer = renderer
        self.model = as_model(model)
        self.values = dict(values or {})
        self.environment = environment
        self.strategy = strategy
        self.size = int(size)
        self.rotation = float(rotation)
        self.seed = int(seed)
        if shape is not None and shape not in SHAPES:
            raise ValueError(f"unknown shape {shape!r}: use one of {', '.join(SHAPES)}")
        self.shape, self.yaw, self.pitch = shape, float(yaw), float(pitch)
        self.view = "ibl" if shape is None else "ibl_object"
        self.samples = 0
        self.passes = 0
        ctx = renderer.ctx
        self._texture = ctx.texture((self.size, self.size), 4, dtype="f4")
        self._flag = ctx.texture((self.size, self.size), 1, dtype="f4")  # the loop guard's
        # Only an exercise's guarded sampler needs the guard's target: blending a second
        # float target costs llvmpipe a share of every pass (ibl-bench measures it).
        self._fbo = self._target()
        self._fbo.clear(0.0, 0.0, 0.0, 0.0)
        self.program = self._compile()

    @property
    def chosen(self) -> str:
        """The strategy the passes run (STRATEGIES less "auto")."""
        return chosen_strategy(self.strategy, self.environment)

    def _target(self) -> moderngl.Framebuffer:
        flag = [self._flag] if guarded(self.model) else []
        return self.renderer.ctx.framebuffer(color_attachments=[self._texture, *flag])

    def _compile(self) -> moderngl.Program:
        return self.renderer.compiled(
            self.model, self.values, self.view, self.chosen, self.sequence
        )

    @property
    def fallback(self) -> str | None:
        return fallback(self.model, self.strategy)

    def reset(self, **changes) -> None:
        """Start again, with any of values, environment, strategy, rotation changed."""
        for name, value in changes.items():
            setattr(self, name, value)
        if {"values", "model", "strategy", "sequence", "environment"} & set(changes):
            self.program = self._compile()
        if "model" in changes:
            if self.renderer.ctx.fbo is self._fbo:
                self.renderer.target(1, 1).use()
            self._fbo.release()
            self._fbo = self._target()
        self.samples = self.passes = 0
        self._fbo.clear(0.0, 0.0, 0.0, 0.0)

    def add(self, spp: int = 4) -> None:
        """One pass of `spp` samples per pixel (a pass longer than ~0.2 s stalls a UI)."""
        spp = int(min(max(spp, 1), 1024))
        ctx = self.renderer.ctx
        uniforms = {
            "u_resolution": (float(self.size), float(self.size)),
            "u_rotation": math.radians(self.rotation),
            "u_strategy": STRATEGIES.index(self.chosen),
            "u_spp": spp,
            "u_frame": self.passes,
            "u_sample0": self.samples,
            "u_seed": self.seed,
            "u_shape": SHAPES.index(self.shape) if self.shape else 1,
            "u_yaw": self.yaw,
            "u_pitch": self.pitch,
            **self.environment.bind(ctx),
        }
        self.renderer.set_uniforms(self.program, self.model, self.values, uniforms)
        watch = guarded(self.model) and self.renderer.loop_stopped is None
        if watch:  # blending adds the flag up: start each pass from 0
            self._flag.write(np.zeros((self.size, self.size), np.float32))
        previous = ctx.fbo  # bound again after: our target may be released while bound
        self._fbo.use()
        ctx.enable(moderngl.BLEND)
        ctx.blend_func = moderngl.ONE, moderngl.ONE
        try:
            self.renderer._vaos[id(self.program)].render(moderngl.TRIANGLES, vertices=3)
        finally:
            ctx.disable(moderngl.BLEND)
            ctx.blend_func = moderngl.DEFAULT_BLENDING
            if previous is not None and previous is not self._fbo:
                previous.use()
        if watch:
            flag = np.frombuffer(self._flag.read(), np.float32)
            hits = np.flatnonzero(flag > 0.5)
            if hits.size:
                first = int(hits[0])
                line = int(round(float(flag[first])))
                self.renderer.loop_stopped = (line, first % self.size, first // self.size)
        self.samples += spp
        self.passes += 1

    def run(self, samples: int, spp: int = 16) -> Progressive:
        """Passes until `samples` per pixel (the last pass may be shorter)."""
        while self.samples < samples:
            self.add(min(spp, samples - self.samples))
        return self

    def image(self) -> np.ndarray:
        """The running mean: (size, size, 4) float32, row 0 at the top, alpha 1 on the sphere."""
        data = np.frombuffer(self._fbo.read(components=4, dtype="f4"), dtype=np.float32)
        data = data.reshape(self.size, self.size, 4)[::-1]
        if self.samples == 0:
            return np.zeros_like(data)
        return (data / float(self.samples)).astype(np.float32)

    def release(self) -> None:
        if self.renderer.ctx.fbo is self._fbo:  # never leave a released target bound
            self.renderer.target(1, 1).use()
        self._fbo.release()
        self._texture.release()
        self._flag.release()


def render(
    model: Model | str,
    values: dict | None = None,
    environment: Environment | str = "sky",
    strategy: str = "mis_power",
    samples: int = 256,
    size: int = 256,
    rotation: float = 0.0,
    seed: int = 0,
    renderer: IBLRenderer | None = None,
    shape: str | None = None,
    sequence: str = "random",
) -> np.ndarray:
    """A finished IBL render of the sphere (or of the object `shape`): (size, size, 4)
    float32, row 0 at the top."""
    renderer = renderer or IBLRenderer()
    env = environment if isinstance(environment, Environment) else Environment.load(environment)
    job = Progressive(
        renderer, model, values, env, strategy, size, rotation, seed, shape, sequence=sequence
    )
    try:
        return job.run(samples).image()
    finally:
        job.release()


def sphere_normals(size: int) -> tuple[np.ndarray, np.ndarray]:
    """Normals (size, size, 3) of the ibl view's pixels (row 0 at the top) and the mask."""
    c = (np.arange(size) + 0.5) / size * 2.0 - 1.0
    x, y = np.meshgrid(c, -c)
    r2 = x * x + y * y
    mask = r2 <= 1.0
    N = np.stack([x, y, np.sqrt(np.clip(1.0 - r2, 0.0, 1.0))], axis=-1)
    return N, mask


def local_view(size: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """theta and phi (degrees) of V in each pixel's local frame (as ibl.glsl builds it)."""
    N, mask = sphere_normals(size)
    X = np.stack([N[..., 2], np.zeros_like(N[..., 0]), -N[..., 0]], axis=-1)
    norm = np.linalg.norm(X, axis=-1, keepdims=True)
    X = np.where(norm > 1e-6, X / np.maximum(norm, 1e-12), np.array([1.0, 0.0, 0.0]))
    Y = np.cross(N, X)
    V = np.array([0.0, 0.0, 1.0])
    theta = np.degrees(np.arccos(np.clip(N @ V, -1.0, 1.0)))
    phi = np.degrees(np.arctan2(Y @ V, X @ V)) % 360.0
    return theta, phi, mask


def ring_peak(image: np.ndarray, rings: int = 24) -> float:
    """The largest mean luminance over rings of equal view angle on the sphere: the furnace's
    reflectance peak, with the Monte Carlo noise of single pixels averaged away."""
    size = image.shape[0]
    theta, _, mask = local_view(size)
    lum = image[..., :3] @ np.array(LUMA)
    which = np.minimum((theta / 90.0 * rings).astype(int), rings - 1)
    means = [lum[mask & (which == r)].mean() for r in range(rings) if (mask & (which == r)).any()]
    return float(max(means)) if means else 0.0

"""The page's FLIP (lab/web/static/flip.js, run in node) equals the grader's mean_flip
(flip-evaluator) on the same 8-bit images: a sphere reference and changed copies of it."""

from __future__ import annotations

import json
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

from lab.grading.compare import mean_flip, read_png

ROOT = Path(__file__).resolve().parents[1]
FLIP_JS = ROOT / "lab" / "web" / "static" / "flip.js"
RUNNER = """
import { readFileSync } from "node:fs";
import { meanFlip } from "%s";
const [ref, size, ...tests] = process.argv.slice(2);
const reference = new Uint8Array(readFileSync(ref));
const flip = (t) => meanFlip(reference, new Uint8Array(readFileSync(t)), Number(size));
console.log(JSON.stringify(tests.map(flip)));
"""


@pytest.mark.skipif(shutil.which("node") is None, reason="node is not installed (apt nodejs)")
def test_page_flip_equals_the_graders(tmp_path):
    reference = read_png(ROOT / "exercises/02_phong/references/sphere.highlight.png")
    rng = np.random.default_rng(3)
    base = reference.astype(int)
    changed = {
        "brighter": base * 1.3,
        "darker": base * 0.6,
        "noisy": base + rng.integers(-25, 25, base.shape),
        "shifted": np.roll(base, 4, axis=1),
        "tinted": base * np.array([1.0, 0.8, 1.1, 1.0]),
    }
    paths = []
    for name, image in changed.items():
        image = np.clip(image, 0, 255).astype(np.uint8)
        image[..., 3] = reference[..., 3]
        paths.append(tmp_path / f"{name}.bin")
        paths[-1].write_bytes(np.ascontiguousarray(image).tobytes())
        changed[name] = image
    (tmp_path / "ref.bin").write_bytes(np.ascontiguousarray(reference).tobytes())
    runner = tmp_path / "run.mjs"
    runner.write_text(RUNNER % FLIP_JS.as_uri())
    size = str(reference.shape[0])
    out = subprocess.run(
        ["node", str(runner), str(tmp_path / "ref.bin"), size, *map(str, paths)],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert out.returncode == 0, out.stderr
    page = json.loads(out.stdout)
    grader = [mean_flip(reference[..., :3], image[..., :3]) for image in changed.values()]
    assert all(g > 0.01 for g in grader), grader  # each change is visible
    np.testing.assert_allclose(page, grader, rtol=0, atol=1e-5)

"""The loop guard counts the passes of all loops together, as Mesa's llvmpipe does, and
the grader shades each row of a row view alone, so lanes with other inputs do not add up."""

from __future__ import annotations

import dataclasses

import numpy as np

from lab.constants import LOOP_LIMIT_MAX, LOOP_TOTAL
from lab.glsl import loop_cause, loop_warning
from lab.models import parse_model

TWO_LOOPS = """// @model two_loops
// @param n float 0 70000 40000
vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {
    float a = 0.0;
    for (int i = 0; i < int(n); ++i) { a += 1.0; }
    float b = 0.0;
    for (int j = 0; j < int(n); ++j) { b += 1.0; }
    return vec3(a, b, 0.0);
}
"""


def two_loops(limit: int):
    model = parse_model(TWO_LOOPS, "two_loops.glsl")
    return dataclasses.replace(model, loop_limit=limit)


def test_loops_that_together_pass_the_total_are_stopped_and_named(renderer):
    model = two_loops(LOOP_LIMIT_MAX)  # each loop alone stays under its limit
    up = np.array([[0.0, 0.0, 1.0]])
    a, b, _ = renderer.probe(model, {"n": 40000.0}, up, up)[0]
    # 40,001 checks of the first loop's condition, the rest for the second
    assert a == 40000 and 0 < b < 25400 and a + b <= LOOP_TOTAL
    line, together = loop_cause(renderer.loop_stop()[0])
    assert together and line == 7
    said = loop_warning(model, renderer.loop_stop()[0])
    assert said.startswith(f"two_loops.glsl:7: the loops ran {LOOP_TOTAL:,} passes in all")
    assert "take fewer steps" in said


def test_a_loop_alone_past_its_limit_is_named_as_before(renderer):
    model = two_loops(10_000)
    up = np.array([[0.0, 0.0, 1.0]])
    a, b, _ = renderer.probe(model, {"n": 20000.0}, up, up)[0]
    assert a == 10000
    line, together = loop_cause(renderer.loop_stop()[0])
    assert not together and line == 5
    assert "did not end within 10,000 iterations" in loop_warning(model, line)


def test_loops_under_the_total_run_to_the_end(renderer):
    model = two_loops(LOOP_LIMIT_MAX)
    up = np.array([[0.0, 0.0, 1.0]])
    a, b, _ = renderer.probe(model, {"n": 30000.0}, up, up)[0]
    assert (a, b) == (30000, 30000) and renderer.loop_stop() is None

"""The HTML report's polar plot is readable without colour vision and without sight: the
two curves differ by line style, every stroke is 3:1 or more against the white page, and
the plot's title says where each curve peaks."""

from __future__ import annotations

import re

import numpy as np
from test_a11y_colour import contrast, hex_rgb  # the WCAG measure the page is held to

from lab.grading import visuals


def test_polar_report_plot_has_styles_contrast_and_words():
    theta = np.linspace(-89.0, 89.0, 179)
    expected = 0.1 + 0.5 * np.exp(-(((theta - 40.0) / 8.0) ** 2))
    got = np.full_like(theta, 0.1)
    curve = {"theta_o": theta, "expected": expected, "got": got, "theta_i": 40.0}
    svg = visuals.polar_svg(curve, failing=[120, 121])
    lines = re.findall(r'<polyline fill="none" stroke="(#\w{6})"([^>]*)>', svg)
    dashed = ["stroke-dasharray" in rest for _, rest in lines]
    assert dashed == [False, True], lines  # the solution solid, the student's dashed
    for colour in set(re.findall(r'(?:stroke|fill)="(#\w{6})"', svg)):
        assert contrast(hex_rgb(colour), [255, 255, 255]) >= 3.0, colour
    title = re.search(r"<title>([^<]*)</title>", svg).group(1)
    assert "the solution peaks at 0.6 sr⁻¹ at θo 40°" in title, title
    assert "yours is flat at 0.1 sr⁻¹" in title, title
    assert "(solid)" in svg and "(dashed)" in svg

"""The HTML report's polar plot is readable without colour vision and without sight: the
two curves differ by line style, every stroke is 3:1 or more against the white page, and
the plot's title says where each curve peaks."""

from __future__ import annotations

import re

import numpy as np

from lab.grading import visuals


def contrast(hex_colour: str) -> float:
    """WCAG contrast ratio of a colour against white."""
    rgb = [int(hex_colour[i : i + 2], 16) / 255 for i in (1, 3, 5)]
    lin = [c / 12.92 if c <= 0.03928 else ((c + 0.055) / 1.055) ** 2.4 for c in rgb]
    luminance = 0.2126 * lin[0] + 0.7152 * lin[1] + 0.0722 * lin[2]
    return 1.05 / (luminance + 0.05)


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
        assert contrast(colour) >= 3.0, colour
    title = re.search(r"<title>([^<]*)</title>", svg).group(1)
    assert "the solution peaks at 0.6 sr⁻¹ at θo 40°" in title, title
    assert "yours is flat at 0.1 sr⁻¹" in title, title
    assert "(solid)" in svg and "(dashed)" in svg

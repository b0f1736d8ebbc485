"""Constants every part of the lab shares, in one place.

Python reads them from here; GLSL gets them as `#define LAB_...` lines at the top of every
assembled program (`glsl_defines`); the web page gets them in its manifest (`as_dict`).
"""

from __future__ import annotations

LUMA = (0.2126, 0.7152, 0.0722)  # Rec. 709 luminance weights of linear RGB
MAX_LIGHTS = 8  # directional lights a view takes at once (uniform array sizes)
GRAZING_DEG = 87.0  # plots leave out |θo| beyond this when they scale (Ward diverges there)
PLOT_DECADES = 3.0  # range of the log scale of the polar plot and the 3D lobe
LOOP_LIMIT = 10_000  # iterations a loop of a model may run per invocation (the loop guard)
# Mesa's llvmpipe silently ends every loop of an invocation once all its loops together
# have run 65,535 passes (each loop's every pass counts, nested ones too): the guard stops
# one loop past its limit (at most LOOP_LIMIT_MAX) and all of them past LOOP_TOTAL passes
# in all, above the one loop's so that a loop that never ends is named as such, and under
# llvmpipe's with room for the views' own loops, which the guard does not count.
LOOP_LIMIT_MAX = 65_000
LOOP_TOTAL = 65_400
LOOP_TOTAL_FLAG = 2_000_000  # added to the guard's line when the loops together ran out
# What every view says of a loop the guard stopped (the page fills it with header.js fill();
# {where}: "" or " at θo = 30° of the polar plot").
LOOP_WARNING = (
    "{file}:{line}: the loop at line {line} did not end within {limit} iterations{where}; "
    "the lab stopped it, so the pictures are wrong: check its exit condition (on a GPU "
    "without the lab's guard it would freeze the screen)"
)
# ... and of loops that together reached LOOP_TOTAL passes ({total}).
LOOP_TOTAL_WARNING = (
    "{file}:{line}: the loops ran {total} passes in all by the loop at line {line}{where} "
    "(every pass of every loop counts); the lab stopped them, as a software renderer such "
    "as Mesa's llvmpipe does without a word, so the pictures are wrong: take fewer steps"
)
SLIDER_STEPS = 1000  # positions of a parameter's slider (the app's and the page's)
# Colours of models drawn together on the dark plots, in order: Okabe & Ito's colour-blind
# safe set (black left out), each at 4:1 or more on the plots' grey (tests/test_a11y_colour.py).
MODEL_COLORS = ("#56b4e9", "#e69f00", "#009e73", "#f0e442", "#cc79a7", "#d55e00")


def as_dict() -> dict[str, object]:
    """The constants for the web page (manifest.json)."""
    return {
        "LUMA": list(LUMA),
        "MAX_LIGHTS": MAX_LIGHTS,
        "GRAZING_DEG": GRAZING_DEG,
        "PLOT_DECADES": PLOT_DECADES,
        "LOOP_LIMIT": LOOP_LIMIT,
        "LOOP_WARNING": LOOP_WARNING,
        "LOOP_TOTAL": LOOP_TOTAL,
        "LOOP_TOTAL_FLAG": LOOP_TOTAL_FLAG,
        "LOOP_TOTAL_WARNING": LOOP_TOTAL_WARNING,
        "SLIDER_STEPS": SLIDER_STEPS,
    }


def glsl_defines() -> str:
    """`#define` lines for GLSL, prefixed LAB_ so they cannot collide with a user's names."""
    return "\n".join(
        [
            "#define LAB_LUMA vec3({:.4f}, {:.4f}, {:.4f})".format(*LUMA),
            f"#define LAB_MAX_LIGHTS {MAX_LIGHTS}",
            f"#define LAB_GRAZING_DEG {GRAZING_DEG:.1f}",
            f"#define LAB_PLOT_DECADES {PLOT_DECADES:.1f}",
        ]
    )

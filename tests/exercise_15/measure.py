"""Exercise 15's wrong and correct submissions graded (reference mode and hidden seed 1):
score and diagnosis per file, the figures of tests/exercise_15/BEFORE.txt and AFTER.txt.
The runner is tests/exercise_batch.py, shared by exercises 11-15.

    python tests/exercise_15/measure.py > tests/exercise_15/AFTER.txt
"""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
if "exercise_batch" not in sys.modules:  # loaded by path: run as a script or by a test
    _spec = importlib.util.spec_from_file_location(
        "exercise_batch", HERE.parent / "exercise_batch.py"
    )
    sys.modules["exercise_batch"] = importlib.util.module_from_spec(_spec)  # before: dataclass
    _spec.loader.exec_module(sys.modules["exercise_batch"])
_batch = sys.modules["exercise_batch"]

BATCH = _batch.Batch(
    HERE,
    "15_spherical_harmonics",
    "sh_projection.glsl",
)
MODES = _batch.MODES
submissions = BATCH.submissions
grade = BATCH.grade
named = BATCH.named

if __name__ == "__main__":
    sys.exit(BATCH.main())

#!/usr/bin/env bash
# Gradescope autograder set-up: runs once when the image is built. The Dockerfile beside it
# runs this same script, so Gradescope's image and a self-built one cannot drift apart.
# The lean install: the lab's wheel without its desktop-app dependencies (no Qt, no plots).
set -euo pipefail
AG="${AUTOGRADER_ROOT:-/autograder}"
SOURCE="$AG/source"
# Python, Mesa's software OpenGL (llvmpipe) for rendering without a GPU, and glslang's
# preprocessor, which the grader reads submissions through.
PACKAGES="python3 python3-venv libegl1 libgl1-mesa-dri glslang-tools"
missing=""
for package in $PACKAGES; do
    dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "ok installed" ||
        missing="$missing $package"
done
if [ -n "$missing" ]; then
    export DEBIAN_FRONTEND=noninteractive
    apt-get update
    apt-get install -y --no-install-recommends $missing
    rm -rf /var/lib/apt/lists/*
fi
python3 -m venv "$AG/venv"
# The core set first, at the pinned versions of constraints-core.txt (a grade must not
# change because a dependency released): pip then has nothing to complain about when the
# wheel comes --no-deps.
"$AG/venv/bin/python" -m pip install --no-cache-dir -r "$SOURCE/requirements-core.txt" \
    -c "$SOURCE/constraints-core.txt"
"$AG/venv/bin/python" -m pip install --no-cache-dir --no-deps "$SOURCE"/brdf_lab-*.whl

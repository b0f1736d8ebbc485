#!/usr/bin/env bash
# Gradescope autograder set-up (runs once when the image is built).
set -euo pipefail
apt-get update
apt-get install -y --no-install-recommends python3 python3-venv python3-pip libegl1 libgl1-mesa-dri
python3 -m venv /autograder/venv
/autograder/venv/bin/pip install --upgrade pip
# Editable: the lab reads shaders/ and exercises/ from the source tree.
/autograder/venv/bin/pip install -e /autograder/source

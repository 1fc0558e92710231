#!/usr/bin/env bash
# What the test suite needs beyond cargo: independent readers of the files mintorque writes.
# CI runs this before the tests; run it once on a new machine. The tests fail (never skip) without them.
set -euo pipefail
# tests/report.rs reads exported BVH files back with Python's `bvh` package.
python3 -m pip install --quiet --disable-pip-version-check --root-user-action=ignore 'bvh==0.3'
# tests/sweep.rs reads the sweep's Parquet table back with pyarrow.
python3 -m pip install --quiet --disable-pip-version-check --root-user-action=ignore 'pyarrow==21.0.0'
# tests/mjcf.rs checks the MJCF reader against MuJoCo's own inverse dynamics (a venv, target/mujoco-venv).
bash "$(dirname "$0")/mujoco-venv.sh"
# tests/osim.rs compares the .osim import with OpenSim 4.6 itself, in its own venv.
bash "$(dirname "$0")/opensim-venv.sh"

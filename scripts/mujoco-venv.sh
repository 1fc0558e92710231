#!/usr/bin/env bash
# MuJoCo's Python bindings for tests/mjcf.rs (the MJCF reader checked against MuJoCo's own inverse
# dynamics): a venv at target/mujoco-venv with pinned mujoco and NumPy. Idempotent: a venv that already
# imports the pinned version is left alone.
set -euo pipefail
cd "$(dirname "$0")/.."
venv=target/mujoco-venv
pin_mujoco=4.0.0
pin_numpy=2.3.3
if [ -x "$venv/bin/python" ] && "$venv/bin/python" -c "import mujoco, sys; sys.exit(mujoco.__version__ != '$pin_mujoco')" 2>/dev/null; then
    exit 0
fi
[ -x "$venv/bin/python" ] || python3 -m venv "$venv"
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check "mujoco==$pin_mujoco" "numpy==$pin_numpy"
"$venv/bin/python" -c "import mujoco; assert mujoco.__version__ == '$pin_mujoco', mujoco.__version__"

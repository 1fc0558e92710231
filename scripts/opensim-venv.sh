#!/usr/bin/env bash
# OpenSim 4.6 (PyPI wheel, with its own Simbody) in a virtual environment under target/opensim-venv, for
# tests/osim.rs, which compares mintorque's .osim import with OpenSim's inverse dynamics. Idempotent: a venv
# that already imports opensim 4.6 is left alone. The wheel needs no system libraries beyond glibc.
set -euo pipefail
cd "$(dirname "$0")/.."
venv=target/opensim-venv
if "$venv/bin/python" -c 'import opensim, sys; sys.exit(opensim.__version__ != "4.6")' 2>/dev/null; then
    exit 0
fi
python3 -m venv "$venv"
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check 'opensim==4.6' 'numpy==2.3.5'
"$venv/bin/python" -c 'import opensim; print("opensim", opensim.__version__, "in '"$venv"'")'

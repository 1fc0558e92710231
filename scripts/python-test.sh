#!/usr/bin/env bash
# The Python package's tests: builds the abi3 wheel with maturin (from PyPI) into a venv this script makes
# (target/python-venv), installs it there with NumPy, pandas and pytest, and runs python/tests.
set -euo pipefail
cd "$(dirname "$0")/.."
venv=target/python-venv
[ -x "$venv/bin/python" ] || python3 -m venv "$venv"
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check 'maturin==1.9.4' 'numpy==2.3.3' 'pandas==2.3.2' 'pytest==8.4.2' 'dask[distributed]==2026.8.0'
rm -rf target/wheels
"$venv/bin/maturin" build --quiet --release -m python/Cargo.toml -o target/wheels -i "$venv/bin/python"
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check --force-reinstall --no-deps target/wheels/mintorque-*.whl
"$venv/bin/python" -m pytest -q python/tests

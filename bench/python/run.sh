#!/usr/bin/env bash
# Builds the wheel into target/python-bench-venv (as scripts/python-test.sh does), with Pinocchio's Python binding, and
# runs the overhead benchmark.
set -euo pipefail
cd "$(dirname "$0")/../.."
cargo build --release --quiet
venv=target/python-bench-venv
[ -x "$venv/bin/python" ] || python3 -m venv "$venv"
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check 'maturin==1.9.4' 'numpy==2.3.3' 'pin==4.1.0'
"$venv/bin/maturin" build --quiet --release -m python/Cargo.toml -o target/wheels -i "$venv/bin/python"
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check --force-reinstall --no-deps target/wheels/mintorque-*.whl
"$venv/bin/python" bench/python/overhead.py "$@"

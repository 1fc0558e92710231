#!/usr/bin/env bash
# One command: build mintorque (release), set up the peer's venv, run both on the suite, print the table.
#   bash bench/peer/run.sh                 # whole suite
#   bash bench/peer/run.sh pendulum h7     # only tasks whose path contains one of the words
# Environment: MINTORQUE=/path/to/mintorque (default: target/release/mintorque of this checkout, built here
# unless MINTORQUE is set), CARGO_TARGET_DIR (honoured by the build), PEER_OUT (default bench/peer/out),
# MOCO=0 (skip OpenSim Moco; otherwise scripts/opensim-venv.sh makes or finds target/opensim-venv).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
repo="$(cd "$here/../.." && pwd)"
if [ -z "${MINTORQUE:-}" ]; then
    (cd "$repo" && cargo build --release --quiet)
    export MINTORQUE="${CARGO_TARGET_DIR:-$repo/target}/release/mintorque"
    case "$MINTORQUE" in /*) ;; *) MINTORQUE="$repo/$MINTORQUE" ;; esac
fi
bash "$here/setup.sh" >&2
if [ "${MOCO:-1}" != "0" ]; then
    bash "$repo/scripts/opensim-venv.sh" >&2
    export MOCO_PYTHON="$repo/target/opensim-venv/bin/python"
fi
echo "mintorque: $MINTORQUE ($(cd "$repo" && git rev-parse --short HEAD 2>/dev/null || echo '?'))" >&2
exec "$here/.venv/bin/python" "$here/run_suite.py" "$@"

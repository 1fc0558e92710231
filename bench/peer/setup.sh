#!/usr/bin/env bash
# Creates bench/peer/.venv (git-ignored) with pinned PyPI versions of the peer's tools.
#   bash bench/peer/setup.sh            # casadi + pin (Pinocchio)
# OpenSim Moco has its own venv, target/opensim-venv (scripts/opensim-venv.sh, which run.sh calls).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
venv="$here/.venv"
python="${PYTHON:-python3}"
if [ ! -x "$venv/bin/python" ]; then
    "$python" -m venv "$venv"
fi
"$venv/bin/pip" install --quiet --disable-pip-version-check \
    casadi==3.7.2 \
    pin==4.1.0 \
    numpy==2.4.6
"$venv/bin/python" - <<'PY'
import casadi, pinocchio, numpy
print(f"casadi {casadi.__version__}, pinocchio {pinocchio.__version__}, numpy {numpy.__version__}")
try:
    import pinocchio.casadi  # noqa: F401
    print("pinocchio.casadi: available (not used: the RNEA is written in CasADi in ipopt_transcription.py)")
except ImportError:
    print("pinocchio.casadi: not in the PyPI wheel; ipopt_transcription.py writes the RNEA in CasADi itself")
PY

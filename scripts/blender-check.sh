#!/usr/bin/env bash
# Imports exported BVH and glTF (.glb) files with Blender's stock importers, headless, and checks the
# armature's bone count, the keyed frame range and the scene's frame rate against what each file says
# (scripts/blender_check.py). Installs Debian's blender (and python3-numpy, which its glTF importer needs)
# with apt when missing. Exits non-zero on any mismatch.
#   bash scripts/blender-check.sh FILE.bvh FILE.glb ...
set -euo pipefail
if [ "$#" -eq 0 ]; then
    echo "usage: bash scripts/blender-check.sh FILE.bvh|FILE.glb ..." >&2
    exit 2
fi
if ! command -v blender >/dev/null || ! python3 -c 'import numpy' 2>/dev/null; then
    apt-get install -y --no-install-recommends blender python3-numpy >/dev/null
fi
log=$(mktemp)
trap 'rm -f "$log"' EXIT
status=0
blender -b --factory-startup --python-exit-code 1 --python "$(dirname "$0")/blender_check.py" -- "$@" >"$log" 2>&1 || status=$?
grep -E '^(Blender .*Python|ok|FAIL|all checks|[0-9]+ check|     )|Error' "$log" || true
exit "$status"

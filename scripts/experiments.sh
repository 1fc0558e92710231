#!/usr/bin/env bash
# Plans every bundled example (examples/*.toml) as `mintorque plan` does, copies each filmstrip to
# docs/experiments/NAME.png (the pictures docs/experiments.md shows) and prints the README's experiments
# table: converged, effort ½∫τᵀWτ dt, iterations and solve time, as measured in this run.
#   bash scripts/experiments.sh            # all examples
#   bash scripts/experiments.sh push_up    # some
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --quiet
names=("$@")
[ ${#names[@]} -gt 0 ] || names=($(ls examples/*.toml | xargs -n1 basename | sed 's/\.toml$//'))
mkdir -p docs/experiments out/experiments
echo "| example | converged | objective | iterations | solve (s) |"
echo "|---|---|---|---|---|"
for name in "${names[@]}"; do
    dir="out/experiments/$name"
    code=0
    ./target/release/mintorque plan "examples/$name.toml" --out "$dir" > "out/experiments/$name.log" 2>&1 || code=$?
    if [ "$code" -ne 0 ] && [ "$code" -ne 3 ]; then
        echo "| $name | error (exit $code, see out/experiments/$name.log) | | | |"
        continue
    fi
    cp "$dir/filmstrip.png" "docs/experiments/$name.png"
    python3 - "$dir/summary.json" "$name" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
print(f"| {sys.argv[2]} | {'yes' if d['converged'] else 'no'} | {d['objective']:.4g} | {d['iterations']} | {d['solve_seconds']:.2f} |")
PY
done

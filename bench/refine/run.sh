#!/usr/bin/env bash
# The refinement of N on the bundled examples (docs/performance.md, "A converged discretisation"): each
# example planned with --refine (its N the first level), one row per example — the levels (N, effort,
# iterations), the verdict, the last change of the effort and the whole solve's seconds — as a Markdown
# table on stdout. Usage: bash bench/refine/run.sh [EXAMPLE ...] (default: every examples/*.toml).
# Each plan gets TIME_LIMIT seconds of wall time (default 300), then is killed and listed so.
set -euo pipefail
cd "$(dirname "$0")/../.."
cargo build --release --quiet
out=$(mktemp -d)
names=("$@")
[ ${#names[@]} -gt 0 ] || names=($(ls examples/*.toml | xargs -n1 basename | sed 's/\.toml$//'))
echo "| example | levels: N (effort, iterations) | discretisation | last change | solve (s) |"
echo "|---|---|---|---|---|"
for name in "${names[@]}"; do
    code=0
    timeout "${TIME_LIMIT:-300}" ./target/release/mintorque plan "examples/$name.toml" --refine --no-plots -q --out "$out/$name" 2>"$out/$name.err" || code=$?
    if [ ! -f "$out/$name/summary.json" ]; then
        echo "| $name | (exit $code: $(head -c 120 "$out/$name.err" | tr '\n' ' ')) | | | |"
        continue
    fi
    python3 - "$out/$name/summary.json" "$name" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
levels = " → ".join(
    f"{l['control_points']} ({l['objective']:.6g}, {l['iterations']})" + ("" if l["converged"] else " not converged")
    for l in s["refinement"]
)
change = s.get("effort_change_last_refinement")
change = "—" if change is None else f"{100 * change:.2f} %"
print(f"| {sys.argv[2]} | {levels} | {s.get('discretization')} | {change} | {s['solve_seconds']:.2f} |")
PY
done
rm -rf "$out"

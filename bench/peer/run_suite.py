#!/usr/bin/env python3
"""Runs mintorque and the CasADi/IPOPT peer side by side on the suite and prints a markdown table.

Called by bench/peer/run.sh. For each task: `mintorque plan TASK --out DIR -q --no-plots` as a subprocess
(its effort, iterations and solve seconds from DIR/summary.json; the process timed around it), then
`ipopt_transcription.py DIR` (same discrete problem, same start; the process timed around it). A failed
sameness check or a mintorque exit other than 0/3 is reported in the table and makes the exit status 1.
"""

import json
import os
import subprocess
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
REPO = HERE.parent.parent
SUITE = [
    "examples/pendulum.toml",
    "examples/double_pendulum.toml",
    "examples/arm_lift_earth.toml",
    "examples/arm_lift_space.toml",
    "bench/peer/tasks/h7_reach_earth.toml",
    "bench/peer/tasks/h7_raise_moon.toml",
    "bench/peer/tasks/h13_twist_reach_earth.toml",
    "bench/peer/tasks/h13_side_bend_mars.toml",
    "bench/peer/tasks/h21_two_arm_raise_earth.toml",
    "bench/peer/tasks/h21_asymmetric_space.toml",
    "bench/peer/tasks/h36_wave_step_earth.toml",
    "bench/peer/tasks/h36_crouch_arms_mars.toml",
]


def fmt_t(s):
    if s is None:
        return "—"
    return f"{s * 1e3:.1f} ms" if s < 1 else f"{s:.2f} s"


def main():
    mintorque = os.environ.get("MINTORQUE", str(REPO / "target" / "release" / "mintorque"))
    python = os.environ.get("PEER_PYTHON", str(HERE / ".venv" / "bin" / "python"))
    out_root = Path(os.environ.get("PEER_OUT", HERE / "out"))
    only = [a for a in sys.argv[1:]]
    tasks = [t for t in SUITE if not only or any(o in t for o in only)]
    header = (
        "| task | ours | DOF | N | F ours | F IPOPT | F ours / F IPOPT | ours solve | ours whole | ours iter | "
        "IPOPT solve | IPOPT build | IPOPT whole | IPOPT iter | IPOPT solve / ours solve | sameness | notes |\n"
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
    )
    print(header, flush=True)

    class Rows(list):
        def append(self, row):
            super().append(row)
            print(row, flush=True)

    rows, failures, records = Rows(), 0, []
    # Our solver in several configurations, side by side against one IPOPT run per task (IPOPT's problem is
    # read from the first configuration's plan directory; the discrete problem is the same for all).
    variants = [v.split() for v in os.environ.get(
        "MINTORQUE_VARIANTS", "default;--solver structured --starts 1;--solver newton --starts 1").split(";")]
    for task in tasks:
        name = Path(task).stem
        ours = []
        for v in variants:
            label = " ".join(v) or "default"
            d = out_root / name / (label.replace(" ", "_").replace("-", "") or "default")
            d.mkdir(parents=True, exist_ok=True)
            args = [] if v == ["default"] else v
            t0 = time.perf_counter()
            p = subprocess.run([mintorque, "plan", str(REPO / task), "--out", str(d), "-q", "--no-plots", *args],
                               capture_output=True, text=True)
            whole = time.perf_counter() - t0
            if p.returncode not in (0, 3) or not (d / "summary.json").exists():
                rows.append(f"| {name} | {label} | mintorque failed (exit {p.returncode}): {p.stderr.strip()[:80]} |")
                failures += 1
                continue
            ours.append((label, d, json.loads((d / "summary.json").read_text()), whole))
        if not ours:
            continue
        d = ours[0][1]
        subprocess.run([mintorque, "figure", str(d / "model.figure.toml"), "--out", str(d / "model.urdf")],
                       check=True, capture_output=True)
        t0 = time.perf_counter()
        q = subprocess.run([python, str(HERE / "ipopt_transcription.py"), str(d)], capture_output=True, text=True)
        peer_whole = time.perf_counter() - t0
        try:
            r = json.loads(q.stdout.strip().splitlines()[-1])
        except (IndexError, json.JSONDecodeError):
            rows.append(f"| {name} | — | — | peer failed (exit {q.returncode}): {q.stderr.strip()[-120:]} |")
            failures += 1
            continue
        (d / "peer.json").write_text(q.stdout.strip().splitlines()[-1])
        r.pop("x_ipopt_ctrl", None)
        if not r["checks_ok"]:
            failures += 1
        same = max(r["checks"]["F_at_our_plan_rel"], r["checks"]["F_at_guess_rel"])
        for label, _, s, ours_whole in ours:
            ratio = s["objective"] / r["F_ipopt"] if r["F_ipopt"] > 0 else float("nan")
            note = []
            if not s["converged"]:
                note.append(f"ours NOT converged ({s.get('reason')})")
            if not r["ipopt_success"] or r["ipopt_status"] != "Solve_Succeeded":
                note.append(f"IPOPT: {r['ipopt_status']}")
            if not r["checks_ok"]:
                note.append("SAMENESS CHECK FAILED")
            rows.append(
                f"| {name} | {label} | {r['dof']} | {r['n_ctrl']} | {s['objective']:.6g} | {r['F_ipopt']:.6g} | "
                f"{ratio:.4f} | {fmt_t(s['solve_seconds'])} | {fmt_t(ours_whole)} | {s['iterations']} | "
                f"{fmt_t(r['ipopt_solve_s'])} | {fmt_t(r['ipopt_build_s'])} | {fmt_t(peer_whole)} | "
                f"{r['ipopt_iterations']} | {r['ipopt_solve_s'] / max(s['solve_seconds'], 1e-9):.0f}× | {same:.0e} | "
                f"{'; '.join(note)} |"
            )
            records.append({"task": name, "variant": label,
                            "ours": {k: s[k] for k in ("objective", "converged", "reason", "iterations",
                                                       "solve_seconds", "initial_guess_objective")},
                            "ours_whole_s": ours_whole, "peer": r, "peer_whole_s": peer_whole})
        print(f"done {name}: IPOPT {r['F_ipopt']:.6g}", file=sys.stderr, flush=True)
    (out_root / "results.json").write_text(json.dumps(records, indent=1))
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()

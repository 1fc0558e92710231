#!/usr/bin/env python3
"""Runs mintorque and the CasADi/IPOPT peer side by side on the suite and prints a markdown table.

Called by bench/peer/run.sh. For each task: `mintorque plan TASK --out DIR -q --no-plots` as a subprocess
(its effort, iterations and solve seconds from DIR/summary.json; the process timed around it), then
`ipopt_transcription.py DIR` (same discrete problem, same start; the process timed around it). A failed
sameness check or a mintorque exit other than 0/3 is reported in the table and makes the exit status 1.

On the small figures (MOCO_TASKS) also OpenSim Moco: `mintorque export DIR --format osim`, then
`moco_study.py DIR --intervals M` in OpenSim's venv ($MOCO_PYTHON; MOCO=0 skips it) for M = 100 and for M = our
number of knot spans (N - 3), and ours once more with `--refine` (the converged discretisation).
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
# The figures OpenSim Moco also solves (its dense finite-difference Jacobians make bigger ones take too long).
MOCO_TASKS = ("pendulum", "double_pendulum", "arm_lift_earth")
MOCO_INTERVALS = 100


def fmt_t(s):
    if s is None:
        return "—"
    return f"{s * 1e3:.1f} ms" if s < 1 else f"{s:.2f} s"


HEADER = (
    "| task | ours | DOF | N | F ours | F IPOPT | F ours / F IPOPT | ours solve | ours whole | ours iter | "
    "IPOPT solve | IPOPT build | IPOPT whole | IPOPT iter | IPOPT solve / ours solve | sameness | "
    "F Moco (100) | F ours / F Moco | Moco solve | Moco whole | Moco iter | F Moco (N − 3) | notes |\n"
    "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
)


def run_ours(mintorque, task, out_root, variants):
    """Each configuration of ours on the task: [(label, DIR, summary, whole s)], and the failure rows."""
    name, ours, failed = Path(task).stem, [], []
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
            failed.append(f"| {name} | {label} | mintorque failed (exit {p.returncode}): {p.stderr.strip()[:80]} |")
            continue
        ours.append((label, d, json.loads((d / "summary.json").read_text()), whole))
    return ours, failed


def run_peer(python, args):
    """A peer script as a subprocess: (its JSON result or None, the process's wall time, stderr's tail)."""
    t0 = time.perf_counter()
    q = subprocess.run([python, *map(str, args)], capture_output=True, text=True, cwd=HERE)
    whole = time.perf_counter() - t0
    try:
        return json.loads(q.stdout.strip().splitlines()[-1]), whole, ""
    except (IndexError, json.JSONDecodeError):
        return None, whole, f"exit {q.returncode}: {q.stderr.strip()[-120:]}"


def run_moco(mintorque, python, d, n_ctrl):
    """Moco on DIR's figure at 100 intervals and at N - 3 (our knot spans): {intervals: (result, whole s)}."""
    subprocess.run([mintorque, "export", str(d), "--format", "osim", "-o", str(d / "model.osim")], check=True,
                   capture_output=True)
    out = {}
    for m in (MOCO_INTERVALS, n_ctrl - 3):
        r, whole, err = run_peer(python, [HERE / "moco_study.py", d, "--intervals", m])
        if r is not None:
            r.pop("time", None), r.pop("q", None)
        out[m] = (r, whole, err)
        print(f"  Moco {m} intervals: {r['F_moco'] if r else err}", file=sys.stderr, flush=True)
    return out


def moco_cells(moco, F_ours):
    """The Moco columns of a row (F at 100, ratio, solve, whole, iterations, F at N - 3) and notes."""
    if not moco:
        return ["—"] * 6, []
    (r, whole, err), (rc, _, errc) = moco[MOCO_INTERVALS], list(moco.values())[-1]
    notes = [] if r else [f"Moco failed ({err})"]
    if r and (not r["checks_ok"] or not r["moco_success"]):
        notes.append(f"Moco: {r['moco_status']}, checks {r['checks']}")
    if rc is None:
        notes.append(f"Moco coarse failed ({errc})")
    if not r:
        return ["—"] * 6, notes
    coarse = f"{rc['F_moco']:.6g} ({rc['intervals']})" if rc else "—"
    return [f"{r['F_moco']:.6g}", f"{F_ours / r['F_moco']:.4f}", fmt_t(r["moco_solve_s"]), fmt_t(whole),
            str(r["moco_iterations"]), coarse], notes


def ipopt_cells(r, s, peer_whole, same_n):
    """The IPOPT columns of a row; its ratios only where our discretisation is the one IPOPT solved."""
    ratio = f"{s['objective'] / r['F_ipopt']:.4f}" if same_n and r["F_ipopt"] > 0 else "— (other N)"
    speed = f"{r['ipopt_solve_s'] / max(s['solve_seconds'], 1e-9):.0f}×" if same_n else "—"
    same = max(r["checks"]["F_at_our_plan_rel"], r["checks"]["F_at_guess_rel"])
    return [f"{r['F_ipopt']:.6g}", ratio, fmt_t(s["solve_seconds"]), None, str(s["iterations"]),
            fmt_t(r["ipopt_solve_s"]), fmt_t(r["ipopt_build_s"]), fmt_t(peer_whole), str(r["ipopt_iterations"]),
            speed, f"{same:.0e}"]


def row(name, label, r, s, ours_whole, peer_whole, moco):
    """One markdown row: ours in one configuration against IPOPT (same N) and Moco."""
    same_n = s["control_points"] == r["n_ctrl"]
    cells = ipopt_cells(r, s, peer_whole, same_n)
    cells[3] = fmt_t(ours_whole)
    mcells, notes = moco_cells(moco, s["objective"])
    if not s["converged"]:
        notes.insert(0, f"ours NOT converged ({s.get('reason')})")
    if not r["ipopt_success"] or r["ipopt_status"] != "Solve_Succeeded":
        notes.append(f"IPOPT: {r['ipopt_status']}")
    if not r["checks_ok"]:
        notes.append("SAMENESS CHECK FAILED")
    head = [name, label, str(r["dof"]), str(s["control_points"]), f"{s['objective']:.6g}"]
    return "| " + " | ".join(head + cells + mcells + ["; ".join(notes)]) + " |"


def main():
    mintorque = os.environ.get("MINTORQUE", str(REPO / "target" / "release" / "mintorque"))
    python = os.environ.get("PEER_PYTHON", str(HERE / ".venv" / "bin" / "python"))
    moco_python = os.environ.get("MOCO_PYTHON", str(REPO / "target" / "opensim-venv" / "bin" / "python"))
    with_moco = os.environ.get("MOCO", "1") != "0"
    out_root = Path(os.environ.get("PEER_OUT", HERE / "out"))
    only = sys.argv[1:]
    tasks = [t for t in SUITE if not only or any(o in t for o in only)]
    print(HEADER, flush=True)
    failures, records = 0, []
    # Our solver in several configurations, side by side against one IPOPT run per task (IPOPT's problem is
    # read from the first configuration's plan directory; the discrete problem is the same for all).
    variants = [v.split() for v in os.environ.get(
        "MINTORQUE_VARIANTS", "default;--solver structured --starts 1;--solver newton --starts 1").split(";")]
    for task in tasks:
        name = Path(task).stem
        moco_task = with_moco and name in MOCO_TASKS
        ours, failed = run_ours(mintorque, task, out_root, variants + ([["--refine"]] if moco_task else []))
        failures += len(failed)
        for f in failed:
            print(f, flush=True)
        if not ours:
            continue
        d = ours[0][1]
        subprocess.run([mintorque, "figure", str(d / "model.figure.toml"), "--out", str(d / "model.urdf")],
                       check=True, capture_output=True)
        r, peer_whole, err = run_peer(python, [HERE / "ipopt_transcription.py", d])
        if r is None:
            print(f"| {name} | — | — | peer failed ({err}) |", flush=True)
            failures += 1
            continue
        (d / "peer.json").write_text(json.dumps(r))
        r.pop("x_ipopt_ctrl", None)
        moco = run_moco(mintorque, moco_python, d, r["n_ctrl"]) if moco_task else {}
        failures += (not r["checks_ok"]) + sum(m is None or not m["checks_ok"] for m, _, _ in moco.values())
        for label, _, s, ours_whole in ours:
            print(row(name, label, r, s, ours_whole, peer_whole, moco), flush=True)
            records.append({"task": name, "variant": label,
                            "ours": {k: s[k] for k in ("objective", "converged", "reason", "iterations",
                                                       "solve_seconds", "initial_guess_objective",
                                                       "control_points")},
                            "ours_whole_s": ours_whole, "peer": r, "peer_whole_s": peer_whole,
                            "moco": {str(m): {"result": v[0], "whole_s": v[1]} for m, v in moco.items()}})
        print(f"done {name}: IPOPT {r['F_ipopt']:.6g}", file=sys.stderr, flush=True)
    (out_root / "results.json").write_text(json.dumps(records, indent=1))
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()

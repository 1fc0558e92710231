#!/usr/bin/env python3
"""Two mintorque binaries (or one binary under two environments) on the same tasks, side by side: what a
solver change does to the iterations, the time and the optima, against the noise floor of rounding.

    python3 bench/ab/compare.py --a OLD_BIN --b NEW_BIN                 # 27 bundled examples + 8 peer tasks, default starts
    python3 bench/ab/compare.py --a BIN --b BIN --env-b KNOB=1          # one binary, a switch read from the environment
    python3 bench/ab/compare.py --a OLD --b NEW --starts 1 --tasks h7 h13   # one start; tasks whose path has a word
    python3 bench/ab/compare.py --a OLD --b NEW --reps 5 --tasks h36        # the median time of five alternating runs

Each task runs `plan TASK -q --no-plots --out DIR` with A, then with B (alternating, so that a busy machine
slows both alike), and the table lists per task: the iterations of every start's first solve summed
("all starts") and of the kept plan (its between-node re-solves included), the kept effort of each and their
relative change, and the solve seconds. Below it: the totals, the tasks and the starts whose effort moved by
more than --tol (relative; 1e-3 by default), and the noise floor to read them against.

Solve times on this host swing by up to 2.4× within the hour: with --reps K each task runs K times, A and B
alternating, and the table gives the median solve seconds with the range (the iterations and efforts are the
first run's; a plan is the same run after run).

The noise floor (docs/performance.md, "Step control and the inequalities' kinks"): a change in the last bits of
the factorisation alone, on these 35 tasks with the default starts, moved 2 kept efforts (by 0.1 and 0.3 %) and
5 of about 110 starts into other basins. A change that moves many more, both ways, has changed which basins
the paths reach; only the totals and the peer ratios tell whether for the better.

Standard library only. Exit status 1 if a run fails (no summary.json).
"""

import argparse
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
PEER = ["h7", "h13", "h21", "h36"]


def tasks(words):
    """The bundled examples and the peer tasks, or those whose path contains one of `words`."""
    paths = sorted((REPO / "examples").glob("*.toml"))
    paths += [p for w in PEER for p in sorted((REPO / "bench/peer/tasks").glob(f"{w}_*.toml"))]
    if words:
        paths = [p for p in paths if any(w in str(p.relative_to(REPO)) for w in words)]
    return paths


def run(binary, task, starts, env, scratch):
    """One plan; its summary's figures, or None if it wrote none."""
    out = scratch / f"{task.stem}-{time.monotonic_ns()}"
    cmd = [binary, "plan", str(task), "--out", str(out), "-q", "--no-plots"]
    if starts:
        cmd += ["--starts", starts]
    subprocess.run(cmd, env={**os.environ, **env}, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    summary = out / "summary.json"
    if not summary.exists():
        return None
    s = json.loads(summary.read_text())
    shutil.rmtree(out, ignore_errors=True)
    first = [(t["iterations"], t["objective"], t["converged"]) for t in s.get("starts", [])]
    return {
        "iterations": s["iterations"],
        "objective": s["objective"],
        "seconds": s["solve_seconds"],
        "converged": s["converged"],
        "starts": first,
        "all_starts": sum(t[0] for t in first) or s["iterations"],
    }


def moved(a, b, tol):
    """+1 if effort `b` is higher than `a` by more than `tol` (relative), −1 if lower, 0 otherwise."""
    if a is None or b is None:
        return 0
    rel = (b - a) / max(abs(a), 1e-300)
    return 1 if rel > tol else (-1 if rel < -tol else 0)


def seconds(times, a, b):
    """The solve seconds of A and B: the medians, and with several runs their ranges."""
    if len(times[0]) < 2:
        return f"{a['seconds']:.2f} · {b['seconds']:.2f}"
    span = lambda t: f"{min(t):.3f}–{max(t):.3f}"
    return f"{a['seconds']:.3f} ({span(times[0])}) · {b['seconds']:.3f} ({span(times[1])})"


def env_pairs(pairs):
    env = {}
    for p in pairs or []:
        key, _, value = p.partition("=")
        env[key] = value
    return env


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--a", required=True, help="the reference binary")
    ap.add_argument("--b", required=True, help="the binary under test (may be the same as --a with --env-b)")
    ap.add_argument("--env-a", nargs="*", metavar="K=V", help="environment for A's runs")
    ap.add_argument("--env-b", nargs="*", metavar="K=V", help="environment for B's runs")
    ap.add_argument("--starts", default=None, help="--starts for both (default: the task's, i.e. auto)")
    ap.add_argument("--tasks", nargs="*", default=[], help="only tasks whose path contains one of these words")
    ap.add_argument("--tol", type=float, default=1e-3, help="relative effort change that counts as moved")
    ap.add_argument("--reps", type=int, default=1, help="alternating runs per task; the median solve time is shown")
    args = ap.parse_args()
    env_a, env_b = env_pairs(args.env_a), env_pairs(args.env_b)
    scratch = Path(tempfile.mkdtemp(prefix="mintorque-ab-"))
    print("| task | all starts A · B | kept A · B | effort A | effort B | change | solve s A · B |")
    print("|---|---|---|---|---|---|---|")
    totals = {"all": [0, 0], "kept": [0, 0], "s": [0.0, 0.0]}
    tasks_moved, starts_moved, failed = [0, 0], [0, 0], []
    for task in tasks(args.tasks):
        a, b, times = None, None, ([], [])
        for _ in range(max(1, args.reps)):
            ra = run(args.a, task, args.starts, env_a, scratch)
            rb = run(args.b, task, args.starts, env_b, scratch)
            a, b = a or ra, b or rb
            for t, r in zip(times, (ra, rb)):
                if r is not None:
                    t.append(r["seconds"])
        if a is None or b is None:
            failed.append(task.stem)
            print(f"| {task.stem} | run failed: {'A' if a is None else ''}{'B' if b is None else ''} | | | | | |")
            continue
        a["seconds"], b["seconds"] = statistics.median(times[0]), statistics.median(times[1])
        for k, key in (("all", "all_starts"), ("kept", "iterations"), ("s", "seconds")):
            totals[k][0] += a[key]
            totals[k][1] += b[key]
        m = moved(a["objective"], b["objective"], args.tol)
        if m:
            tasks_moved[m < 0] += 1
        for sa, sb in zip(a["starts"], b["starts"]):
            ms = moved(sa[1], sb[1], args.tol) if sa[2] and sb[2] else 0
            if ms:
                starts_moved[ms < 0] += 1
        rel = (b["objective"] - a["objective"]) / max(abs(a["objective"]), 1e-300)
        flag = {1: " higher", -1: " lower", 0: ""}[m]
        conv = "" if a["converged"] == b["converged"] else f" (converged {a['converged']} → {b['converged']})"
        print(
            f"| {task.stem} | {a['all_starts']} · {b['all_starts']} | {a['iterations']} · {b['iterations']} | "
            f"{a['objective']:.6g} | {b['objective']:.6g} | {rel:+.4%}{flag}{conv} | {seconds(times, a, b)} |"
        )
    shutil.rmtree(scratch, ignore_errors=True)
    print()
    print(f"iterations, all starts' first solves: A {totals['all'][0]}, B {totals['all'][1]}; kept plans: A {totals['kept'][0]}, B {totals['kept'][1]}")
    what = f"medians of {args.reps} alternating runs, summed" if args.reps > 1 else "one run each"
    print(f"solve seconds ({what}): A {totals['s'][0]:.2f}, B {totals['s'][1]:.2f}")
    print(f"efforts moved by more than {args.tol:g}: tasks {tasks_moved[0]} higher, {tasks_moved[1]} lower; starts {starts_moved[0]} higher, {starts_moved[1]} lower")
    print("noise floor of rounding alone (default starts, 35 tasks): 2 tasks and 5 of ~110 starts moved")
    if failed:
        print(f"failed: {', '.join(failed)}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())

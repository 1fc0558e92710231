#!/usr/bin/env python3
"""OpenSim Moco on the figure of a mintorque plan: the continuous minimum-torque problem, by direct collocation.

  moco_study.py DIR [--intervals M]

Reads a plan directory written by `mintorque plan TASK --out DIR` (and DIR/model.osim, written by
`mintorque export DIR --format osim -o DIR/model.osim`) and poses the same optimal control problem in Moco:

  * the model: DIR/model.osim (bodies, inertias, joint axes and placements, gravity exported by mintorque),
    plus each joint's passive spring and damper from DIR/model.figure.toml as a SpringGeneralizedForce
    (tau_passive = -stiffness (q - rest) - damping q', mintorque's "resistant torque"), plus one
    CoordinateActuator per coordinate with optimal force 1 N·m (so its control u is the active torque);
  * sameness of the model, checked on every run (exit 2 if it fails): OpenSim's inverse dynamics
    (InverseDynamicsSolver, the springs applied, no actuators) at samples of DIR/trajectory.csv equals
    mintorque's active torque there, max |tau_OpenSim - tau_ours| / max |tau_ours| <= 1e-6 (the CSV's digits);
  * the problem: t in [0, T] with T = plan.json's duration; q(0), q(T) = plan.json's first and last control
    points (the task's start and goal), q'(0) = q'(T) = 0; coordinate bounds = the figure's position limits
    (unlimited sides unbounded) when constraints.position_limits; control bounds = +-effort when
    constraints.torque_limits; speeds bounded by +-SPEED_BOUND (never active here; Moco wants a bound);
  * the objective: MocoControlGoal (weight 1, exponent 2, per-control weights = the task's joint weights),
    J = integral of sum_i w_i u_i^2 dt, so F_Moco = J / 2 = 1/2 integral tau^T W tau dt, mintorque's effort;
  * the solver: MocoCasADiSolver with its defaults (Hermite-Simpson collocation, IPOPT with a limited-memory
    Hessian, Moco's default guess: states linear from the initial to the final bounds, controls at the middle
    of their bounds) and `--intervals` mesh intervals (default 100).

F_Moco is recomputed from the solution as 1/2 sum_i w_i u_i^2 integrated by Simpson's rule over each mesh
interval (Hermite-Simpson's own quadrature: the controls at both mesh points and the midpoint), and checked
against Moco's reported objective / 2 (1e-6 relative). Prints one JSON object on stdout.
"""

import argparse
import csv
import json
import math
import sys
import time
import tomllib
from pathlib import Path

T_START = time.perf_counter()

import numpy as np  # noqa: E402
import opensim as osim  # noqa: E402

from task_features import unsupported_features  # noqa: E402

SPEED_BOUND = 100.0  # rad/s or m/s
ID_CHECK_TOL = 1e-6
ID_CHECK_SAMPLES = 7


def figure_joints(figure, names):
    """Per joint of plan.json's order, from model.figure.toml: kind, limits, effort, spring, damper (SI)."""
    found = {}
    for body in figure.get("body", []):
        j = body.get("joint", {})
        kind = j.get("type")
        if kind == "fixed":
            continue
        if kind not in ("revolute", "prismatic"):
            raise SystemExit(f"model.figure.toml body {body.get('name')!r}: joint type {kind!r} is not "
                             "supported by the Moco peer (revolute or prismatic only)")
        for field in ("effort_positive", "effort_negative"):
            if field in j:
                raise SystemExit(f"model.figure.toml joint {j['name']!r}: {field} (asymmetric torque limits) "
                                 "is not supported by the Moco peer")
        deg = kind == "revolute"
        angle = (lambda v: math.radians(v)) if deg else (lambda v: v)  # noqa: E731
        suffix = "_deg" if deg else ""
        found[j["name"]] = {
            "revolute": deg,
            "lower": angle(j[f"lower{suffix}"]) if f"lower{suffix}" in j else -math.inf,
            "upper": angle(j[f"upper{suffix}"]) if f"upper{suffix}" in j else math.inf,
            "effort": j.get("effort", math.inf),
            "stiffness": j.get("stiffness", 0.0),
            "rest": angle(j.get(f"rest{suffix}", 0.0)),
            "damping": j.get("damping", 0.0),
        }
    missing = [n for n in names if n not in found]
    if missing:
        raise SystemExit(f"joints {missing} of plan.json are not in model.figure.toml")
    return [found[n] for n in names]


def add_passive(model, names, joints):
    """One SpringGeneralizedForce per joint with a spring or a damper: -stiffness (q - rest) - damping q'."""
    for name, j in zip(names, joints):
        if j["stiffness"] == 0.0 and j["damping"] == 0.0:
            continue
        spring = osim.SpringGeneralizedForce(name)
        spring.setName(f"passive_{name}")
        spring.setStiffness(j["stiffness"])
        spring.setRestLength(j["rest"])
        spring.setViscosity(j["damping"])
        model.addForce(spring)


def add_actuators(model, names):
    """One CoordinateActuator per coordinate, optimal force 1: its control is the joint's active torque."""
    for name in names:
        act = osim.CoordinateActuator(name)
        act.setName(f"tau_{name}")
        act.setOptimalForce(1.0)
        act.setMinControl(-math.inf)
        act.setMaxControl(math.inf)
        model.addForce(act)


def u_indices(model, state, names):
    """Each coordinate's index in Simbody's u (probed: set one speed, see which entry moves)."""
    cs = model.getCoordinateSet()
    out = []
    for name in names:
        state.setU(osim.Vector(state.getNU(), 0.0))
        cs.get(name).setSpeedValue(state, 1.0)
        out.append([i for i in range(state.getNU()) if state.getU()[i] != 0.0][0])
    return out


def trajectory_samples(path, names, joints, count):
    """`count` evenly spaced rows of trajectory.csv: (q, q', q'', tau) in SI, mintorque's active torque."""
    with open(path, newline="") as f:
        rows = [r for r in csv.DictReader(f)]
    picks = np.linspace(0, len(rows) - 1, count).round().astype(int)
    out = []
    for k in picks:
        r = rows[k]
        conv = [math.radians if j["revolute"] else float for j in joints]
        unit = ["deg" if j["revolute"] else "m" for j in joints]
        force = ["Nm" if j["revolute"] else "N" for j in joints]

        def col(suffix, i):
            key = f"{names[i]}.{suffix.format(u=unit[i])}"
            return conv[i](float(r[key]))

        q = [col("q_{u}", i) for i in range(len(names))]
        qd = [col("qd_{u}_s", i) for i in range(len(names))]
        qdd = [col("qdd_{u}_s2", i) for i in range(len(names))]
        tau = [float(r[f"{names[i]}.tau_{force[i]}"]) for i in range(len(names))]
        out.append((q, qd, qdd, tau))
    return out


def inverse_dynamics_check(model, names, samples):
    """max |tau_OpenSim - tau_ours| / max |tau_ours| over the samples (springs applied, no actuators)."""
    state = model.initSystem()
    ui = u_indices(model, state, names)
    cs = model.getCoordinateSet()
    solver = osim.InverseDynamicsSolver(model)
    worst_diff, worst_tau = 0.0, 0.0
    for q, qd, qdd, tau in samples:
        udot = osim.Vector(state.getNU(), 0.0)
        for i, name in enumerate(names):
            cs.get(name).setValue(state, q[i], False)
            cs.get(name).setSpeedValue(state, qd[i])
            udot.set(ui[i], qdd[i])
        model.realizeDynamics(state)
        tau_os = solver.solve(state, udot)
        # tau_ours = H q'' + C - tau_passive, the active torque, as OpenSim's residual with the springs applied.
        for i in range(len(names)):
            worst_diff = max(worst_diff, abs(tau_os.get(ui[i]) - tau[i]))
            worst_tau = max(worst_tau, abs(tau[i]))
    return worst_diff / max(worst_tau, 1e-12)


def pose(model, names, joints, plan, task, intervals):
    """The MocoStudy: time, state and control bounds, the control goal, the CasADi solver."""
    c = task.get("constraints", {})
    n, N = len(names), plan["n_ctrl"]
    ctrl = np.array(plan["ctrl"], dtype=float).reshape(N, n)
    q0, qT = ctrl[0], ctrl[N - 1]
    weights = task.get("objective", {}).get("weights", {}) or {}
    study = osim.MocoStudy()
    study.setName("mintorque_peer")
    problem = study.updProblem()
    problem.setModelAsCopy(model)
    problem.setTimeBounds(0.0, plan["duration"])
    goal = osim.MocoControlGoal("effort", 1.0)
    cs = model.getCoordinateSet()
    for i, (name, j) in enumerate(zip(names, joints)):
        path = cs.get(name).getAbsolutePathString()
        lo, hi = (j["lower"], j["upper"]) if c.get("position_limits", True) else (-math.inf, math.inf)
        # q in [lower, upper], q(0) = start, q(T) = goal; q' = 0 at both ends.
        problem.setStateInfo(f"{path}/value", [lo, hi], float(q0[i]), float(qT[i]))
        problem.setStateInfo(f"{path}/speed", [-SPEED_BOUND, SPEED_BOUND], 0.0, 0.0)
        effort = j["effort"] if c.get("torque_limits", True) else math.inf
        problem.setControlInfo(f"/forceset/tau_{name}", [-effort, effort])
        goal.setWeightForControl(f"/forceset/tau_{name}", float(weights.get(name, 1.0)))
    problem.addGoal(goal)
    solver = study.initCasADiSolver()
    solver.set_num_mesh_intervals(intervals)
    solver.set_verbosity(0)
    solver.set_optim_ipopt_print_level(0)
    return study


def effort_on_grid(solution, names, weights):
    """1/2 integral of sum_i w_i u_i^2 dt by Simpson's rule per mesh interval (mesh point, midpoint, mesh point)."""
    t = np.array(solution.getTimeMat()).ravel()
    labels = list(solution.getControlNames())
    u = np.array(solution.getControlsTrajectoryMat())
    w = np.array([float(weights.get(lab.split("tau_")[-1], 1.0)) for lab in labels])
    f = 0.5 * (u ** 2 * w).sum(axis=1)
    if (len(t) - 1) % 2:
        raise SystemExit(f"Moco's grid has {len(t)} points: not a Hermite-Simpson grid (2M + 1)")
    # Simpson per interval [t_2k, t_2k+2]: (h/6)(f_2k + 4 f_2k+1 + f_2k+2), h = t_2k+2 - t_2k.
    h = t[2::2] - t[:-2:2]
    return float((h / 6.0 * (f[:-2:2] + 4.0 * f[1::2] + f[2::2])).sum()), t


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("plan_dir", help="a directory written by `mintorque plan TASK --out DIR`")
    ap.add_argument("--intervals", type=int, default=100, help="Moco's num_mesh_intervals (default 100)")
    args = ap.parse_args()
    osim.Logger.removeFileSink()  # no opensim.log left behind
    osim.Logger.setLevelString("warn")
    d = Path(args.plan_dir)
    plan = json.loads((d / "plan.json").read_text())
    task = tomllib.loads((d / "task.resolved.toml").read_text())
    figure = tomllib.loads((d / "model.figure.toml").read_text())
    unsupported = unsupported_features(task)
    if unsupported:
        raise SystemExit(f"unsupported by the Moco peer: {', '.join(unsupported)}")
    names = plan["joint_names"]
    joints = figure_joints(figure, names)
    if not (d / "model.osim").exists():
        raise SystemExit(f"{d / 'model.osim'} missing: write it with `mintorque export {d} --format osim -o "
                         f"{d / 'model.osim'}`")
    model = osim.Model(str(d / "model.osim"))
    add_passive(model, names, joints)
    model.finalizeConnections()
    id_rel = inverse_dynamics_check(model, names, trajectory_samples(d / "trajectory.csv", names, joints,
                                                                      ID_CHECK_SAMPLES))
    add_actuators(model, names)
    model.finalizeConnections()
    model.initSystem()
    study = pose(model, names, joints, plan, task, args.intervals)
    build_s = time.perf_counter() - T_START
    solution = study.solve()
    solution.unseal()
    weights = task.get("objective", {}).get("weights", {}) or {}
    F_grid, t = effort_on_grid(solution, names, weights)
    F_reported = 0.5 * solution.getObjective()
    out_dir = d / "moco"
    out_dir.mkdir(exist_ok=True)
    solution.write(str(out_dir / f"solution_{args.intervals}.sto"))
    checks = {"inverse_dynamics_rel": id_rel, "objective_grid_vs_reported_rel":
              abs(F_grid - F_reported) / max(abs(F_reported), 1e-300)}
    ok = checks["inverse_dynamics_rel"] <= ID_CHECK_TOL and checks["objective_grid_vs_reported_rel"] <= 1e-6
    q = np.array(solution.getStatesTrajectoryMat())
    state_names = list(solution.getStateNames())
    result = {
        "dof": len(names), "intervals": args.intervals, "F_moco": F_grid, "F_moco_reported": F_reported,
        "moco_success": bool(solution.success()), "moco_status": solution.getStatus(),
        "moco_iterations": int(solution.getNumIterations()), "moco_solve_s": float(solution.getSolverDuration()),
        "moco_build_s": build_s, "checks": checks, "checks_ok": ok,
        "time": t.tolist(),
        "q": {n: q[:, state_names.index(f"{model.getCoordinateSet().get(n).getAbsolutePathString()}/value")].tolist()
              for n in names},
        "peak_speed": float(np.abs(q[:, [i for i, s in enumerate(state_names) if s.endswith("/speed")]]).max()),
    }
    print(json.dumps(result))
    sys.exit(0 if ok else 2)


if __name__ == "__main__":
    main()

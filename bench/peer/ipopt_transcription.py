#!/usr/bin/env python3
"""The peer of mintorque's B-spline transcription, in CasADi, solved by IPOPT with exact Hessians.

Reads a plan directory written by `mintorque plan TASK --out DIR` and builds exactly the discrete problem
mintorque solved there:

  * the model: DIR/model.figure.toml (mintorque's resolved model: locks, payloads, passive springs and
    limit overrides already applied) converted to URDF by `mintorque figure` (DIR/model.urdf, written by the
    driver or by this script with --mintorque), parsed by Pinocchio (tree, joint placements, inertias);
    the passive springs/dampers from the URDF's <dynamics spring_stiffness spring_reference damping>;
  * the recursive Newton-Euler algorithm written here in CasADi symbolics (the PyPI wheel of `pin` has no
    `pinocchio.casadi`), checked against pinocchio.rnea at random states;
  * the clamped uniform cubic B-spline with N = plan.json's n_ctrl, duration T, the first/last two control
    points fixed by q(0), q'(0) = 0, q(T), q'(T) = 0 (taken bit-exactly from plan.json's control points);
  * the nodes: Gauss-Legendre, nodes_per_span per knot span (summary.json), plus both ends with weight 0;
  * objective F = 1/2 sum_k w_k tau_k^T W tau_k, tau = active torque = RNEA(q, qd, qdd; gravity) - passive;
  * position limits q_low <= q(t_k) <= q_up and torque limits |tau_i(t_k)| <= effort_i at every node;
  * the start: mintorque's linear initial guess (the straight line at the Greville abscissae with
    c1 = c0, c_{N-2} = c_{N-1}), computed here as the Rust code does it.

Sameness checks (the script exits 2 if one fails):
  * F at mintorque's converged control points (plan.json) = summary.json's `objective` to 1e-9 relative;
  * F at our initial guess = summary.json's `initial_guess_objective` to 1e-9 relative (same start);
  * the CasADi RNEA = pinocchio.rnea to 1e-10 relative at random states.

Prints one JSON object on stdout (effort, iterations, times, checks).
"""

import argparse
import json
import math
import subprocess
import sys
import time
import tomllib
import xml.etree.ElementTree as ET
from pathlib import Path

T_START = time.perf_counter()

import casadi as ca  # noqa: E402
import numpy as np  # noqa: E402
import pinocchio as pin  # noqa: E402

from task_features import unsupported_features  # noqa: E402


# ---------------------------------------------------------------- the model


class Body:
    pass


def load_model(urdf_path, joint_names):
    """Bodies in mintorque's joint order (`joint_names`), with parents, placements, axes, inertias, passive."""
    root = ET.parse(urdf_path).getroot()
    # urdfdom (Pinocchio's parser) demands <limit velocity>, which mintorque's URDF export leaves out:
    # parse a copy with a dummy velocity limit (unused here).
    for lim in root.iter("limit"):
        if lim.get("velocity") is None:
            lim.set("velocity", "1e9")
    model = pin.buildModelFromXML(ET.tostring(root, encoding="unicode"))
    xml_joints = {j.get("name"): j for j in root.findall("joint")}
    pin_names = list(model.names)
    if model.nq != model.nv or model.nv != len(joint_names):
        raise SystemExit(
            f"unsupported model: nq={model.nq}, nv={model.nv}, mintorque has {len(joint_names)} joints "
            "(only 1-DOF revolute/prismatic joints are supported)"
        )
    bodies = []
    for i in range(1, model.njoints):
        name = pin_names[i]
        xj = xml_joints[name]
        kind = xj.get("type")
        if kind not in ("revolute", "prismatic", "continuous"):
            raise SystemExit(f"joint {name}: type {kind} unsupported")
        axis_el = xj.find("axis")
        axis = np.array([float(v) for v in axis_el.get("xyz").split()]) if axis_el is not None else np.array([1.0, 0, 0])
        axis = axis / np.linalg.norm(axis)
        b = Body()
        b.name = name
        b.pin_index = i
        b.parent_pin = model.parents[i]
        b.revolute = kind != "prismatic"
        b.axis = axis
        b.R_T = np.array(model.jointPlacements[i].rotation)
        b.p_T = np.array(model.jointPlacements[i].translation)
        inertia = model.inertias[i]
        b.mass = float(inertia.mass)
        b.com = np.array(inertia.lever)
        b.I_c = np.array(inertia.inertia)
        dyn = xj.find("dynamics")
        num = lambda a: float(dyn.get(a)) if dyn is not None and dyn.get(a) is not None else 0.0  # noqa: E731
        b.stiffness, b.rest, b.damping = num("spring_stiffness"), num("spring_reference"), num("damping")
        limit = xj.find("limit")
        lim = lambda a, d: float(limit.get(a)) if limit is not None and limit.get(a) is not None else d  # noqa: E731
        if kind == "continuous":
            b.lower, b.upper = -math.inf, math.inf
        else:
            b.lower, b.upper = lim("lower", -math.inf), lim("upper", math.inf)
        b.effort = lim("effort", math.inf)
        bodies.append(b)
    by_name = {b.name: b for b in bodies}
    missing = [n for n in joint_names if n not in by_name]
    if missing:
        raise SystemExit(f"joints {missing} of plan.json are not in {urdf_path}")
    # Our order: mintorque's. Parents as indices into it (-1 = the fixed root).
    ordered = [by_name[n] for n in joint_names]
    pos = {b.pin_index: k for k, b in enumerate(ordered)}
    for b in ordered:
        b.parent = pos.get(b.parent_pin, -1) if b.parent_pin != 0 else -1
    # A parent must come before its child for the forward pass: process in Pinocchio's order.
    order = sorted(range(len(ordered)), key=lambda k: ordered[k].pin_index)
    return model, ordered, order


def rot_axis(axis, angle, lib):
    """Rodrigues: rotation by `angle` about the unit `axis` (numpy constant)."""
    c, s = lib.cos(angle), lib.sin(angle)
    x, y, z = axis
    C = 1 - c
    return [
        [c + x * x * C, x * y * C - z * s, x * z * C + y * s],
        [y * x * C + z * s, c + y * y * C, y * z * C - x * s],
        [z * x * C - y * s, z * y * C + x * s, c + z * z * C],
    ]


def rnea(bodies, order, q, qd, qdd, gravity, lib):
    """Inverse dynamics in each joint's frame (Featherstone, [angular; linear] split as 3-vectors).

    `lib` is casadi (symbolic; q etc. SX/MX column vectors) or numpy (floats). Returns the list of tau_i
    in our order, minus nothing (passive terms are added by the caller).
    """
    n = len(bodies)
    if lib is np:
        vec = lambda a: np.asarray(a, dtype=float)  # noqa: E731
        mat = lambda m: np.asarray(m, dtype=float)  # noqa: E731
        cross = np.cross
        dot = lambda A, v: A @ v  # noqa: E731
        tdot = lambda A, v: A.T @ v  # noqa: E731
        zero = np.zeros(3)
    else:
        vec = lambda a: ca.vertcat(*a) if isinstance(a, (list, tuple)) else a  # noqa: E731
        mat = lambda m: ca.vertcat(*[ca.horzcat(*r) for r in m])  # noqa: E731
        cross = ca.cross
        dot = lambda A, v: ca.mtimes(A, v)  # noqa: E731
        tdot = lambda A, v: ca.mtimes(A.T, v)  # noqa: E731
        zero = ca.DM.zeros(3, 1)
    g = np.asarray(gravity, dtype=float)
    R = [None] * n
    p = [None] * n
    w = [None] * n
    v = [None] * n
    al = [None] * n
    a = [None] * n
    fn = [None] * n
    ff = [None] * n
    for k in order:
        b = bodies[k]
        if b.revolute:
            RJ = rot_axis(b.axis, q[k], lib)
            R[k] = dot(b.R_T, mat(RJ))
            p[k] = vec(b.p_T) if lib is np else ca.DM(b.p_T)
        else:
            R[k] = b.R_T if lib is np else ca.DM(b.R_T)
            p[k] = (b.p_T + b.R_T @ b.axis * q[k]) if lib is np else ca.DM(b.p_T) + ca.DM(b.R_T @ b.axis) * q[k]
        if b.parent < 0:
            wp, vp, alp = zero, zero, zero
            ap = -g if lib is np else ca.DM(-g)
        else:
            wp, vp, alp, ap = w[b.parent], v[b.parent], al[b.parent], a[b.parent]
        # motion from parent coords to ours: w = R^T w_p, v = R^T (v_p + w_p x p)
        S = b.axis if lib is np else ca.DM(b.axis)
        wi = tdot(R[k], wp)
        vi = tdot(R[k], vp + cross(wp, p[k]))
        ali = tdot(R[k], alp)
        ai = tdot(R[k], ap + cross(alp, p[k]))
        # spatial cross products of the joint velocity: a += v x S qd
        if b.revolute:
            wJ = S * qd[k]
            ali_new = ali + S * qdd[k] + cross(wi, wJ)
            ai_new = ai + cross(vi, wJ)
            wi = wi + wJ
        else:
            vJ = S * qd[k]
            ali_new = ali
            ai_new = ai + S * qdd[k] + cross(wi, vJ)
            vi = vi + vJ
        w[k], v[k], al[k], a[k] = wi, vi, ali_new, ai_new
        # f = I a + v x* I v
        m, c = b.mass, (b.com if lib is np else ca.DM(b.com))
        Ic = b.I_c if lib is np else ca.DM(b.I_c)
        h_lin = m * (vi - cross(c, wi))
        h_ang = dot(Ic, wi) + cross(c, h_lin)
        Ia_lin = m * (ai_new - cross(c, ali_new))
        Ia_ang = dot(Ic, ali_new) + cross(c, Ia_lin)
        ff[k] = Ia_lin + cross(wi, h_lin)
        fn[k] = Ia_ang + cross(wi, h_ang) + cross(vi, h_lin)
    tau = [None] * n
    for k in reversed(order):
        b = bodies[k]
        S = b.axis if lib is np else ca.DM(b.axis)
        if b.revolute:
            tau[k] = (fn[k] @ S) if lib is np else ca.dot(fn[k], S)
        else:
            tau[k] = (ff[k] @ S) if lib is np else ca.dot(ff[k], S)
        if b.parent >= 0:
            f_par = dot(R[k], ff[k])
            n_par = dot(R[k], fn[k]) + cross(p[k], f_par)
            ff[b.parent] = ff[b.parent] + f_par
            fn[b.parent] = fn[b.parent] + n_par
    return tau


def check_rnea(model, bodies, order, gravity, rng):
    """Our RNEA (numpy path and CasADi path) against pinocchio.rnea at random states; max relative error."""
    pin_model = model.copy() if hasattr(model, "copy") else model
    pin_model.gravity = pin.Motion(np.array(gravity, dtype=float), np.zeros(3))
    data = pin_model.createData()
    n = len(bodies)
    qs, vs, As = ca.SX.sym("q", n), ca.SX.sym("v", n), ca.SX.sym("a", n)
    f = ca.Function("rnea", [qs, vs, As], [ca.vertcat(*rnea(bodies, order, qs, vs, As, gravity, ca))])
    worst = 0.0
    for _ in range(5):
        q = rng.uniform(-1.5, 1.5, n)
        v = rng.uniform(-2, 2, n)
        a = rng.uniform(-3, 3, n)
        # pinocchio order
        qp, vp, ap = np.zeros(n), np.zeros(n), np.zeros(n)
        for k, b in enumerate(bodies):
            j = pin_model.idx_qs[b.pin_index]
            qp[j], vp[j], ap[j] = q[k], v[k], a[k]
        tp = pin.rnea(pin_model, data, qp, vp, ap)
        ref = np.array([tp[pin_model.idx_vs[b.pin_index]] for b in bodies])
        ours = np.array(f(q, v, a)).ravel()
        ours_np = np.array(rnea(bodies, order, q, v, a, gravity, np), dtype=float)
        scale = 1.0 + np.max(np.abs(ref))
        worst = max(worst, np.max(np.abs(ours - ref)) / scale, np.max(np.abs(ours_np - ref)) / scale)
    return worst


# ---------------------------------------------------------------- the B-spline


class Spline:
    """Clamped uniform cubic B-spline, N control points on [0, T] (src/trajectory/bspline.rs)."""

    def __init__(self, n_ctrl, duration):
        self.N, self.T = n_ctrl, duration
        self.spans = n_ctrl - 3
        self.h = duration / self.spans
        self.knots = [0.0] * 3 + [duration * (k / self.spans) for k in range(self.spans + 1)] + [duration] * 3

    def span(self, t):
        last = self.spans - 1
        s = min(max(int(math.floor(t / self.h)), 0), last)
        if s > 0 and t < self.knots[s + 3]:
            s -= 1
        elif s < last and t >= self.knots[s + 4]:
            s += 1
        return s

    def basis_in_span(self, s, t):
        """(first, b[4], db[4], ddb[4]): the span's polynomial pieces by Cox-de Boor on span s."""
        U = self.knots

        def B(j, p, d):
            # d-th derivative of B_{j,p} at t, restricted to span s (indicator of span s at degree 0)
            if p == 0:
                return (1.0 if j == s + 3 else 0.0) if d == 0 else 0.0
            if d == 0:
                left = (t - U[j]) / (U[j + p] - U[j]) * B(j, p - 1, 0) if U[j + p] > U[j] else 0.0
                right = (U[j + p + 1] - t) / (U[j + p + 1] - U[j + 1]) * B(j + 1, p - 1, 0) if U[j + p + 1] > U[j + 1] else 0.0
                return left + right
            left = p / (U[j + p] - U[j]) * B(j, p - 1, d - 1) if U[j + p] > U[j] else 0.0
            right = p / (U[j + p + 1] - U[j + 1]) * B(j + 1, p - 1, d - 1) if U[j + p + 1] > U[j + 1] else 0.0
            return left - right

        return s, [B(s + a, 3, 0) for a in range(4)], [B(s + a, 3, 1) for a in range(4)], [B(s + a, 3, 2) for a in range(4)]

    def basis(self, t):
        t = min(max(t, 0.0), self.T)
        return self.basis_in_span(self.span(t), t)

    def nodes(self, per_span):
        """Gauss-Legendre nodes per span plus both ends (weight 0), as mintorque's Transcription::new."""
        x, wx = np.polynomial.legendre.leggauss(per_span)
        ts, ws, bs = [0.0], [0.0], [self.basis(0.0)]
        for s in range(self.spans):
            a, b = self.knots[s + 3], self.knots[s + 4]
            half, mid = 0.5 * (b - a), 0.5 * (a + b)
            for xk, wk in zip(x, wx):
                t = mid + half * xk
                ts.append(t)
                ws.append(half * wk)
                bs.append(self.basis_in_span(s, t))
        ts.append(self.T)
        ws.append(0.0)
        bs.append(self.basis(self.T))
        return ts, ws, bs

    def greville(self):
        return [(self.knots[j + 1] + self.knots[j + 2] + self.knots[j + 3]) / 3.0 for j in range(self.N)]

    def linear_guess(self, q0, qt):
        c = [q0 + (qt - q0) * tau / self.T for tau in self.greville()]
        c[1] = q0
        c[self.N - 2] = qt
        return c


# ---------------------------------------------------------------- the problem


def build(bodies, order, spline, per_span, gravity, weights, position_limits, torque_limits, c_fixed):
    """The NLP in CasADi: x = free control points (control points 2 .. N-3 of every joint, joint-fastest).

    Returns the plain NLP (x, f, g, bounds) and exact derivative functions assembled node by node: each
    Gauss node touches 4 control points per joint, so its torque Jacobian (n x 4n) and its block of the
    Lagrangian Hessian (4n x 4n) come from CasADi's AD of one SX node function, mapped over the nodes and
    scattered into the banded global matrices by constant 0/1 matrices. (Letting nlpsol differentiate the
    mapped MX graph itself gives the same numbers but is 30x slower; `expand` runs out of memory beyond
    13 DOF.)
    """
    n = len(bodies)
    N = spline.N
    ts, ws, bs = spline.nodes(per_span)
    K = len(ts)
    nfree = N - 4
    nx = n * nfree
    x = ca.MX.sym("x", nx)
    X = ca.reshape(x, n, nfree)  # column j = control point j+2
    Cfull = ca.horzcat(ca.DM(c_fixed[:, 0:2]), X, ca.DM(c_fixed[:, N - 2:N]))
    # ---- per-node SX functions of C (n x 4 local control points) and basis B (4 x 3: b, db, ddb)
    Cs = ca.SX.sym("C", n, 4)
    Bs = ca.SX.sym("B", 4, 3)
    cvec = ca.vec(Cs)  # column-major: entry a*n + i = joint i of control point first+a
    q, qd, qdd = ca.mtimes(Cs, Bs[:, 0]), ca.mtimes(Cs, Bs[:, 1]), ca.mtimes(Cs, Bs[:, 2])
    tau = rnea(bodies, order, q, qd, qdd, gravity, ca)
    tau = ca.vertcat(*[tau[k] + b.stiffness * (q[k] - b.rest) + b.damping * qd[k] for k, b in enumerate(bodies)])
    Wd = ca.DM(np.array(weights, dtype=float))
    ws_sym = ca.SX.sym("w")
    mu = ca.SX.sym("mu", n)
    phi = 0.5 * ca.dot(Wd * tau, tau)  # 1/2 tau^T W tau at the node
    J = ca.jacobian(tau, cvec)  # n x 4n
    node_fn = ca.Function("node", [Cs, Bs, ws_sym], [tau, ca.densify(J), ca.densify(ws_sym * ca.gradient(phi, cvec))])
    lag = ws_sym * phi + ca.dot(mu, tau)
    Hn = ca.densify(ca.hessian(lag, cvec)[0])
    hess_fn = ca.Function("node_hess", [Cs, Bs, ws_sym, mu], [Hn])
    node_map = node_fn.map(K, "serial")
    hess_map = hess_fn.map(K, "serial")
    # ---- gathering and scattering
    cols = []
    for (s, _, _, _) in bs:
        cols.extend(range(s, s + 4))
    Bstack = ca.DM(np.hstack([np.array([b, db, ddb]).T for (_, b, db, ddb) in bs]))
    wrow = ca.DM(np.array(ws)).T  # 1 x K

    def glob(j, i):
        return (j - 2) * n + i if 2 <= j <= N - 3 else None

    P = []  # P_k: 4n x nx selection of the node's free unknowns
    for (s, _, _, _) in bs:
        r, c_ = [], []
        for a in range(4):
            for i in range(n):
                gidx = glob(s + a, i)
                if gidx is not None:
                    r.append(a * n + i)
                    c_.append(gidx)
        P.append(ca.DM(ca.Sparsity.triplet(4 * n, nx, r, c_), 1.0))
    Pcat = ca.horzcat(*[Pk.T for Pk in P])  # nx x 4nK

    def node_values(xv):
        Cf = ca.horzcat(ca.DM(c_fixed[:, 0:2]), ca.reshape(xv, n, nfree), ca.DM(c_fixed[:, N - 2:N]))
        return Cf[:, cols]

    # ---- constraints: position rows (linear in x) then torque rows (joint-major, node-fastest)
    pos_rows, lbg, ubg = [], [], []
    pos_r, pos_c, pos_v = [], [], []
    if position_limits:
        # q at the nodes; the two end nodes are the fixed postures (checked by mintorque): skipped.
        for kk in range(1, K - 1):
            s, b, _, _ = bs[kk]
            for i, body in enumerate(bodies):
                if math.isfinite(body.lower) or math.isfinite(body.upper):
                    row = len(pos_rows)
                    pos_rows.append((kk, i))
                    lbg.append(body.lower if math.isfinite(body.lower) else -ca.inf)
                    ubg.append(body.upper if math.isfinite(body.upper) else ca.inf)
                    for a in range(4):
                        gidx = glob(s + a, i)
                        if gidx is not None:
                            pos_r.append(row)
                            pos_c.append(gidx)
                            pos_v.append(b[a])
    npos = len(pos_rows)
    Jpos = ca.DM.triplet(pos_r, pos_c, ca.DM(pos_v), npos, nx) if npos else ca.DM(0, nx)
    tq = [i for i, body in enumerate(bodies) if torque_limits and math.isfinite(body.effort)]
    for i in tq:
        lbg.extend([-bodies[i].effort] * K)
        ubg.extend([bodies[i].effort] * K)
    ntq = len(tq) * K
    # constant parts of q at the nodes (fixed control points) for the position rows
    q_const = np.zeros(npos)
    for row, (kk, i) in enumerate(pos_rows):
        s, b, _, _ = bs[kk]
        q_const[row] = sum(b[a] * c_fixed[i, s + a] for a in range(4) if glob(s + a, i) is None)
    Sel = []  # Sel_k: ntq x n, torque row of (joint i, node k) <- tau_i at node k
    for k in range(K):
        r = [m * K + k for m in range(len(tq))]
        Sel.append(ca.DM(ca.Sparsity.triplet(ntq, n, r, tq), 1.0))

    def evaluate(xv, with_jac):
        taus, Js, Gs = node_map(node_values(xv), Bstack, wrow)
        F = 0.5 * ca.sum2(wrow * ca.sum1(ca.repmat(Wd, 1, K) * taus**2))
        gq = ca.mtimes(Jpos, xv) + ca.DM(q_const) if npos else ca.MX(0, 1)
        gt = ca.vec(taus[tq, :].T) if tq else ca.MX(0, 1)
        g = ca.vertcat(gq, gt)
        if not with_jac:
            return F, g
        grad = ca.mtimes(Pcat, ca.vec(Gs))
        Jt = None
        for k in range(K):
            term = ca.mtimes(Sel[k], ca.mtimes(Js[:, k * 4 * n:(k + 1) * 4 * n], P[k])) if tq else None
            Jt = term if Jt is None else Jt + term
        jac = ca.vertcat(Jpos, Jt) if tq else ca.MX(Jpos)
        return F, g, grad, jac

    F, g = evaluate(x, False)
    p = ca.MX.sym("p", 0)
    _, _, grad, jac = evaluate(x, True)
    grad_f = ca.Function("grad_f", [x, p], [F, grad], ["x", "p"], ["f", "grad_f_x"])
    jac_g = ca.Function("jac_g", [x, p], [g, jac], ["x", "p"], ["g", "jac_g_x"])
    lam_f = ca.MX.sym("lam_f")
    lam_g = ca.MX.sym("lam_g", npos + ntq)
    mu_rows = []
    for i in range(n):
        if i in tq:
            m = tq.index(i)
            mu_rows.append(lam_g[npos + m * K:npos + (m + 1) * K].T)
        else:
            mu_rows.append(ca.MX.zeros(1, K))
    mu_mat = ca.vertcat(*mu_rows)
    Hs = hess_map(node_values(x), Bstack, lam_f * wrow, mu_mat)
    H = None
    for k in range(K):
        term = ca.mtimes(P[k].T, ca.mtimes(Hs[:, k * 4 * n:(k + 1) * 4 * n], P[k]))
        H = term if H is None else H + term
    hess_lag = ca.Function("hess_lag", [x, p, lam_f, lam_g], [ca.triu(H)],
                           ["x", "p", "lam_f", "lam_g"], ["triu_hess_gamma_x_x"])
    return dict(x=x, F=F, g=g, lbg=np.array(lbg), ubg=np.array(ubg), grad_f=grad_f, jac_g=jac_g,
                hess_lag=hess_lag, nodes=(ts, ws, bs))


def objective_numpy(bodies, order, spline, nodes, gravity, weights, ctrl):
    """F = 1/2 sum_k w_k tau^T W tau in plain floats (numpy RNEA), ctrl = N x n."""
    ts, ws, bs = nodes
    total = 0.0
    for (s, b, db, ddb), w in zip(bs, ws):
        C = ctrl[s:s + 4, :]
        q, qd, qdd = np.array(b) @ C, np.array(db) @ C, np.array(ddb) @ C
        tau = np.array(rnea(bodies, order, q, qd, qdd, gravity, np), dtype=float)
        for k, body in enumerate(bodies):
            tau[k] += body.stiffness * (q[k] - body.rest) + body.damping * qd[k]
        total += w * float(np.sum(np.array(weights) * tau * tau))
    return 0.5 * total


def rel(a, b):
    return abs(a - b) / max(abs(b), 1e-300)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("plan_dir", help="a directory written by `mintorque plan TASK --out DIR`")
    ap.add_argument("--mintorque", default=None, help="binary used to write DIR/model.urdf if it is missing")
    ap.add_argument("--tol", type=float, default=1e-8, help="IPOPT tol (default 1e-8)")
    ap.add_argument("--max-iter", type=int, default=3000)
    ap.add_argument("--casadi-derivatives", action="store_true",
                    help="let nlpsol differentiate the whole MX graph (slow) instead of the node-wise derivatives")
    ap.add_argument("--check-derivatives", action="store_true",
                    help="compare the node-wise derivatives with nlpsol's own AD at the start (slow for big models)")
    ap.add_argument("--check-tol", type=float, default=1e-9, help="relative tolerance of the sameness checks")
    ap.add_argument("--print-level", type=int, default=0)
    args = ap.parse_args()
    d = Path(args.plan_dir)
    plan = json.loads((d / "plan.json").read_text())
    summary = json.loads((d / "summary.json").read_text())
    task = tomllib.loads((d / "task.resolved.toml").read_text())
    urdf = d / "model.urdf"
    if not urdf.exists():
        if not args.mintorque:
            raise SystemExit(f"{urdf} missing: pass --mintorque BIN to write it from model.figure.toml")
        subprocess.run([args.mintorque, "figure", str(d / "model.figure.toml"), "--out", str(urdf)], check=True,
                       stdout=subprocess.DEVNULL)
    # Features this peer does not transcribe: refuse rather than solve another problem.
    c = task.get("constraints", {})
    unsupported = unsupported_features(task)
    if unsupported:
        raise SystemExit(f"unsupported by the peer transcription: {', '.join(unsupported)}")

    names = plan["joint_names"]
    n = len(names)
    N = plan["n_ctrl"]
    T = plan["duration"]
    gravity = plan["gravity"]
    per_span = summary["quadrature"]["nodes_per_span"]
    ctrl_ours = np.array(plan["ctrl"], dtype=float).reshape(N, n)
    wmap = task.get("objective", {}).get("weights", {}) or {}
    weights = [float(wmap.get(nm, 1.0)) for nm in names]
    position_limits = c.get("position_limits", True)
    torque_limits = c.get("torque_limits", True)

    model, bodies, order = load_model(urdf, names)
    rnea_err = check_rnea(model, bodies, order, gravity, np.random.default_rng(1))
    spline = Spline(N, T)
    # Fixed control points: bit-exactly mintorque's (c0 = c1 = q(0), c_{N-2} = c_{N-1} = q(T)).
    c_fixed = ctrl_ours.T.copy()  # n x N; only columns 0, 1, N-2, N-1 are used as constants
    q0, qT = ctrl_ours[0], ctrl_ours[N - 1]
    guess_ctrl = np.array([spline.linear_guess(q0[i], qT[i]) for i in range(n)]).T  # N x n

    t_build0 = time.perf_counter()
    nlp = build(bodies, order, spline, per_span, gravity, weights, position_limits, torque_limits, c_fixed)
    x, F, g, lbg, ubg, nodes = nlp["x"], nlp["F"], nlp["g"], nlp["lbg"], nlp["ubg"], nlp["nodes"]
    opts = {
        "ipopt.hessian_approximation": "exact",
        "ipopt.tol": args.tol,
        "ipopt.max_iter": args.max_iter,
        "ipopt.print_level": args.print_level,
        "ipopt.sb": "yes",
        "print_time": False,
    }
    if not args.casadi_derivatives:
        opts.update({"grad_f": nlp["grad_f"], "jac_g": nlp["jac_g"], "hess_lag": nlp["hess_lag"]})
    solver = ca.nlpsol("ipopt", "ipopt", {"x": x, "f": F, "g": g}, opts)
    fF = ca.Function("F", [x], [F])
    build_s = time.perf_counter() - t_build0

    def to_x(ctrl):  # N x n -> x (free control points, joint-major within each control point column)
        return ctrl[2:N - 2, :].reshape(-1)  # row j (ctrl j+2) -> n entries: matches reshape(x, n, nfree)

    # --- sameness checks
    F_ours_eval = float(fF(to_x(ctrl_ours)))
    F_ours_np = objective_numpy(bodies, order, spline, nodes, gravity, weights, ctrl_ours)
    F_guess_eval = float(fF(to_x(guess_ctrl)))
    checks = {
        "rnea_vs_pinocchio": rnea_err,
        "F_at_our_plan_rel": rel(F_ours_eval, summary["objective"]),
        "F_at_our_plan_numpy_rel": rel(F_ours_np, summary["objective"]),
        "F_at_guess_rel": rel(F_guess_eval, summary["initial_guess_objective"]),
    }
    if args.check_derivatives:
        # the node-wise derivatives against CasADi's AD of the whole MX graph, at the start, random multipliers
        x0 = to_x(guess_ctrl)
        rng = np.random.default_rng(2)
        lg = rng.normal(size=g.shape[0])
        lf = ca.MX.sym("lf")
        lgs = ca.MX.sym("lg", g.shape[0])
        ref = ca.Function("ref", [x, lf, lgs], [ca.gradient(F, x), ca.jacobian(g, x),
                                                ca.triu(ca.hessian(lf * F + ca.dot(lgs, g), x)[0])])
        gr, jr, hr = [np.array(ca.densify(v)) for v in ref(x0, 0.7, lg)]
        go = np.array(nlp["grad_f"](x0, [])[1])
        jo = np.array(ca.densify(nlp["jac_g"](x0, [])[1]))
        ho = np.array(ca.densify(nlp["hess_lag"](x0, [], 0.7, lg)))
        err = lambda a, b: float(np.max(np.abs(a - b)) / (1.0 + np.max(np.abs(b)))) if b.size else 0.0  # noqa: E731
        checks["derivatives_vs_casadi_ad"] = max(err(go, gr), err(jo, jr), err(ho, hr))
    ok = (rnea_err < 1e-10 and checks.get("derivatives_vs_casadi_ad", 0.0) < 1e-10 and checks["F_at_our_plan_rel"] < args.check_tol
          and checks["F_at_our_plan_numpy_rel"] < args.check_tol and checks["F_at_guess_rel"] < args.check_tol)

    # --- solve from the same start
    t0 = time.perf_counter()
    sol = solver(x0=to_x(guess_ctrl), lbg=lbg, ubg=ubg)
    solve_s = time.perf_counter() - t0
    st = solver.stats()
    xs = np.array(sol["x"]).ravel()
    gs = np.array(sol["g"]).ravel()
    viol = 0.0
    if gs.size:
        viol = float(max(np.max(lbg - gs), np.max(gs - ubg), 0.0))
    out = {
        "task_dir": str(d),
        "dof": n,
        "n_ctrl": N,
        "nodes": len(nodes[0]),
        "nodes_per_span": per_span,
        "F_ipopt": float(sol["f"]),
        "F_ours_reported": summary["objective"],
        "F_ours_evaluated": F_ours_eval,
        "F_guess": F_guess_eval,
        "ipopt_status": st.get("return_status"),
        "ipopt_success": bool(st.get("success")),
        "ipopt_iterations": int(st.get("iter_count", -1)),
        "ipopt_solve_s": solve_s,
        "ipopt_build_s": build_s,
        "ipopt_max_violation": viol,
        "ipopt_t_wall_nlp_f_grad_hess_s": {k: st.get(k) for k in ("t_wall_nlp_f", "t_wall_nlp_grad_f",
                                                                  "t_wall_nlp_hess_l", "t_wall_nlp_jac_g")},
        "process_s_before_exit": time.perf_counter() - T_START,
        "checks": checks,
        "checks_ok": ok,
        "x_ipopt_ctrl": np.vstack([ctrl_ours[:2], xs.reshape(N - 4, n), ctrl_ours[N - 2:]]).tolist(),
    }
    print(json.dumps(out))
    if not ok:
        print(f"SAMENESS CHECK FAILED for {d}: {checks}", file=sys.stderr)
        sys.exit(2)


if __name__ == "__main__":
    main()

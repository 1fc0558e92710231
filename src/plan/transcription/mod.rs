//! The B-spline transcription (paper section 5.3, eq. 30–33): the motion planning problem of eq. 12–13
//! becomes a finite problem over the control points, in the least-squares form the solvers take:
//!
//! ```text
//! minimise ½ Σₖ wₖ τₐ(tₖ)ᵀ W τₐ(tₖ) ≈ ½ ∫ τₐᵀ W τₐ dt          (Gauss–Legendre nodes tₖ, weights wₖ)
//! τₐ = H q̈ + Q(q, q̇) − Σ_c J_cᵀ λ_c − Σ Jᵀ f_load − τ_passive(q, q̇)     (eq. 12, active torque)
//! subject to  Φ(q(tₖ)) = 0                                         (contacts / loop closure, eq. 13)
//!             q_low ≤ q(tₖ) ≤ q_up,  |τₐ(tₖ)| ≤ τ_max               (eq. 12)
//!             n·λ(tₖ) ≥ 0, friction pyramid, centre of pressure in the support rectangle
//! ```
//!
//! Unknowns `x`, control-point-major so that every Jacobian is banded: for control point `j`, the values
//! of the free joints (none for the end control points the end conditions fix: at rest `c₀ = c₁ = q₀`,
//! `c_{N−2} = c_{N−1} = q_T` make `q(0), q̇(0), q(T), q̇(T)` exact, holding `c₂`, `c_{N−3}` too; with a
//! task-space goal at the end the tied last ones share one unknown posture, `Layout::owner`), then the control points of the
//! contact forces `λ(t)` (cubic B-splines on the same knots, so the loads on the hands are smooth and
//! defined at every time). Gradients follow eq. 33 from the engine's `∂τ/∂q`, `∂τ/∂q̇` and `H`, touching
//! only the four non-zero basis functions at each node.

pub(crate) mod collision;
mod constraints;
pub mod goals;
mod hessian;
mod measure;
mod objective;
mod terms;

use super::spec::{Objective, Spec};
use crate::dynamics::point_force::{add_generalized_force, generalized_force_derivative, path_dofs, point_jacobian};
use crate::dynamics::{kinematics, rnea::rnea, rnea_derivatives::rnea_derivatives, Data};
use crate::solve::{ConstraintKind, Dims, Evaluation, Patterns, Problem, RowFamily, Scales, SymmetricMatrix};
use crate::spatial::{Force, Vec3};
use crate::trajectory::bspline::{BasisAt, CubicBSpline, Nodes};
pub use constraints::IneqRow;
pub use measure::{Measured, RowKind};
pub use terms::Terms;

/// Where each control point's unknowns sit in `x`.
#[derive(Clone, Debug)]
pub struct Layout {
    /// Degrees of freedom.
    pub nv: usize,
    /// Control points per joint, N.
    pub n_ctrl: usize,
    /// Contact-force components per control point.
    pub n_lambda: usize,
    /// Control points whose joint values are fixed by the boundary conditions.
    pub fixed: Vec<bool>,
    /// The control point whose unknowns each control point's joint values are: itself, or — for the last
    /// control points of a goal posture left to the planner, tied by the goal's end condition — the first of
    /// them (`c_{N−2} = c_{N−1}` at rest, `c_{N−3} = c_{N−2} = c_{N−1}` holding: one unknown posture).
    pub owner: Vec<usize>,
    /// Index in `x` of each control point's first unknown.
    pub block_start: Vec<usize>,
    /// Number of unknowns.
    pub n: usize,
    /// Contact forces are stored as `λ / lambda_scale` (the figure's weight, N) so that every unknown is of
    /// order one — Levenberg–Marquardt's damping then treats radians and newtons alike.
    pub lambda_scale: f64,
}

impl Layout {
    /// The layout of `n_ctrl` control points of `nv` joints and `n_lambda` contact-force components; the
    /// first `head` and the last `tail` joint control points are fixed (by the end conditions:
    /// [`EndCondition::tied`](super::spec::EndCondition::tied)), and the last `shared` share one posture's
    /// unknowns (a task-space goal: `tail = 0`, `shared` the goal's `tied`).
    pub fn new(nv: usize, n_ctrl: usize, n_lambda: usize, [head, tail]: [usize; 2], shared: usize, lambda_scale: f64) -> Layout {
        let fixed: Vec<bool> = (0..n_ctrl).map(|j| j < head || j + tail >= n_ctrl).collect();
        let first_shared = n_ctrl - shared.max(1);
        let owner: Vec<usize> = (0..n_ctrl).map(|j| j.min(first_shared)).collect();
        let mut block_start = Vec::with_capacity(n_ctrl);
        let mut n = 0;
        for j in 0..n_ctrl {
            block_start.push(n);
            n += if !fixed[j] && owner[j] == j { nv } else { 0 } + n_lambda;
        }
        Layout { nv, n_ctrl, n_lambda, fixed, owner, block_start, n, lambda_scale }
    }

    /// Whether control point `j` holds joint unknowns of its own (neither fixed nor sharing another's).
    pub fn owns(&self, j: usize) -> bool {
        !self.fixed[j] && self.owner[j] == j
    }

    /// Index in `x` of joint `i` at control point `j`, `None` when it is fixed.
    pub fn joint_var(&self, j: usize, i: usize) -> Option<usize> {
        let o = self.owner[j];
        (!self.fixed[o]).then(|| self.block_start[o] + i)
    }

    /// For the node whose four basis functions start at control point `first`: which block of `nv` motion
    /// columns each of the four control points' unknowns are (its owner's for a shared one), `None` if fixed.
    pub fn motion_slots(&self, first: usize) -> [Option<usize>; 4] {
        let mut slots = [None; 4];
        let mut next = 0;
        for a in 0..4 {
            let j = first + a;
            if self.owns(j) {
                slots[a] = Some(next);
                next += 1;
            } else if !self.fixed[j] {
                slots[a] = slots[self.owner[j] - first]; // the owner precedes it in the same window
            }
        }
        slots
    }

    /// Index in `x` of contact-force component `m` at control point `j`.
    pub fn lambda_var(&self, j: usize, m: usize) -> usize {
        self.block_start[j] + if self.owns(j) { self.nv } else { 0 } + m
    }

    /// Splits `x` into joint control points (`n_ctrl × nv`, fixed ones taken from `fixed_values`) and
    /// contact-force control points (`n_ctrl × n_lambda`).
    pub fn unpack(&self, x: &[f64], fixed_values: &[f64], ctrl: &mut [f64], lambda: &mut [f64]) {
        for j in 0..self.n_ctrl {
            for i in 0..self.nv {
                ctrl[j * self.nv + i] = match self.joint_var(j, i) {
                    Some(v) => x[v],
                    None => fixed_values[j * self.nv + i],
                };
            }
            for m in 0..self.n_lambda {
                lambda[j * self.n_lambda + m] = x[self.lambda_var(j, m)] * self.lambda_scale;
            }
        }
    }

    /// The inverse of [`Layout::unpack`].
    pub fn pack(&self, ctrl: &[f64], lambda: &[f64]) -> Vec<f64> {
        let mut x = vec![0.0; self.n];
        for j in 0..self.n_ctrl {
            for i in 0..self.nv {
                if let Some(v) = self.joint_var(j, i) {
                    x[v] = ctrl[j * self.nv + i];
                }
            }
            for m in 0..self.n_lambda {
                x[self.lambda_var(j, m)] = lambda[j * self.n_lambda + m] / self.lambda_scale;
            }
        }
        x
    }
}

/// A row's derivatives with respect to a node's `q`, `q̇`, `q̈` (each `nv`) and contact forces `λ̃`.
struct Derivatives<'a> {
    q: &'a [f64],
    v: &'a [f64],
    a: &'a [f64],
    lambda: Option<&'a [f64]>,
}

impl NodeWork {
    /// The objective's residual and its derivatives times `s`.
    fn scale_residual(&mut self, s: f64) {
        for v in [&mut self.res, &mut self.rdq, &mut self.rdv, &mut self.rda, &mut self.rdl] {
            v.iter_mut().for_each(|x| *x *= s);
        }
    }

    /// The derivatives of the objective's residual `l` at this node.
    fn residual_row(&self, l: usize, nv: usize, nl: usize) -> Derivatives<'_> {
        Derivatives {
            q: &self.rdq[l * nv..(l + 1) * nv],
            v: &self.rdv[l * nv..(l + 1) * nv],
            a: &self.rda[l * nv..(l + 1) * nv],
            lambda: (nl > 0).then(|| &self.rdl[l * nl..(l + 1) * nl]),
        }
    }

    /// The derivatives of active torque `l` at this node.
    fn torque_row(&self, l: usize, nv: usize, nl: usize) -> Derivatives<'_> {
        Derivatives {
            q: &self.dq[l * nv..(l + 1) * nv],
            v: &self.dv[l * nv..(l + 1) * nv],
            a: &self.da[l * nv..(l + 1) * nv],
            lambda: (nl > 0).then(|| &self.dl[l * nl..(l + 1) * nl]),
        }
    }
}

/// Per-contact data fixed for the whole solve.
struct ContactInfo {
    path: Vec<usize>,
    directions: Vec<Vec3>,
    /// Offset of this contact's components in a control point's λ block.
    offset: usize,
    tangents: (Vec3, Vec3),
}

/// The planning problem transcribed: the motion as cubic B-splines, the objective and the
/// constraints evaluated at Gauss–Legendre nodes — what the solvers see as a [`crate::solve::Problem`].
pub struct Transcription<'s> {
    /// The problem transcribed.
    pub spec: &'s Spec,
    /// The B-spline of every joint (and contact force).
    pub spline: CubicBSpline,
    /// The quadrature nodes of the objective and the inequality constraints.
    pub nodes: Nodes,
    /// Where the contacts (loop closures) are imposed: the interior knots and the end spans' midpoints. Imposing them
    /// at every quadrature node would ask more of a cubic spline than it has freedom for (a curved closure
    /// manifold cannot be followed exactly); between these points the drift is measured and reported.
    pub contact_nodes: Nodes,
    /// Where the unknowns sit in `x`.
    pub layout: Layout,
    /// Joint control points fixed by the boundary conditions (`n_ctrl × nv`; free entries unused).
    pub fixed_values: Vec<f64>,
    /// The inequality rows, in order, at each node.
    pub ineq_rows: Vec<IneqRow>,
    contacts: Vec<ContactInfo>,
    load_paths: Vec<Vec<usize>>,
    n_eq_node: usize,
    /// The objective's terms' rows and scratch.
    terms: terms::TermWork,
    limits_low: Vec<f64>,
    limits_up: Vec<f64>,
    /// Effort limits along `+axis` and `−axis` (magnitudes) per joint.
    effort: [Vec<f64>; 2],
    total_weight: f64,
    collisions: collision::Collisions,
    // scratch, allocated once
    data: Data,
    ctrl: Vec<f64>,
    lam_ctrl: Vec<f64>,
    work: NodeWork,
    hess: hessian::HessianWork,
    goals: goals::Goals,
}

/// Per-node values and derivatives with respect to the node's `q`, `q̇`, `q̈` and `λ̃`.
struct NodeWork {
    q: Vec<f64>,
    qd: Vec<f64>,
    qdd: Vec<f64>,
    lambda: Vec<f64>,
    tau: Vec<f64>,
    /// Row-major `nv × nv`.
    dq: Vec<f64>,
    dv: Vec<f64>,
    da: Vec<f64>,
    /// Row-major `nv × n_lambda`.
    dl: Vec<f64>,
    /// Root reaction wrench and its derivatives (6 per column).
    w: Force,
    w_dq: Vec<Force>,
    w_dv: Vec<Force>,
    w_da: Vec<Force>,
    w_dl: Vec<Force>,
    /// Contact points (world) and point Jacobians along their paths.
    points: Vec<Vec3>,
    jac: Vec<Vec<Vec3>>,
    scratch: Vec<f64>,
    row: Vec<f64>,
    /// The objective's residual at this node (`√W τ`, or `L⁻¹τ` with `H = LLᵀ`) and its derivatives.
    res: Vec<f64>,
    rdq: Vec<f64>,
    rdv: Vec<f64>,
    rda: Vec<f64>,
    rdl: Vec<f64>,
}

impl<'s> Transcription<'s> {
    /// The transcription on the spec's quadrature nodes.
    pub fn new(spec: &'s Spec) -> crate::Result<Self> {
        let spline = CubicBSpline::new(spec.n_ctrl, spec.duration)?;
        // The Gauss–Legendre nodes, plus both ends with weight 0: they add nothing to the objective but put
        // the limits where they often bind hardest — the start and goal postures, holding still.
        let mut nodes = spline.quadrature_nodes(spec.nodes_per_span)?;
        let ends = spline.grid(&[0.0, spline.duration()])?;
        nodes.t.insert(0, ends.t[0]);
        nodes.w.insert(0, 0.0);
        nodes.basis.insert(0, ends.basis[0]);
        nodes.t.push(ends.t[1]);
        nodes.w.push(0.0);
        nodes.basis.push(ends.basis[1]);
        let h = spline.knot_spacing();
        // Interior knots, plus the middle of the two end spans, where the fixed end conditions leave the
        // spline least freedom to follow the loop.
        let n = spline.n_spans();
        let mut times: Vec<f64> = (1..n).map(|k| k as f64 * h).collect();
        times.insert(0, h / 2.0);
        times.push(spline.duration() - h / 2.0);
        let mut contact_nodes = spline.grid(&times)?;
        // The refinement's check nodes come last, so that the other rows keep their indices.
        let ordered = nodes.t.len();
        append(&mut nodes, spline.grid(&spec.check_nodes.limits)?);
        append(&mut contact_nodes, spline.grid(&spec.check_nodes.closures)?);
        let mut t = Self::with_nodes(spec, spline, nodes, contact_nodes);
        // The ends and the Gauss nodes are in time order: the torque-change rows join them.
        t.terms = terms::TermWork::new(&t, ordered);
        Ok(t)
    }

    /// Joint `i`'s effort limit along `+axis` (`upper`) or `−axis`, a magnitude (N·m or N).
    pub fn torque_bound(&self, i: usize, upper: bool) -> f64 {
        self.effort[usize::from(!upper)][i]
    }

    /// Equality rows per contact node (the contact-force components).
    pub fn n_eq_per_node(&self) -> usize {
        self.n_eq_node
    }

    /// The problem evaluated at the times `times` (s) instead of its quadrature nodes — every row, contacts
    /// included, at every time (weights 0): for sampling a plan and checking it between the nodes.
    pub fn on_grid(spec: &'s Spec, times: &[f64]) -> crate::Result<Self> {
        let spline = CubicBSpline::new(spec.n_ctrl, spec.duration)?;
        let nodes = spline.grid(times)?;
        Ok(Self::with_nodes(spec, spline, nodes.clone(), nodes))
    }

    /// The same problem evaluated at other nodes (a dense grid to check constraints between nodes).
    pub fn with_nodes(spec: &'s Spec, spline: CubicBSpline, nodes: Nodes, contact_nodes: Nodes) -> Self {
        let model = &spec.model;
        let nv = model.nv();
        let mut contacts = Vec::new();
        let mut offset = 0;
        for c in &spec.contacts {
            let directions = c.directions();
            let normal = c.push_normal.unwrap_or(Vec3::z());
            contacts.push(ContactInfo {
                path: path_dofs(model, model.frames[c.frame].body),
                offset,
                tangents: super::spec::perpendicular_pair(&normal),
                directions: directions.clone(),
            });
            offset += directions.len();
        }
        let n_lambda = offset;
        let total_weight = model.total_mass() * spec.gravity.norm().max(9.81);
        let head = spec.start_condition.tied();
        let (tail, shared) = if spec.goal_is_free() { (0, spec.goal_condition.tied()) } else { (spec.goal_condition.tied(), 0) };
        let layout = Layout::new(nv, spec.n_ctrl, n_lambda, [head, tail], shared, total_weight);
        // The tied control points equal the end posture: c₀ (= c₁ (= c₂)) = q₀, likewise at the goal.
        let mut fixed_values = vec![0.0; spec.n_ctrl * nv];
        for j in 0..spec.n_ctrl {
            let end = if j < head { &spec.start } else { &spec.goal };
            fixed_values[j * nv..(j + 1) * nv].copy_from_slice(end);
        }
        let (limits_low, limits_up): (Vec<f64>, Vec<f64>) = model.position_limits();
        let effort: [Vec<f64>; 2] =
            [true, false].map(|up| model.joints[1..].iter().map(|j| j.limits.effort_toward(up)).collect());
        let mut ineq_rows = Vec::new();
        if spec.position_limits {
            for i in 0..nv {
                if limits_up[i].is_finite() {
                    ineq_rows.push(IneqRow::UpperPosition(i));
                }
                if limits_low[i].is_finite() {
                    ineq_rows.push(IneqRow::LowerPosition(i));
                }
            }
        }
        if spec.torque_limits {
            for i in 0..nv {
                if effort[0][i].is_finite() {
                    ineq_rows.push(IneqRow::UpperTorque(i));
                }
                if effort[1][i].is_finite() {
                    ineq_rows.push(IneqRow::LowerTorque(i));
                }
            }
        }
        for (c, contact) in spec.contacts.iter().enumerate() {
            if contact.push_normal.is_some() {
                ineq_rows.push(IneqRow::Push(c));
                if contact.friction.is_some() {
                    for k in 0..4 {
                        ineq_rows.push(IneqRow::Friction(c, k));
                    }
                }
            }
        }
        if spec.balance.is_some() {
            for k in 0..5 {
                ineq_rows.push(IneqRow::Balance(k));
            }
        }
        let collisions = collision::Collisions::new(spec);
        ineq_rows.extend((0..collisions.pairs.len()).map(IneqRow::Collision));
        let load_paths = spec.loads.iter().map(|l| path_dofs(model, model.frames[l.frame].body)).collect();
        let work = NodeWork {
            q: vec![0.0; nv],
            qd: vec![0.0; nv],
            qdd: vec![0.0; nv],
            lambda: vec![0.0; n_lambda],
            tau: vec![0.0; nv],
            dq: vec![0.0; nv * nv],
            dv: vec![0.0; nv * nv],
            da: vec![0.0; nv * nv],
            dl: vec![0.0; nv * n_lambda],
            w: Force::ZERO,
            w_dq: vec![Force::ZERO; nv],
            w_dv: vec![Force::ZERO; nv],
            w_da: vec![Force::ZERO; nv],
            w_dl: vec![Force::ZERO; n_lambda],
            points: vec![Vec3::zeros(); spec.contacts.len()],
            jac: contacts.iter().map(|c: &ContactInfo| vec![Vec3::zeros(); c.path.len()]).collect(),
            scratch: vec![0.0; nv * nv],
            row: vec![0.0; 3 * nv + n_lambda],
            res: vec![0.0; nv],
            rdq: vec![0.0; nv * nv],
            rdv: vec![0.0; nv * nv],
            rda: vec![0.0; nv * nv],
            rdl: vec![0.0; nv * n_lambda],
        };
        let goals = goals::Goals::new(spec, &spline);
        let mut t = Transcription {
            n_eq_node: n_lambda,
            terms: terms::TermWork::default(),
            data: Data::new(model),
            ctrl: vec![0.0; spec.n_ctrl * nv],
            lam_ctrl: vec![0.0; spec.n_ctrl * n_lambda],
            spec,
            spline,
            nodes,
            contact_nodes,
            layout,
            fixed_values,
            ineq_rows,
            contacts,
            load_paths,
            limits_low,
            limits_up,
            effort,
            total_weight,
            collisions,
            work,
            hess: hessian::HessianWork::new(nv, n_lambda),
            goals,
        };
        t.terms = terms::TermWork::new(&t, 0);
        t
    }

    /// Degrees of freedom.
    pub fn nv(&self) -> usize {
        self.layout.nv
    }

    fn n_nodes(&self) -> usize {
        self.nodes.t.len()
    }

    /// Columns touched at a node by the motion (joint values of the four active control points) and by
    /// the contact forces (their λ control points): `(motion, lambda)`.
    fn node_columns(&self, basis: &BasisAt) -> (Vec<usize>, Vec<usize>) {
        let l = &self.layout;
        let mut motion = Vec::new();
        let mut lambda = Vec::new();
        for j in basis.first..basis.first + 4 {
            if l.owns(j) {
                motion.extend((0..l.nv).filter_map(|i| l.joint_var(j, i)));
            }
            lambda.extend((0..l.n_lambda).map(|m| l.lambda_var(j, m)));
        }
        (motion, lambda)
    }

    /// Evaluates everything at one node into `self.work` (derivatives when `jac`).
    fn eval_node(&mut self, k: usize, jac: bool) {
        self.node_state(k);
        self.eval_state(jac);
    }

    /// `q, q̇, q̈, λ` at node `k` into `self.work` (eq. 30–32).
    fn node_state(&mut self, k: usize) {
        let nv = self.layout.nv;
        let nl = self.layout.n_lambda;
        let basis = self.nodes.basis[k];
        let w = &mut self.work;
        basis.eval(&self.ctrl, nv, &mut w.q, &mut w.qd, &mut w.qdd);
        for m in 0..nl {
            w.lambda[m] = (0..4).map(|a| basis.b[a] * self.lam_ctrl[(basis.first + a) * nl + m]).sum();
        }
    }

    /// The dynamics at the state in `self.work`: active torques, root wrench, contact points, the
    /// objective's residual, and their derivatives when `jac`.
    fn eval_state(&mut self, jac: bool) {
        let spec = self.spec;
        let model = &spec.model;
        let nv = self.layout.nv;
        let nl = self.layout.n_lambda;
        let w = &mut self.work;
        let data = &mut self.data;
        if jac {
            rnea_derivatives(model, data, &w.q, &w.qd, &w.qdd, &spec.gravity, None);
            for r in 0..nv {
                for c in 0..nv {
                    w.dq[r * nv + c] = data.dtau_dq[(r, c)];
                    w.dv[r * nv + c] = data.dtau_dv[(r, c)];
                    w.da[r * nv + c] = data.M[(r, c)];
                }
            }
            w.w_dq.copy_from_slice(&data.dW_dq);
            w.w_dv.copy_from_slice(&data.dW_dv);
            w.w_da.copy_from_slice(&data.dW_da);
            w.dl.iter_mut().for_each(|x| *x = 0.0);
        } else {
            rnea(model, data, &w.q, &w.qd, &w.qdd, &spec.gravity, None);
        }
        w.tau.copy_from_slice(data.tau.as_slice());
        w.w = data.root_wrench;
        // Passive joint torques: the muscles supply τ − τ_passive.
        for i in 0..nv {
            let p = &model.joints[i + 1].passive;
            w.tau[i] -= p.torque(w.q[i], w.qd[i]);
            if jac {
                w.dq[i * nv + i] += p.stiffness;
                w.dv[i * nv + i] += p.damping;
            }
        }
        // Loads and contact forces: world-fixed forces at body points, τ −= Jᵀf, W −= [p×f; f].
        let world_force = |w: &mut NodeWork, data: &Data, path: &[usize], p: &Vec3, f: &Vec3, jac: bool| {
            add_generalized_force(data, path, p, &(-f), &mut w.tau);
            w.w -= Force::new(p.cross(f), *f);
            if jac {
                let m = path.len();
                generalized_force_derivative(data, path, p, f, &mut w.scratch[..m * m]);
                for (r, &kr) in path.iter().enumerate() {
                    for (c, &kc) in path.iter().enumerate() {
                        w.dq[kr * nv + kc] -= w.scratch[r * m + c];
                    }
                }
                for &kc in path {
                    let s = &data.S[kc + 1];
                    let p_dot = s.w.cross(p) + s.v;
                    w.w_dq[kc] -= Force::new(p_dot.cross(f), Vec3::zeros());
                }
            }
        };
        for (l, load) in spec.loads.iter().enumerate() {
            let p = kinematics::frame_placement(model, data, load.frame).translation;
            world_force(w, data, &self.load_paths[l], &p, &load.force, jac);
        }
        for (c, contact) in spec.contacts.iter().enumerate() {
            let info = &self.contacts[c];
            let p = kinematics::frame_placement(model, data, contact.frame).translation;
            w.points[c] = p;
            let mut f = Vec3::zeros();
            for (m, e) in info.directions.iter().enumerate() {
                f += e * w.lambda[info.offset + m];
            }
            world_force(w, data, &info.path, &p, &f, jac);
            if jac {
                point_jacobian(data, &info.path, &p, &mut w.jac[c]);
                for (m, e) in info.directions.iter().enumerate() {
                    // ∂τ/∂λ̃ = −Jᵀe, ∂W/∂λ̃ = −[p×e; e]
                    let fe = Force::new(p.cross(e), *e);
                    for &kk in &info.path {
                        w.dl[kk * nl + info.offset + m] = -data.S[kk + 1].dot(&fe);
                    }
                    w.w_dl[info.offset + m] = -fe;
                }
            }
        }
        if self.hess.torques_only {
            return; // a pass of the second-order term reads the torques' derivatives only
        }
        match spec.objective {
            Objective::Torque => {
                for l in 0..nv {
                    let s = self.torque_factor(l, self.work.tau[l]);
                    let w = &mut self.work;
                    w.res[l] = s * w.tau[l];
                    if jac {
                        for c in 0..nv {
                            w.rdq[l * nv + c] = s * w.dq[l * nv + c];
                            w.rdv[l * nv + c] = s * w.dv[l * nv + c];
                            w.rda[l * nv + c] = s * w.da[l * nv + c];
                        }
                        for m in 0..nl {
                            w.rdl[l * nl + m] = s * w.dl[l * nl + m];
                        }
                    }
                }
            }
            Objective::TorqueInverseInertia => {
                objective::inverse_inertia_residual(model, &mut self.data, &mut self.work, nv, nl, jac);
                self.work.scale_residual(spec.terms.torque.sqrt());
            }
        }
    }

    /// Writes a row's values over the pattern `motion ++ lambda` from its derivatives with respect to the
    /// node's `q`, `q̇`, `q̈` (each `nv`) and `λ̃` (`n_lambda`), by the chain rule of eq. 33, scaled by `s`.
    fn chain_rule(layout: &Layout, basis: &BasisAt, s: f64, d: Derivatives, out: &mut [f64]) {
        let Derivatives { q: d_q, v: d_v, a: d_a, lambda: d_l } = d;
        let slots = layout.motion_slots(basis.first);
        let nv = layout.nv;
        let mut pos = slots.iter().flatten().max().map_or(0, |s| (s + 1) * nv);
        out[..pos].fill(0.0);
        for (a, slot) in slots.iter().enumerate() {
            let Some(slot) = slot else { continue };
            let (b, db, ddb) = (basis.b[a] * s, basis.db[a] * s, basis.ddb[a] * s);
            for i in 0..nv {
                out[slot * nv + i] += d_q[i] * b + d_v[i] * db + d_a[i] * ddb;
            }
        }
        if let Some(d_l) = d_l {
            for a in 0..4 {
                let b = basis.b[a] * s;
                for m in 0..layout.n_lambda {
                    out[pos] = d_l[m] * b * layout.lambda_scale;
                    pos += 1;
                }
            }
        }
    }
}

impl Transcription<'_> {
    /// The contact-force columns of contact `c` at a node.
    fn contact_columns(&self, basis: &BasisAt, c: usize) -> Vec<usize> {
        let info = &self.contacts[c];
        let mut cols = Vec::new();
        for j in basis.first..basis.first + 4 {
            cols.extend((0..info.directions.len()).map(|m| self.layout.lambda_var(j, info.offset + m)));
        }
        cols
    }

    fn n_ineq_node(&self) -> usize {
        self.ineq_rows.len()
    }

    /// Loop-closure rows.
    fn n_contact_eq(&self) -> usize {
        self.contact_nodes.t.len() * self.n_eq_node
    }

    /// Which node and which row within it an inequality index is.
    pub fn decode_ineq(&self, index: usize) -> (usize, IneqRow) {
        let per = self.n_ineq_node().max(1);
        (index / per, self.ineq_rows[index % per])
    }

    /// `true` when the effort limits of some joint differ by direction.
    fn asymmetric_limits(&self) -> bool {
        self.effort[0] != self.effort[1]
    }

    /// Starts a solve-independent evaluation: the control points of `x`.
    pub fn set_x(&mut self, x: &[f64]) {
        self.layout.unpack(x, &self.fixed_values, &mut self.ctrl, &mut self.lam_ctrl);
    }
}

impl Problem for Transcription<'_> {
    fn dims(&self) -> Dims {
        let nn = self.n_nodes();
        Dims {
            n: self.layout.n,
            n_res: self.terms.n_res(),
            n_eq: self.n_contact_eq(),
            n_ineq: nn * self.n_ineq_node() + self.goals.n_rows(),
        }
    }

    fn jacobian_patterns(&self) -> Patterns {
        let nv = self.layout.nv;
        let mut p = Patterns::default();
        for basis in &self.nodes.basis {
            let (motion, lambda) = self.node_columns(basis);
            let both: Vec<usize> = motion.iter().chain(lambda.iter()).copied().collect();
            for _ in 0..nv {
                p.r.push(both.clone());
            }
            for row in &self.ineq_rows {
                p.g.push(match *row {
                    IneqRow::UpperPosition(i) | IneqRow::LowerPosition(i) => (basis.first..basis.first + 4)
                        .filter(|&j| self.layout.owns(j))
                        .filter_map(|j| self.layout.joint_var(j, i))
                        .collect(),
                    IneqRow::UpperTorque(_) | IneqRow::LowerTorque(_) | IneqRow::Balance(_) => both.clone(),
                    IneqRow::Push(c) | IneqRow::Friction(c, _) => self.contact_columns(basis, c),
                    IneqRow::Collision(_) => motion.clone(),
                });
            }
        }
        for basis in &self.contact_nodes.basis {
            let (motion, _) = self.node_columns(basis);
            for _ in 0..self.n_eq_node {
                p.h.push(motion.clone());
            }
        }
        p.g.extend(self.goal_patterns());
        self.term_patterns(&mut p);
        p
    }

    fn evaluate(&mut self, x: &[f64], want_jac: bool, out: &mut Evaluation) -> Result<(), String> {
        self.set_x(x);
        self.contact_rows(want_jac, out);
        let nv = self.layout.nv;
        let nl = self.layout.n_lambda;
        for k in 0..self.n_nodes() {
            self.eval_node(k, want_jac);
            let basis = self.nodes.basis[k];
            let sw = self.nodes.w[k].sqrt();
            let w = &mut self.work;
            // Objective residuals: √wₖ times the node's residual (√W τ, or L⁻¹τ).
            for l in 0..nv {
                out.r[k * nv + l] = sw * w.res[l];
                if want_jac {
                    Self::chain_rule(&self.layout, &basis, sw, w.residual_row(l, nv, nl), out.jr.row_values_mut(k * nv + l));
                }
            }
            self.inequality_rows(k, want_jac, out);
            self.term_rows(k, want_jac, out);
        }
        self.goal_rows(self.n_nodes() * self.n_ineq_node(), want_jac, out);
        self.jerk_rows(want_jac, out);
        Ok(())
    }

    fn add_second_order(&mut self, x: &[f64], weights: [&[f64]; 3], target: &mut SymmetricMatrix) -> bool {
        if self.spec.objective != Objective::Torque {
            return false;
        }
        self.add_second_order_term(x, weights, target);
        true
    }

    fn scales(&self) -> Scales {
        let nn = self.n_nodes();
        let per_node: Vec<f64> = self
            .ineq_rows
            .iter()
            .map(|row| match *row {
                IneqRow::UpperPosition(i) | IneqRow::LowerPosition(i) => {
                    let range = self.limits_up[i] - self.limits_low[i];
                    if range.is_finite() && range > 0.0 {
                        range
                    } else {
                        1.0
                    }
                }
                IneqRow::UpperTorque(i) => self.torque_bound(i, true).max(1e-9),
                IneqRow::LowerTorque(i) => self.torque_bound(i, false).max(1e-9),
                IneqRow::Push(_) | IneqRow::Friction(..) => self.total_weight.max(1.0),
                IneqRow::Balance(4) => self.total_weight.max(1.0),
                IneqRow::Balance(_) => (0.1 * self.total_weight).max(1.0),
                IneqRow::Collision(_) => 1.0, // metres, like the contacts
            })
            .collect();
        // Goals in metres (like the contacts), their orientations as cosines.
        let goals = std::iter::repeat_n(1.0, self.goals.n_rows());
        Scales { eq: vec![1.0; self.n_contact_eq()], ineq: (0..nn).flat_map(|_| per_node.iter().copied()).chain(goals).collect() }
    }

    fn row_name(&self, family: RowFamily, index: usize) -> String {
        match family {
            RowFamily::Residual => {
                let nv = self.layout.nv;
                let (k, l) = (index / nv, index % nv);
                let joint = &self.spec.model.joints[l + 1].name;
                format!("the objective's torque residual of joint \"{joint}\" at t = {:.3} s (node {k})", self.nodes.t[k])
            }
            RowFamily::Equality => self.constraint_name(ConstraintKind::Equality, index),
            RowFamily::Inequality => self.constraint_name(ConstraintKind::Inequality, index),
        }
    }

    fn constraint_name(&self, kind: ConstraintKind, index: usize) -> String {
        let joint = |i: usize| self.spec.model.joints[i + 1].name.clone();
        match kind {
            ConstraintKind::Inequality if index >= self.n_nodes() * self.n_ineq_node() => {
                self.goal_row_name(index - self.n_nodes() * self.n_ineq_node())
            }
            ConstraintKind::Equality => {
                let per = self.n_eq_node.max(1);
                let (k, m) = (index / per, index % per);
                let c = self.contacts.iter().rposition(|c| c.offset <= m).unwrap_or(0);
                format!(
                    "contact \"{}\" (component {}) at t = {:.3} s",
                    self.spec.contacts[c].name,
                    m - self.contacts[c].offset,
                    self.contact_nodes.t[k]
                )
            }
            ConstraintKind::Inequality => {
                let (k, row) = self.decode_ineq(index);
                let t = self.nodes.t[k];
                let contact = |c: usize| self.spec.contacts[c].name.clone();
                let what = match row {
                    IneqRow::UpperPosition(i) => format!("upper position limit of joint \"{}\"", joint(i)),
                    IneqRow::LowerPosition(i) => format!("lower position limit of joint \"{}\"", joint(i)),
                    IneqRow::UpperTorque(i) => format!("torque limit (+) of joint \"{}\"", joint(i)),
                    IneqRow::LowerTorque(i) => format!("torque limit (−) of joint \"{}\"", joint(i)),
                    IneqRow::Push(c) => format!("push-only contact force of \"{}\"", contact(c)),
                    IneqRow::Friction(c, _) => format!("friction cone of \"{}\"", contact(c)),
                    IneqRow::Balance(4) => "balance: feet stay loaded".to_string(),
                    IneqRow::Balance(_) => "balance: centre of pressure inside the support".to_string(),
                    IneqRow::Collision(p) => format!("distance between {}", self.collisions.describe(self.spec, p)),
                };
                format!("{what} at t = {t:.3} s")
            }
        }
    }
}

/// `nodes` followed by `more` (weight 0).
fn append(nodes: &mut Nodes, more: Nodes) {
    nodes.t.extend(more.t);
    nodes.w.extend(more.w);
    nodes.basis.extend(more.basis);
}

/// Everything known about the motion at one time.
#[derive(Clone, Debug, Default)]
pub struct NodeValues {
    /// Time (s).
    pub t: f64,
    /// Joint positions (rad or m).
    pub q: Vec<f64>,
    /// Joint velocities (rad/s or m/s).
    pub qd: Vec<f64>,
    /// Joint accelerations (rad/s² or m/s²).
    pub qdd: Vec<f64>,
    /// Active (muscle) torques: total minus passive, contact and load contributions.
    pub tau: Vec<f64>,
    /// The contact forces the environment applies, world axes (N), one per contact.
    pub contact_forces: Vec<Vec3>,
    /// The contact points (world, m).
    pub contact_points: Vec<Vec3>,
    /// The wrench the ground applies to the root (world axes, moment about the world origin).
    pub root_wrench: Force,
}

impl Transcription<'_> {
    /// The values at node `k` for the control points last given to [`Transcription::set_x`].
    pub fn node_values(&mut self, k: usize) -> NodeValues {
        self.eval_node(k, false);
        let w = &self.work;
        let contact_forces = self
            .contacts
            .iter()
            .map(|info| info.directions.iter().enumerate().fold(Vec3::zeros(), |f, (m, e)| f + e * w.lambda[info.offset + m]))
            .collect();
        NodeValues {
            t: self.nodes.t[k],
            q: w.q.clone(),
            qd: w.qd.clone(),
            qdd: w.qdd.clone(),
            tau: w.tau.clone(),
            contact_forces,
            contact_points: w.points.clone(),
            root_wrench: w.w,
        }
    }

    /// Number of nodes.
    pub fn len(&self) -> usize {
        self.n_nodes()
    }

    /// Whether there are no nodes.
    pub fn is_empty(&self) -> bool {
        self.n_nodes() == 0
    }
}

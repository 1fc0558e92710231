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
mod hessian_exact;
mod hessian_mapping;
mod joint_goal;
mod layout;
mod measure;
mod node;
mod node_gradient;
mod objective;
mod problem;
mod root;
mod root_gradient;
pub(crate) mod samples;
mod strength;
mod terms;
mod values;
mod warm;

use super::spec::{Objective, Spec};
use crate::dynamics::point_force::{add_generalized_force, generalized_force_derivative, path_dofs, point_jacobian};
use crate::dynamics::{kinematics, rnea::rnea, rnea_derivatives::rnea_derivatives, Data};
use crate::solve::{ConstraintKind, Dims, Evaluation, Patterns, Problem, RowFamily, Scales, SymmetricMatrix};
use crate::spatial::{Force, Vec3};
use crate::trajectory::bspline::{BasisAt, CubicBSpline, Nodes};
pub use collision::worst_clearance;
pub use constraints::IneqRow;
pub use layout::Layout;
pub use measure::{Measured, RowKind};
use node::{Derivatives, NodeWork};
pub use terms::Terms;
pub use values::NodeValues;

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
    /// A free root's zero-force rows, at one node per span (empty for a figure held by the world).
    root: root::RootRows,
    /// A free body's momentum and joint torques (`root.rs`).
    free: root::FreeBody,
    /// The position limits at more times than the nodes (`samples.rs`; none on a grid).
    samples: samples::PositionSamples,
    /// Per DOF `l`, the DOFs `τ_l` depends on ([`Model::torque_dofs`]): the support of its rows.
    torque_dofs: Vec<Vec<usize>>,
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
        // A free root's momenta: equality rows at one node per span instead of limit rows at every node.
        let unactuated: Vec<usize> = (0..spec.model.nv()).filter(|&i| spec.model.is_unactuated(i)).collect();
        let n_spans = t.spline.n_spans();
        t.root = root::RootRows::one_per_span(unactuated, n_spans, spec.nodes_per_span, t.nodes.t.len());
        t.ineq_rows.retain(|r| !matches!(r, IneqRow::UpperTorque(i) | IneqRow::LowerTorque(i) if spec.model.is_unactuated(*i)));
        // The ends and the Gauss nodes are in time order: the torque-change rows join them.
        t.terms = terms::TermWork::new(&t, ordered);
        t.samples = samples::PositionSamples::new(spec, &t.spline, &t.ineq_rows)?;
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
        // A free root's generalised forces are held at 0 (τ ≤ 0 and −τ ≤ 0) whether or not the limits are —
        // rows kept for the dense check (`on_grid`); on the quadrature nodes `new` replaces them by `root` rows.
        for i in 0..nv {
            if spec.torque_limits || model.is_unactuated(i) {
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
            hess: hessian::HessianWork::new(&spec.model, n_lambda),
            goals,
            root: root::RootRows::default(),
            free: root::FreeBody::new(spec, n_lambda),
            samples: samples::PositionSamples::default(),
            // A free body's joint torques depend on every DOF (`root.rs`).
            torque_dofs: (0..nv)
                .map(|l| if model.is_free_floating() { (0..nv).collect() } else { model.torque_dofs(l) })
                .collect(),
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

    /// The pattern of a row at the node `basis` that depends on the DOFs `dofs` only, ascending: per control
    /// point its own columns of `dofs` (if it owns any), then its contact forces.
    fn supported_columns(&self, basis: &BasisAt, dofs: &[usize]) -> Vec<usize> {
        let l = &self.layout;
        let mut columns = Vec::new();
        for j in basis.first..basis.first + 4 {
            if l.owns(j) {
                columns.extend(dofs.iter().filter_map(|&i| l.joint_var(j, i)));
            }
            columns.extend((0..l.n_lambda).map(|m| l.lambda_var(j, m)));
        }
        columns
    }

    /// The DOFs node residual `l` depends on: those of `τ_l` when it is `f τ_l` (`None`, all, for `L⁻¹τ`).
    fn residual_dofs(&self, l: usize) -> Option<&[usize]> {
        matches!(self.spec.objective, Objective::Torque).then(|| &self.torque_dofs[l][..])
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

    /// Where the loop closures' rows start among the equality rows (after the free root's).
    fn contact_eq0(&self) -> usize {
        self.root.n_rows()
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

/// `nodes` followed by `more` (weight 0).
fn append(nodes: &mut Nodes, more: Nodes) {
    nodes.t.extend(more.t);
    nodes.w.extend(more.w);
    nodes.basis.extend(more.basis);
}

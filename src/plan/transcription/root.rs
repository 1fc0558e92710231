//! A free-floating figure's unactuated root (`model::floating`): nothing holds the body, so its momentum
//! stays what it was at the start — zero, the figure starting at rest — and its root moves as that dictates.
//!
//! **The root follows the momentum.** The six generalised momenta of the root's joints vanish,
//!
//! ```text
//!   pᵢ(tₖ) = (H(q) q̇)ᵢ = Sᵢ · h = 0,   i ∈ root DOF,   tₖ one collocation node per knot span
//! ```
//!
//! (`h` the body's spatial momentum; every body lies below every root joint, so the six `pᵢ` are `h` seen
//! along the root's six axes, and they vanish together with it away from the root's gimbal lock). They are
//! equality rows at **one node per knot span**: per root DOF the spline has as many free control points as
//! knot spans (the start's two are fixed, the end's two share the solved goal posture), so one row per span
//! determines the root's velocity from the joints'. Between the rows the dense check measures the momentum
//! in kg·m/s and kg·m²/s against `plan::Tolerances::root_momentum`. (Rows of the root's *force* `τᵢ = 0`,
//! used before, are its momentum's derivative: a spline matches them only where they hold, and between
//! them the forces of a brisk arm raise reached 40–230 N at N = 16–32.)
//!
//! **The joints' torques are the free body's.** The spline gives the root an acceleration `q̈_r` of its own;
//! every node takes instead the joints' torques of the same `q, q̇, q̈_j` with the root accelerating freely,
//! `q̈_r* = q̈_r − H_rr⁻¹ τ_r` (the root's force then 0), so that no force holding the root to its spline
//! enters the objective, the limits or the reports (the root's own force is then 0):
//!
//! ```text
//!   τ_j* = τ_j − G τ_r,   G = H_jr H_rr⁻¹
//!   ∂τ_j*/∂x = ∂τ_j/∂x − G ∂τ_r/∂x − [x = q] (D_j − G D_r),   D = ∂(H(q) ỹ)/∂q,  ỹ = [H_rr⁻¹ τ_r; 0]
//! ```
//!
//! (`D`, like `∂p/∂q = ∂(H(q) q̇)/∂q`, is the derivative of inverse dynamics at zero velocity and gravity:
//! one more pass of the engine each.)
//!
//! **Held or pushed** — a contact (a hand on a rail), gravity, a load — the momentum is not conserved, and
//! the rows are the root's forces `τᵢ(tₖ) = 0` of the spline's motion instead, measured between the nodes
//! against `root_force_n`.
//!
//! The rows come first among the equality rows (the loop closures' check nodes are appended after theirs,
//! so that warm multipliers keep their indices).

use super::node::Derivatives;
use super::{Spec, Transcription};
use crate::dynamics::{crba::crba, rnea_derivatives::rnea_derivatives};
use crate::model::Model;
use crate::solve::Evaluation;
use crate::spatial::Vec3;
use nalgebra::{Cholesky, Const, DMatrix, Matrix6, Vector6};

/// Where the root's rows are: its DOFs and the nodes they hold at.
#[derive(Clone, Debug, Default)]
pub(super) struct RootRows {
    /// The unactuated DOFs (the free root's six), in `q` order.
    pub(super) dofs: Vec<usize>,
    /// For each quadrature node, the index of its block of rows (`None`: no root rows there).
    pub(super) block_of: Vec<Option<usize>>,
    /// The nodes that carry a block, in order.
    pub(super) nodes: Vec<usize>,
}

impl RootRows {
    /// The rows of `dofs` at node `1 + nodes_per_span·s + ⌊(nodes_per_span − 1)/2⌋` of every span `s` — the
    /// Gauss node just before the span's middle (node 0 is the start, the Gauss nodes follow span by span,
    /// then the end; at both ends the figure is at rest and its momentum 0 already).
    pub(super) fn one_per_span(dofs: Vec<usize>, n_spans: usize, nodes_per_span: usize, n_nodes: usize) -> Self {
        if dofs.is_empty() {
            return RootRows::default();
        }
        let inner = (0..n_spans).map(|s| 1 + nodes_per_span * s + (nodes_per_span - 1) / 2);
        let nodes: Vec<usize> = inner.collect();
        let mut block_of = vec![None; n_nodes];
        for (b, &k) in nodes.iter().enumerate() {
            block_of[k] = Some(b);
        }
        RootRows { dofs, block_of, nodes }
    }

    /// Their number of rows.
    pub(super) fn n_rows(&self) -> usize {
        self.nodes.len() * self.dofs.len()
    }

    /// The block of node `k`, if it has one.
    pub(super) fn block(&self, k: usize) -> Option<usize> {
        self.block_of.get(k).copied().flatten()
    }

    /// Which node and which DOF equality row `index` (< `n_rows`) is.
    pub(super) fn decode(&self, index: usize) -> (usize, usize) {
        let per = self.dofs.len().max(1);
        (self.nodes[index / per], self.dofs[index % per])
    }
}

/// A free body's root rows and joint torques at a node: scratch allocated once (empty for a held figure).
#[derive(Clone, Debug, Default)]
pub(super) struct FreeBody {
    /// The root's six DOFs (empty: the figure is held).
    pub(super) dofs: Vec<usize>,
    /// Whether the momentum is conserved (no contact, no gravity, no load): the rows are then the momenta
    /// `pᵢ`; otherwise the root's forces `τᵢ` of the spline's motion (a hand on a rail, gravity).
    pub(super) conserved: bool,
    /// `G = H_jr H_rr⁻¹`, `nv × 6` row-major (the root's rows unused).
    pub(super) g: Vec<f64>,
    /// The root rows' values, and their derivatives along `q`, `q̇`, `q̈` (`6 × nv` each) and `λ̃` (`6 × n_λ`).
    pub(super) row: [f64; 6],
    d_q: Vec<f64>,
    d_v: Vec<f64>,
    d_a: Vec<f64>,
    d_l: Vec<f64>,
    /// `y = H_rr⁻¹ τ_r`: the free root's acceleration is the spline's less `y` (`q̈_r* = q̈_r − y`).
    pub(super) accel_shift: [f64; 6],
    /// `ỹ` and zeros (`nv`).
    pub(super) y_tilde: Vec<f64>,
    pub(super) zeros: Vec<f64>,
    /// The contracted gradient's (`root_gradient.rs`): `H_rr`'s factor at the `q` of `g`, the weights `ω̃`
    /// and those of the first pass, and one pass's `∂/∂q, ∂/∂q̇, ∂/∂q̈` (`nv` each).
    pub(super) root_factor: Option<Cholesky<f64, Const<6>>>,
    pub(super) omega_tilde: Vec<f64>,
    pub(super) omega_first: Vec<f64>,
    pub(super) pass: [Vec<f64>; 3],
}

impl FreeBody {
    pub(super) fn new(spec: &Spec, nl: usize) -> Self {
        let nv = spec.model.nv();
        let dofs: Vec<usize> = (0..nv).filter(|&i| spec.model.is_unactuated(i)).collect();
        if dofs.len() != 6 {
            return FreeBody::default();
        }
        let conserved =
            spec.contacts.is_empty() && spec.gravity.norm() == 0.0 && spec.loads.iter().all(|l| l.force.norm() == 0.0);
        let z = vec![0.0; 6 * nv];
        FreeBody {
            dofs,
            conserved,
            g: z.clone(),
            row: [0.0; 6],
            accel_shift: [0.0; 6],
            d_q: z.clone(),
            d_v: z.clone(),
            d_a: z,
            d_l: vec![0.0; 6 * nl],
            y_tilde: vec![0.0; nv],
            zeros: vec![0.0; nv],
            root_factor: None,
            omega_tilde: vec![0.0; nv],
            omega_first: vec![0.0; nv],
            pass: [vec![0.0; nv], vec![0.0; nv], vec![0.0; nv]],
        }
    }

    /// `H_rr`'s factor into `root_factor` and `G = H_jr H_rr⁻¹` into `g` from `h = H(q)`; the factor, or
    /// `None` if `H_rr` is singular.
    pub(super) fn factor_root(&mut self, h: &DMatrix<f64>) -> Option<&Cholesky<f64, Const<6>>> {
        let r = &self.dofs;
        self.root_factor = Matrix6::from_fn(|a, b| h[(r[a], r[b])]).cholesky();
        let factor = self.root_factor.as_ref()?;
        for j in (0..h.nrows()).filter(|j| !r.contains(j)) {
            // G_j = H_jr H_rr⁻¹ (its row: H_rr⁻¹ H_rj, H_rr symmetric)
            let g_j = factor.solve(&Vector6::from_fn(|a, _| h[(j, r[a])]));
            self.g[j * 6..j * 6 + 6].copy_from_slice(g_j.as_slice());
        }
        Some(factor)
    }

    /// Root row `m`'s derivatives with respect to the node's `q`, `q̇`, `q̈`, `λ̃`.
    pub(super) fn row_derivatives(&self, m: usize, nv: usize, nl: usize) -> Derivatives<'_> {
        Derivatives::row(m, (nv, nl), [&self.d_q, &self.d_v, &self.d_a], &self.d_l)
    }

    /// The unit of root row `m` on DOF `i`: a momentum's or a force's.
    pub(super) fn unit(&self, model: &Model, i: usize) -> &'static str {
        let prismatic = model.joints[i + 1].kind == crate::model::JointKind::Prismatic;
        match (self.conserved, prismatic) {
            (true, true) => "kg·m/s",
            (true, false) => "kg·m²/s",
            (false, true) => "N",
            (false, false) => "N·m",
        }
    }
}

impl Transcription<'_> {
    /// For a free body: the root rows into `self.free`, and the joints' torques in `self.work` (and their
    /// derivatives when `jac`) replaced by the free body's, `τ_j* = τ_j − H_jr H_rr⁻¹ τ_r` (module docs).
    /// `self.data.M` must hold `H(q)` when `jac`.
    pub(super) fn free_body(&mut self, jac: bool) {
        if self.free.dofs.is_empty() {
            return;
        }
        if !jac {
            crba(&self.spec.model, &mut self.data, &self.work.q);
        }
        self.root_row_values(jac);
        let Some(y) = self.project_joint_torques() else { return };
        if jac {
            self.project_joint_torque_slopes(&y);
        }
    }

    /// The root rows: the momenta `pᵢ = Hᵢ· q̇` (`∂/∂q̇ = Hᵢ·`, `∂/∂q = ∂(H q̇)/∂q`: inverse dynamics at
    /// velocity 0, acceleration q̇, no gravity), or the spline's root forces `τᵢ`.
    fn root_row_values(&mut self, jac: bool) {
        let (nv, nl) = (self.layout.nv, self.layout.n_lambda);
        let (model, w, data, f) = (&self.spec.model, &self.work, &mut self.data, &mut self.free);
        for (m, &ra) in f.dofs.iter().enumerate() {
            let rows = m * nv..(m + 1) * nv;
            if f.conserved {
                f.row[m] = (0..nv).map(|c| data.M[(ra, c)] * w.qd[c]).sum();
                (0..nv).for_each(|c| f.d_v[m * nv + c] = data.M[(ra, c)]);
            } else {
                f.row[m] = w.tau[ra];
                if jac {
                    f.d_q[rows.clone()].copy_from_slice(&w.dq[ra * nv..(ra + 1) * nv]);
                    f.d_v[rows.clone()].copy_from_slice(&w.dv[ra * nv..(ra + 1) * nv]);
                    f.d_a[rows].copy_from_slice(&w.da[ra * nv..(ra + 1) * nv]);
                    f.d_l[m * nl..(m + 1) * nl].copy_from_slice(&w.dl[ra * nl..(ra + 1) * nl]);
                }
            }
        }
        if f.conserved && jac {
            rnea_derivatives(model, data, &w.q, &f.zeros, &w.qd, &Vec3::zeros(), None);
            for (m, &ra) in f.dofs.iter().enumerate() {
                (0..nv).for_each(|c| f.d_q[m * nv + c] = data.dtau_dq[(ra, c)]);
            }
        }
    }

    /// `τ_j* = τ_j − H_jr y`, `H_rr y = τ_r`, and `G`; the root's torques then 0. `None` if `H_rr` is
    /// singular (the torques are left as they are).
    fn project_joint_torques(&mut self) -> Option<Vector6<f64>> {
        let nv = self.layout.nv;
        let (w, f, h) = (&mut self.work, &mut self.free, &self.data.M);
        f.accel_shift = [0.0; 6];
        let tau_r = Vector6::from_fn(|a, _| w.tau[f.dofs[a]]);
        let y = f.factor_root(h)?.solve(&tau_r);
        f.accel_shift.copy_from_slice(y.as_slice());
        let r = &f.dofs;
        for j in (0..nv).filter(|j| !r.contains(j)) {
            // τ_j* = τ_j − H_jr y
            w.tau[j] -= Vector6::from_fn(|a, _| h[(j, r[a])]).dot(&y);
        }
        r.iter().for_each(|&ra| w.tau[ra] = 0.0);
        Some(y)
    }

    /// `∂τ_j* = ∂τ_j − G ∂τ_r` for the `q, q̇, q̈, λ̃` columns, less `D_j − G D_r` along `q`
    /// (`D = ∂(H ỹ)/∂q`); the root's rows then 0.
    fn project_joint_torque_slopes(&mut self, y: &Vector6<f64>) {
        let (nv, nl) = (self.layout.nv, self.layout.n_lambda);
        let (model, w, data, f) = (&self.spec.model, &mut self.work, &mut self.data, &mut self.free);
        let r = &f.dofs;
        for j in (0..nv).filter(|j| !r.contains(j)) {
            for (m, &ra) in r.iter().enumerate() {
                let g = f.g[j * 6 + m];
                for mat in [&mut w.dq, &mut w.dv, &mut w.da] {
                    for c in 0..nv {
                        mat[j * nv + c] -= g * mat[ra * nv + c];
                    }
                }
                for c in 0..nl {
                    w.dl[j * nl + c] -= g * w.dl[ra * nl + c];
                }
            }
        }
        for &ra in r {
            for mat in [&mut w.dq, &mut w.dv, &mut w.da] {
                mat[ra * nv..(ra + 1) * nv].fill(0.0);
            }
            w.dl[ra * nl..(ra + 1) * nl].fill(0.0);
        }
        f.y_tilde.fill(0.0);
        for (m, &ra) in r.iter().enumerate() {
            f.y_tilde[ra] = y[m];
        }
        rnea_derivatives(model, data, &w.q, &f.zeros, &f.y_tilde, &Vec3::zeros(), None);
        for j in (0..nv).filter(|j| !r.contains(j)) {
            for c in 0..nv {
                let gd: f64 = r.iter().enumerate().map(|(m, &ra)| f.g[j * 6 + m] * data.dtau_dq[(ra, c)]).sum();
                w.dq[j * nv + c] -= data.dtau_dq[(j, c)] - gd;
            }
        }
    }

    /// The root's rows `h = pᵢ` (or `τᵢ`) of node `k` (after `eval_node(k)`), with their Jacobians (eq. 33).
    pub(super) fn root_rows(&mut self, k: usize, want_jac: bool, out: &mut Evaluation) {
        let Some(b) = self.root.block(k) else { return };
        let (nv, nl) = (self.layout.nv, self.layout.n_lambda);
        let basis = self.nodes.basis[k];
        for m in 0..self.root.dofs.len() {
            let row = b * self.root.dofs.len() + m;
            out.h[row] = self.free.row[m];
            if want_jac {
                Self::chain_rule(&self.layout, &basis, 1.0, self.free.row_derivatives(m, nv, nl), out.jh.row_values_mut(row));
            }
        }
    }

    /// The root rows' multipliers `w_h` at node `k` into `hess.root_w` (`∇²(w · p)`).
    pub(super) fn root_weights(&mut self, k: usize, w_h: &[f64]) {
        self.hess.root_w = [0.0; 6];
        let Some(b) = self.root.block(k) else { return };
        let per = self.root.dofs.len();
        for m in 0..per {
            self.hess.root_w[m] = w_h[b * per + m];
        }
    }

    /// The name of root row `index`: the joint and the time.
    pub(super) fn root_row_name(&self, index: usize) -> String {
        let (k, i) = self.root.decode(index);
        let joint = &self.spec.model.joints[i + 1].name;
        let what = if self.free.conserved { "momentum" } else { "force" };
        format!("zero {what} along the free root's joint \"{joint}\" at t = {:.3} s", self.nodes.t[k])
    }

    /// The unit of DOF `i`'s generalised force.
    pub(super) fn force_unit(&self, i: usize) -> &'static str {
        if self.spec.model.joints[i + 1].kind == crate::model::JointKind::Prismatic {
            "N"
        } else {
            "N·m"
        }
    }
}

//! The second-order term of the Lagrangian's Hessian, `Σⱼ wⱼ ∇²cⱼ`, node by node, for the structured
//! solver's model `JᵀJ + Σ wⱼ∇²cⱼ` (see `solve::least_squares`).
//!
//! At a node the rows that curve are functions of the active torque `τ(z, λ)` and the root wrench
//! `W(z, λ)`, `z = (q, q̇, q̈)`: the residuals `√wₖ √W_l τ_l`, the torque limits `±τᵢ − τ_max` and the
//! balance rows `c·W`; a free root's momentum rows add `Σ w_pᵢ ∇pᵢ` (`root.rs`). With the rows' weights they
//! add up to one scalar per node,
//!
//! ```text
//!   φₖ(z, λ) = Σ_l ω_l τ_l(z, λ) + ω_W · W(z, λ),      ∇²_x(Σ wⱼcⱼ) = Σₖ Bₖᵀ ∇²φₖ Bₖ      (eq. 33)
//! ```
//!
//! `Bₖ` the chain rule of eq. 33 (the four basis functions and their derivatives; `hessian_mapping.rs`). `∇φₖ`
//! is exact and costs one O(nv) contracted pass of the engine (`node_gradient.rs`, `dynamics::rnea_gradient`).
//!
//! **Exact nodes** — a fixed base and no strength terms (`hessian_exact.rs`): `∇²φₖ` over `(q, q̇, q̈)` comes
//! whole from one O(nv·depth) pass (`dynamics::rnea_hessian`), the loads and contact
//! forces add their own terms (`dynamics::point_force`), and nothing is differenced.
//!
//! **Differenced nodes** — a free root, or strength terms, whose weights vary with `q` and `q̇`: `∇²φₖ`'s `q`
//! columns are the gradient's forward differences, one moved pass per `qᵢ` (`dynamics::rnea_gradient_moved`
//! recomputes only the moved joint's subtree; a free root repeats whole passes and skips its translations,
//! whose columns are zero). The `q̇`–`q̇` block is exact where there are no strength terms (a free body's `q̇`
//! part is `ω̃ᵀτ` at weights of `q` alone: `dynamics::rnea_velocity_hessian`), else differenced too. The rest
//! follows by structure: `τ` is linear in `q̈` and in `λ`, and `∂τ/∂q̈ = H(q)` does not depend on `q̇`, so
//! `∂²φ/∂q̈² = ∂²φ/∂q̈∂q̇ = ∂²φ/∂λ² = ∂²φ/∂λ∂q̇ = 0` and the remaining blocks follow by symmetry from the `q`
//! (and `q̇`) columns.
//!
//! **Other rows.** The loop closures `Φ = Eᵀ(p(q) − target)` at the contact nodes add `Σ w_h ∇²Φ`, the
//! difference of the point Jacobians along each `qᵢ`; the distances between solids `margin − d(q)` at the
//! quadrature nodes add `Σ w_g ∇²(−d)`, the difference of their exact witness-point gradients along each `qᵢ`
//! (`collision.rs`), and the task-space goals' rows (`goals.rs`) the same way at their times. Position
//! limits and contact-force signs are linear and add nothing.

use super::constraints::balance_coefficients;
use super::hessian_mapping::Group;
use super::node_gradient::Pass;
use super::{IneqRow, Transcription};
use crate::dynamics::rnea_gradient_moved::{restore, Moved, Subtrees};
use crate::dynamics::rnea_velocity_hessian::VelocityHessianWork;
use crate::dynamics::{kinematics, point_force::point_jacobian, Data};
use crate::model::Model;
use crate::solve::SymmetricMatrix;
use crate::spatial::{Motion, Vec3};
use crate::trajectory::bspline::BasisAt;

/// Relative step of the forward differences: `ε = STEP·(1 + |zᵢ|)`, about √(machine ε).
const STEP: f64 = 1e-7;

/// Scratch for the second-order term, allocated once per transcription.
#[derive(Clone, Debug)]
pub(super) struct HessianWork {
    /// The node state `(q, q̇, q̈, λ)` and `∇φ` there; a perturbed gradient.
    pub(super) z: Vec<f64>,
    pub(super) grad: Vec<f64>,
    pub(super) grad_perturbed: Vec<f64>,
    /// `∇²φ`, `d × d` row-major, `d = 3nv + n_λ`.
    pub(super) s: Vec<f64>,
    /// Per-node weights: `ω` (nv) and `ω_W`.
    pub(super) omega: Vec<f64>,
    /// The weights `ρ` of residuals `f(qᵢ, q̇ᵢ) τᵢ` whose factor varies (`strength.rs`), the direction
    /// each `τᵢ` points to at the node, and the multipliers `σ` of the strength rows (`[+, −]`).
    pub(super) rho: Vec<f64>,
    pub(super) positive: Vec<bool>,
    pub(super) sigma: [Vec<f64>; 2],
    pub(super) omega_w: [f64; 6],
    /// The multipliers of a free root's momentum rows at the node (`root.rs`).
    pub(super) root_w: [f64; 6],
    /// The weighted collision pairs `(p, −w)` of a node and their gradients, `nv` each
    /// (`Transcription::collision_hessian`).
    pub(super) pairs: Vec<(usize, f64)>,
    pub(super) pair_gradients: Vec<f64>,
    /// The node's unknowns in groups, and one row of their entries (`add_mapped`).
    pub(super) groups: Vec<Group>,
    pub(super) row: Vec<f64>,
    /// `ω̂ = ω + ρ f(q, q̇)`, the torques' weights at the state of a pass (`node_gradient.rs`).
    pub(super) omega_hat: Vec<f64>,
    /// The engine's pass at the node's state and its `∇(ω̂ᵀτ + u₀·W)` (`3nv`), the base of the moved passes;
    /// each joint's subtree and ancestors (`dynamics::rnea_gradient_moved`).
    pub(super) base: Data,
    pub(super) base_gradient: Vec<f64>,
    pub(super) subtrees: Subtrees,
    /// Scratch of the exact velocity block ([`rnea_velocity_hessian`]) and its weights.
    pub(super) velocity: VelocityHessianWork,
    pub(super) velocity_weights: Vec<f64>,
    /// Whether the engine's exact blocks may replace differences ([`Transcription::set_exact_node_blocks`]).
    pub(super) exact_blocks: bool,
}

impl HessianWork {
    /// `u₀ = ω_W` as a motion `[ω; v]`: the weights of the root wrench `W = [n; f]` in `φ`.
    pub(super) fn root_weight(&self) -> Motion {
        let ow = &self.omega_w;
        Motion::new(Vec3::new(ow[0], ow[1], ow[2]), Vec3::new(ow[3], ow[4], ow[5]))
    }

    pub(super) fn new(model: &Model, nl: usize) -> Self {
        let nv = model.nv();
        let d = 3 * nv + nl;
        HessianWork {
            z: vec![0.0; d],
            grad: vec![0.0; d],
            grad_perturbed: vec![0.0; d],
            s: vec![0.0; d * d],
            omega: vec![0.0; nv],
            rho: vec![0.0; nv],
            positive: vec![true; nv],
            sigma: [vec![0.0; nv], vec![0.0; nv]],
            omega_w: [0.0; 6],
            root_w: [0.0; 6],
            pairs: Vec::new(),
            pair_gradients: Vec::new(),
            groups: Vec::with_capacity(8),
            row: vec![0.0; nv.max(nl)],
            omega_hat: vec![0.0; nv],
            base: Data::new(model),
            base_gradient: vec![0.0; 3 * nv],
            subtrees: Subtrees::of(model),
            velocity: VelocityHessianWork::new(model),
            velocity_weights: vec![0.0; nv],
            exact_blocks: true,
        }
    }
}

impl Transcription<'_> {
    /// `target += Σⱼ wⱼ ∇²cⱼ` at `x` (lower triangle), `weights = [w_r, w_h, w_g]` the rows' weights.
    /// Only for the `½∫τᵀWτ` objective (the caller checks).
    pub(super) fn add_second_order_term(&mut self, x: &[f64], weights: [&[f64]; 3], target: &mut SymmetricMatrix) {
        self.set_x(x);
        for k in 0..self.n_nodes() {
            if self.node_weights(k, weights[0], weights[1], weights[2]) {
                self.node_hessian(k);
                let basis = self.nodes.basis[k];
                self.add_mapped(&basis, 3, target);
            }
        }
        if !self.spec.contacts.is_empty() {
            for k in 0..self.contact_nodes.t.len() {
                let eq0 = self.contact_eq0();
                let rows = &weights[1][eq0 + k * self.n_eq_node..eq0 + (k + 1) * self.n_eq_node];
                if rows.iter().any(|w| *w != 0.0) {
                    let basis = self.contact_nodes.basis[k];
                    self.state_at(&basis);
                    self.q_hessian(&mut |t: &mut Self, out: &mut [f64]| t.closure_gradient(rows, out));
                    self.add_mapped(&basis, 1, target);
                }
            }
        }
        let per = self.ineq_rows.len();
        if self.ineq_rows.iter().any(|r| matches!(r, IneqRow::Collision(_))) {
            for k in 0..self.n_nodes() {
                let rows = &weights[2][k * per..(k + 1) * per];
                let collides = |(r, w): (&IneqRow, &f64)| matches!(r, IneqRow::Collision(_)) && *w != 0.0;
                if self.ineq_rows.iter().zip(rows).any(collides) {
                    let basis = self.nodes.basis[k];
                    self.state_at(&basis);
                    self.collision_hessian(rows);
                    self.add_mapped(&basis, 1, target);
                }
            }
        }
        let g0 = self.goal_row0();
        self.add_goal_second_order(&weights[2][g0..], target);
    }

    /// `ω` and `ω_W` of node `k` from the row weights; `false` if all vanish.
    fn node_weights(&mut self, k: usize, w_r: &[f64], w_h: &[f64], w_g: &[f64]) -> bool {
        let nv = self.layout.nv;
        let sw = self.nodes.w[k].sqrt();
        // The node residual is f(τ_l) τ_l with f constant on each side of 0 (the strength term's bound per
        // direction): the sign of τ at the node picks f.
        // Under strength limits f also depends on qᵢ, q̇ᵢ: those residuals go to ρ (`strength.rs`).
        let by_sign = self.spec.terms.strength > 0.0 && (self.asymmetric_limits() || self.spec.strength.is_some());
        if by_sign {
            self.eval_node(k, false);
        }
        for l in 0..nv {
            let (positive, q, qd) =
                if by_sign { (self.work.tau[l] >= 0.0, self.work.q[l], self.work.qd[l]) } else { (true, 0.0, 0.0) };
            let weight = w_r[k * nv + l] * sw;
            let varies = self.factor_varies(l);
            let f = if varies { 0.0 } else { self.torque_factor(l, positive, q, qd).value };
            self.hess.omega[l] = weight * f;
            self.hess.rho[l] = if varies { weight } else { 0.0 };
            self.hess.positive[l] = positive;
            self.hess.sigma[0][l] = 0.0;
            self.hess.sigma[1][l] = 0.0;
        }
        self.torque_change_weights(k, w_r);
        self.root_weights(k, w_h);
        let h = &mut self.hess;
        h.omega_w = [0.0; 6];
        let per = self.ineq_rows.len();
        for (r, row) in self.ineq_rows.iter().enumerate() {
            let w = w_g[k * per + r];
            match *row {
                IneqRow::UpperTorque(i) => {
                    h.omega[i] += w;
                    h.sigma[0][i] += w;
                }
                IneqRow::LowerTorque(i) => {
                    h.omega[i] -= w;
                    h.sigma[1][i] += w;
                }
                IneqRow::Balance(b) if w != 0.0 => {
                    let c = balance_coefficients(b, self.spec.balance.as_ref().expect("balance rows need a balance"));
                    h.omega_w.iter_mut().zip(c).for_each(|(o, c)| *o += w * c);
                }
                _ => {}
            }
        }
        h.omega.iter().chain(&h.omega_w).chain(&h.rho).chain(&h.root_w).any(|v| *v != 0.0)
    }

    /// `∇²φₖ` into `hess.s`: forward differences of `∇φ` along `q` (and `q̇` where the velocity block is not
    /// exact), the rest by structure.
    fn node_hessian(&mut self, k: usize) {
        let nv = self.layout.nv;
        self.node_state(k);
        self.save_state();
        let mut grad = std::mem::take(&mut self.hess.grad);
        let mut perturbed = std::mem::take(&mut self.hess.grad_perturbed);
        // A fixed-base tree: each perturbed pass recomputes the moved joint's subtree only. A free body
        // (whose root moves every body) repeats whole passes; a q̇ column keeps q, so the placements of the
        // previous pass hold from the second q̇ column on.
        let free = !self.free.dofs.is_empty();
        // The base of the moved passes is kept only where they follow (on a fixed base, the q columns are exact
        // wherever the velocity block is).
        let velocity_exact = self.velocity_block_exact();
        let moved_passes = !free && !velocity_exact;
        self.node_gradient(&mut grad, if moved_passes { Pass::Base } else { Pass::Full { placed: false } });
        self.hess.s.fill(0.0);
        let columns = if self.position_blocks_exact() {
            self.add_exact_blocks();
            0
        } else if velocity_exact {
            self.add_velocity_block();
            nv
        } else {
            2 * nv
        };
        for j in 0..columns {
            if free && self.moves_the_whole_figure(j) {
                continue;
            }
            self.restore_state();
            let epsilon = self.perturb(j);
            let moved = if j < nv { (j, Moved::Position) } else { (j - nv, Moved::Velocity) };
            self.node_gradient(&mut perturbed, if free { Pass::Full { placed: j > nv } } else { Pass::Moved(moved.0, moved.1) });
            if !free {
                restore(&self.hess.base, &mut self.data, moved, &self.hess.subtrees);
            }
            self.add_column(j, &perturbed, &grad, epsilon, velocity_exact);
        }
        self.restore_state();
        self.hess.grad = grad;
        self.hess.grad_perturbed = perturbed;
    }

    /// Column `j` (a `q` or `q̇` column) of `hess.s` from the difference of `∇φ`, and row `j` by symmetry for
    /// the other blocks. The `q`/`q̇` block is symmetrised (half from each side), except the `q̇` rows when the
    /// velocity block is exact: there the `q` columns alone give the `q̇`–`q` entries.
    fn add_column(&mut self, j: usize, perturbed: &[f64], grad: &[f64], epsilon: f64, velocity_exact: bool) {
        let nv = self.layout.nv;
        let d = 3 * nv + self.layout.n_lambda;
        let halves = if velocity_exact { nv } else { 2 * nv };
        let s = &mut self.hess.s;
        for i in 0..d {
            let v = (perturbed[i] - grad[i]) / epsilon;
            if i < halves {
                s[i * d + j] += 0.5 * v;
                s[j * d + i] += 0.5 * v;
            } else {
                s[i * d + j] = v;
                s[j * d + i] = v;
            }
        }
    }

    fn save_state(&mut self) {
        let (nv, nl) = (self.layout.nv, self.layout.n_lambda);
        let (w, z) = (&self.work, &mut self.hess.z);
        z[..nv].copy_from_slice(&w.q);
        z[nv..2 * nv].copy_from_slice(&w.qd);
        z[2 * nv..3 * nv].copy_from_slice(&w.qdd);
        z[3 * nv..3 * nv + nl].copy_from_slice(&w.lambda);
    }

    fn restore_state(&mut self) {
        let (nv, nl) = (self.layout.nv, self.layout.n_lambda);
        let (w, z) = (&mut self.work, &self.hess.z);
        w.q.copy_from_slice(&z[..nv]);
        w.qd.copy_from_slice(&z[nv..2 * nv]);
        w.qdd.copy_from_slice(&z[2 * nv..3 * nv]);
        w.lambda.copy_from_slice(&z[3 * nv..3 * nv + nl]);
    }

    /// Moves `qⱼ` (j < nv) or `q̇ⱼ₋ₙᵥ` of the state by `ε` and returns the `ε` actually taken.
    pub(super) fn perturb(&mut self, j: usize) -> f64 {
        let nv = self.layout.nv;
        let value = if j < nv { &mut self.work.q[j] } else { &mut self.work.qd[j - nv] };
        let before = *value;
        *value = before + STEP * (1.0 + before.abs());
        *value - before
    }

    /// `q, q̇, q̈` of the node with `basis` into `work` (for the rows of `q` only).
    pub(super) fn state_at(&mut self, basis: &BasisAt) {
        let w = &mut self.work;
        basis.eval(&self.ctrl, self.layout.nv, &mut w.q, &mut w.qd, &mut w.qdd);
    }

    /// `∇²_q Σ w c` of rows that depend on `q` only (the loop closures `Φ`, the distances between solids,
    /// the frame goals) at `work.q`, into the `q` block of `hess.s` (dimension `d` as for the nodes): forward
    /// differences of their exact weighted gradient, which `gradient` writes at `work.q`, along each `qⱼ`,
    /// symmetrised. `work.q` is restored.
    pub(super) fn q_hessian(&mut self, gradient: &mut dyn FnMut(&mut Self, &mut [f64])) {
        let nv = self.layout.nv;
        let d = 3 * nv + self.layout.n_lambda;
        self.hess.z[..nv].copy_from_slice(&self.work.q);
        self.hess.s.fill(0.0);
        let mut grad = std::mem::take(&mut self.hess.grad);
        let mut perturbed = std::mem::take(&mut self.hess.grad_perturbed);
        gradient(self, &mut grad[..nv]);
        for j in 0..nv {
            self.work.q.copy_from_slice(&self.hess.z[..nv]);
            let epsilon = self.perturb(j);
            gradient(self, &mut perturbed[..nv]);
            perturbed[..nv].iter_mut().zip(&grad[..nv]).for_each(|(p, g)| *p -= g);
            add_difference_column(&mut self.hess.s, d, j, &perturbed[..nv], epsilon);
        }
        self.work.q.copy_from_slice(&self.hess.z[..nv]);
        self.hess.grad = grad;
        self.hess.grad_perturbed = perturbed;
    }

    /// `∂/∂q Σ w Φ` at `work.q` into `out[..nv]`.
    fn closure_gradient(&mut self, weights: &[f64], out: &mut [f64]) {
        let model = &self.spec.model;
        out.fill(0.0);
        kinematics::placements(model, &mut self.data, &self.work.q);
        for (c, contact) in self.spec.contacts.iter().enumerate() {
            let info = &self.contacts[c];
            let p = kinematics::frame_placement(model, &self.data, contact.frame).translation;
            point_jacobian(&self.data, &info.path, &p, &mut self.work.jac[c]);
            for (m, e) in info.directions.iter().enumerate() {
                let w = weights[info.offset + m];
                for (col, &dof) in info.path.iter().enumerate() {
                    out[dof] += w * e.dot(&self.work.jac[c][col]);
                }
            }
        }
    }
}

/// `S[i][j] = S[j][i] += ½ Δᵢ / ε` (`S` the `d × d` node block of `hess.s`): the `j`-th column of a forward
/// difference `Δ = g(z + ε eⱼ) − g(z)` of a gradient, symmetrised.
pub(super) fn add_difference_column(s: &mut [f64], d: usize, j: usize, difference: &[f64], epsilon: f64) {
    for (i, delta) in difference.iter().enumerate() {
        let v = 0.5 * delta / epsilon;
        s[i * d + j] += v;
        s[j * d + i] += v;
    }
}

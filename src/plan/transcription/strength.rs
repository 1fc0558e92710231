//! Strength as the torque limit (`constraints.strength_limits`, `model::strength`): where joint `i` has a
//! strength `S±(qᵢ, q̇ᵢ)` (per direction, at the task's population percentile), its torque rows are
//!
//! ```text
//!   τᵢ − S₊(qᵢ, q̇ᵢ) ≤ 0,   −τᵢ − S₋(qᵢ, q̇ᵢ) ≤ 0          ∂/∂x = ±∂τᵢ/∂x − (∂S/∂qᵢ Bₐ + ∂S/∂q̇ᵢ Ḃₐ)   (eq. 33)
//! ```
//!
//! and the objective's strength term divides by the same `S`: the node residual `f τᵢ` with
//! `f = √(c_τ Wᵢ + c_s/S²)`, `∂f = −c_s ∂S / (f S³)`. `S` depends on the joint's own `qᵢ`, `q̇ᵢ` only. For the
//! second-order term (`hessian.rs`) the node's `∇φ` gains `ρᵢ (f ∂τᵢ + τᵢ ∂f)` for the residual (`ρᵢ` its
//! weight times `√wₖ`, the direction `τᵢ` points to fixed at the node) and `−σ± ∂S±` for the rows (`σ±`
//! their multipliers), and `hessian.rs` differences that gradient along `q` and `q̇` as it does the rest.
//! Without strength limits `S` is the model's constant effort limit.

use super::Transcription;
use crate::model::strength::Sloped;
use crate::trajectory::bspline::BasisAt;

/// [`Transcription::torque_limit`] from the spec and the effort limits (`[+axis, −axis]`).
pub(super) fn limit_of(spec: &crate::plan::Spec, effort: &[Vec<f64>; 2], i: usize, upper: bool, q: f64, qd: f64) -> Sloped {
    let strength = spec.strength.as_ref().filter(|_| !spec.model.is_unactuated(i));
    strength.and_then(|s| s.bound(i, q, qd, upper)).unwrap_or_else(|| flat(effort[usize::from(!upper)][i]))
}

/// A constant: no slope.
fn flat(value: f64) -> Sloped {
    Sloped { value, d1: 0.0, d2: 0.0 }
}

impl Transcription<'_> {
    /// Joint `i`'s torque limit along `+axis` (`upper`) or `−axis` (a magnitude, N·m or N) at its `q`, `q̇`,
    /// with its derivatives: its strength under strength limits, else its effort limit.
    pub(super) fn torque_limit(&self, i: usize, upper: bool, q: f64, qd: f64) -> Sloped {
        limit_of(self.spec, &self.effort, i, upper, q, qd)
    }

    /// Whether joint `i`'s torque limit depends on its angle and velocity.
    pub(super) fn limit_varies(&self, i: usize) -> bool {
        self.spec.strength.as_ref().is_some_and(|s| s.varies(i)) && !self.spec.model.is_unactuated(i)
    }

    /// `qᵢ`, `q̇ᵢ` at node `k` for the control points last given to `set_x`.
    pub(super) fn joint_state(&self, k: usize, i: usize) -> (f64, f64) {
        let (b, nv) = (&self.nodes.basis[k], self.layout.nv);
        // q = Σₐ Bₐ cₐ, q̇ = Σₐ Ḃₐ cₐ
        (0..4).fold((0.0, 0.0), |(q, qd), a| {
            let c = self.ctrl[(b.first + a) * nv + i];
            (q + b.b[a] * c, qd + b.db[a] * c)
        })
    }

    /// Joint `i`'s torque limit at node `k` (N·m or N, a magnitude).
    pub(super) fn torque_limit_at_node(&self, k: usize, i: usize, upper: bool) -> f64 {
        let (q, qd) = self.joint_state(k, i);
        self.torque_limit(i, upper, q, qd).value
    }

    /// `vals −= ∂S/∂qᵢ Bₐ + ∂S/∂q̇ᵢ Ḃₐ` over a torque row's motion columns (eq. 33 for `−S(qᵢ, q̇ᵢ)`), the row
    /// supported on `dofs` (which hold `i`; see [`Transcription::chain_rule_on`]).
    pub(super) fn subtract_limit_slope(
        layout: &super::Layout,
        basis: &BasisAt,
        dofs: &[usize],
        i: usize,
        s: &Sloped,
        vals: &mut [f64],
    ) {
        let at = dofs.binary_search(&i).expect("a torque row's support holds its own DOF");
        let (motion_at, _) = super::node::supported_offsets(layout, basis.first, dofs.len());
        for (a, offset) in motion_at.iter().enumerate() {
            if let Some(offset) = offset {
                vals[offset + at] -= s.d1 * basis.b[a] + s.d2 * basis.db[a];
            }
        }
    }

    /// The factor `f = √(c_τ W_l + c_s/S²)` of the node residual `f τ_l` (torque and strength terms; the
    /// torque objective only), `S` the limit in the direction `τ_l` points to, with `∂f/∂q_l`, `∂f/∂q̇_l`.
    pub(super) fn torque_factor(&self, l: usize, positive: bool, q: f64, qd: f64) -> Sloped {
        let terms = &self.spec.terms;
        let bound = self.torque_limit(l, positive, q, qd);
        let usable = bound.value.is_finite() && bound.value > 0.0 && terms.strength > 0.0;
        let strength = if usable { terms.strength / (bound.value * bound.value) } else { 0.0 };
        let f = (terms.torque * self.spec.weights[l] + strength).sqrt();
        if !usable || f == 0.0 {
            return flat(f);
        }
        // ∂f/∂S = −c_s / (f S³)
        let df = -terms.strength / (f * bound.value.powi(3));
        Sloped { value: f, d1: df * bound.d1, d2: df * bound.d2 }
    }

    /// Whether the node residual's factor `f` depends on the state (strength term on varying limits).
    pub(super) fn factor_varies(&self, l: usize) -> bool {
        self.spec.terms.strength > 0.0 && self.limit_varies(l)
    }

    /// `∇φ` (`out`, `[∂/∂q, ∂/∂q̇, ∂/∂q̈, ∂/∂λ̃]`) gains the strength parts at the state in `work` (the active
    /// torques in `work.tau`): `ρ_l τ_l ∂f` and `−σ± ∂S±` (`ρ_l f ∂τ_l` is in the weights `ω̂`).
    pub(super) fn add_strength_gradient(&self, out: &mut [f64]) {
        let nv = self.layout.nv;
        let (w, h) = (&self.work, &self.hess);
        for l in 0..nv {
            let (q, qd) = (w.q[l], w.qd[l]);
            if h.rho[l] != 0.0 {
                // ρ f ∂τ is in ω̂ (`node_gradient.rs`); here ρ τ ∂f
                let f = self.torque_factor(l, h.positive[l], q, qd);
                let rt = h.rho[l] * w.tau[l];
                out[l] += rt * f.d1;
                out[nv + l] += rt * f.d2;
            }
            for (d, upper) in [(0, true), (1, false)] {
                if h.sigma[d][l] != 0.0 {
                    let s = self.torque_limit(l, upper, q, qd);
                    out[l] -= h.sigma[d][l] * s.d1;
                    out[nv + l] -= h.sigma[d][l] * s.d2;
                }
            }
        }
    }
}

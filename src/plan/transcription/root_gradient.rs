//! `∇φₖ` of a free body's node (`root.rs`) by contracted passes of the engine, O(nv) each, for the
//! second-order term (`hessian.rs`). With `G = H_jr H_rr⁻¹`, `u = Gᵀω̂_j`, the weights `ω̃ = [−u; ω̂_j]` (root
//! DOFs first here, in `q` order in the code), `y = H_rr⁻¹ τ_r`, `ỹ = [y; 0]` and the root rows' weights `ŵ`:
//!
//! ```text
//!   φ = ω̂_jᵀ τ_j* + ŵ · rows,     τ_j* = τ_j − G τ_r
//!   ∇(ω̂_jᵀ τ_j*) = ∇(ω̃ᵀτ)|_ω̃ − [along q] ∇_q(ω̃ᵀ H(q) ỹ)|_{ω̃, ỹ}      (∂(Gτ_r)/∂q at fixed τ_r = D_j − G D_r)
//!   rows = τ_r (held):      ∇(ŵ · τ_r) = ∇(ŵᵀτ)            — ŵ joins ω̃ in the first pass
//!   rows = (H q̇)_r (free):  ∂/∂q = ∇_q(ŵᵀ H(q) q̇),   ∂/∂q̇ = H ŵ
//! ```
//!
//! `ωᵀ H(q) a` is inverse dynamics at zero velocity and gravity contracted with `ω`: its gradient is one more
//! contracted pass at `(q, 0, a)` ([`rnea_gradient_placed`]), whose `∂/∂q̈` is `H ω`. So a node's gradient
//! costs a CRBA (for `G` and `H_rr`, once per `q`) and two or three contracted passes, where the projection
//! of `root.rs` costs two full derivative passes and O(nv²) per node — and the second-order term takes
//! `2·nv` gradients per node.

use super::Transcription;
use crate::dynamics::{crba::crba, rnea_gradient::rnea_gradient_placed};
use crate::spatial::{Motion, Vec3};
use nalgebra::Vector6;

impl Transcription<'_> {
    /// `∇φ` of a free body at the state in `self.work` into `out` (as [`Self::node_gradient`]; `τ*` into
    /// `work.tau`). `placed`: `work.q` is that of the last call, whose `G` and `H_rr` hold. Falls back to
    /// the projected derivative matrices if `H_rr` is singular.
    pub(super) fn free_node_gradient(&mut self, out: &mut [f64], placed: bool) {
        let nv = self.layout.nv;
        let cached = placed && self.free.root_factor.is_some();
        if !cached && !self.free_inertia() {
            return self.node_gradient_of_rows(out);
        }
        self.free_weights();
        // ∇(ω̃ᵀτ) (+ ŵᵀτ when the rows are the root's forces), τ with passive torques, loads and contacts
        let first = std::mem::take(&mut self.free.omega_first);
        self.contracted_gradient(out, super::node_gradient::Pass::Full { placed: true }, &first, &Motion::ZERO);
        self.free.omega_first = first;
        let (model, w, data, f) = (&self.spec.model, &mut self.work, &mut self.data, &mut self.free);
        let r = &f.dofs;
        // y = H_rr⁻¹ τ_r;  τ_j* = τ_j − G_j τ_r, the root's 0
        let tau_r = Vector6::from_fn(|m, _| w.tau[r[m]]);
        let y = f.root_factor.as_ref().expect("factored above").solve(&tau_r);
        for j in (0..nv).filter(|j| !r.contains(j)) {
            w.tau[j] -= Vector6::from_row_slice(&f.g[j * 6..j * 6 + 6]).dot(&tau_r);
        }
        r.iter().zip(y.iter()).for_each(|(&ra, &ym)| (w.tau[ra], f.y_tilde[ra]) = (0.0, ym));
        // ∂/∂q −= ∇_q(ω̃ᵀ H(q) ỹ)
        let [p_q, p_v, p_a] = &mut f.pass;
        let zero_g = Vec3::zeros();
        let at = (&w.q[..], &f.zeros[..], &f.y_tilde[..]);
        rnea_gradient_placed(model, data, at, &zero_g, None, &f.omega_tilde, &Motion::ZERO, (p_q, p_v, p_a));
        out[..nv].iter_mut().zip(p_q.iter()).for_each(|(o, d)| *o -= d);
        // The momenta: ∂/∂q += ∇_q(ŵᵀ H(q) q̇), ∂/∂q̇ += H ŵ
        if f.conserved && self.hess.root_w.iter().any(|w| *w != 0.0) {
            f.omega_first.fill(0.0);
            r.iter().zip(&self.hess.root_w).for_each(|(&ra, &wm)| f.omega_first[ra] = wm);
            let at = (&w.q[..], &f.zeros[..], &w.qd[..]);
            rnea_gradient_placed(model, data, at, &zero_g, None, &f.omega_first, &Motion::ZERO, (p_q, p_v, p_a));
            out[..nv].iter_mut().zip(p_q.iter()).for_each(|(o, d)| *o += d);
            out[nv..2 * nv].iter_mut().zip(p_a.iter()).for_each(|(o, d)| *o += d);
        }
        if self.spec.strength.is_some() {
            self.add_strength_gradient(out);
        }
    }

    /// `H(q)` by the CRBA, `H_rr`'s factor and `G = H_jr H_rr⁻¹` at `work.q`; `false` if `H_rr` is singular.
    fn free_inertia(&mut self) -> bool {
        let h = crba(&self.spec.model, &mut self.data, &self.work.q);
        self.free.factor_root(h).is_some()
    }

    /// `ω̃ = [−Gᵀω̂_j; ω̂_j]` into `free.omega_tilde`, and the first pass's weights into `free.omega_first`:
    /// `ω̃`, plus the root rows' weights where they are the root's forces.
    fn free_weights(&mut self) {
        let (f, h) = (&mut self.free, &self.hess);
        let r = &f.dofs;
        f.omega_tilde.copy_from_slice(&h.omega_hat);
        let mut u = Vector6::zeros();
        for j in (0..h.omega_hat.len()).filter(|j| !r.contains(j)) {
            u += Vector6::from_row_slice(&f.g[j * 6..j * 6 + 6]) * h.omega_hat[j];
        }
        for (m, &ra) in r.iter().enumerate() {
            f.omega_tilde[ra] = -u[m];
        }
        f.omega_first.copy_from_slice(&f.omega_tilde);
        if !f.conserved {
            r.iter().zip(&h.root_w).for_each(|(&ra, &wm)| f.omega_first[ra] += wm);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::Transcription;
    use crate::plan::task::Task;
    use crate::solve::Problem;

    const FLOATING: &str = "[model]\nhuman = \"whole_body\"\nroot = \"free\"\n[motion]\nduration = 2.0\nstart = {}\n\
        goal = { r_shoulder_y = -40.0, lumbar_z = -10.0 }\n[environment]\ngravity = \"space\"\n\
        [discretization]\ncontrol_points = 7\n";
    const HELD: &str = "[model]\nhuman = \"whole_body\"\nroot = \"free\"\n[motion]\nduration = 1.0\nstart = {}\n\
        goal = {}\n[environment]\ngravity = \"earth\"\n[[environment.payload]]\nframe = \"l_hand\"\nmass = 3.0\n\
        [[constraints.contact]]\nframe = \"r_hand\"\ntype = \"point\"\n[discretization]\ncontrol_points = 7\n";

    /// The contracted gradient of a free body's node against the projected derivative matrices of
    /// `root.rs` (`node_gradient_of_rows`, its reference) on the 3D whole body — floating (momentum rows),
    /// and held by a hand under gravity with a payload (force rows, contact forces): the same gradient and
    /// torques to rounding at every node, for random states and weights.
    #[test]
    fn contracted_free_body_gradient_matches_the_projected_one() {
        let mut seed = 7u64;
        let mut random = move |lo: f64, hi: f64| {
            seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            lo + (hi - lo) * ((seed >> 11) as f64 / (1u64 << 53) as f64)
        };
        for text in [FLOATING, HELD] {
            let task = Task::parse(text, std::path::Path::new("free.toml")).unwrap();
            let mut t = Transcription::new(&task.spec).unwrap();
            assert_eq!(t.free.dofs.len(), 6);
            let (nv, nl) = (t.layout.nv, t.layout.n_lambda);
            let x: Vec<f64> = (0..t.dims().n).map(|_| random(-0.6, 0.6)).collect();
            t.set_x(&x);
            let (mut contracted, mut projected) = (vec![0.0; 3 * nv + nl], vec![0.0; 3 * nv + nl]);
            for k in 0..t.n_nodes() {
                t.node_state(k);
                t.hess.omega.iter_mut().for_each(|o| *o = random(-2.0, 2.0));
                t.hess.root_w.iter_mut().for_each(|w| *w = random(-2.0, 2.0));
                t.node_gradient(&mut contracted, crate::plan::transcription::node_gradient::Pass::Full { placed: false });
                let tau = t.work.tau.clone();
                t.node_state(k);
                t.node_gradient_of_rows(&mut projected);
                let scale = projected.iter().fold(1.0f64, |m, v| m.max(v.abs()));
                for (i, (a, b)) in contracted.iter().zip(&projected).enumerate() {
                    assert!((a - b).abs() < 1e-10 * scale, "node {k}, entry {i}: contracted {a}, projected {b}");
                }
                for (a, b) in tau.iter().zip(&t.work.tau) {
                    assert!((a - b).abs() < 1e-10 * scale, "node {k}: τ* {a} against {b}");
                }
            }
        }
    }
}

//! The node Hessian's blocks that need no differences (`hessian.rs`): on a fixed base the engine's whole
//! `∇²φ` (`dynamics::rnea_hessian`) and the loads' and contact forces' terms
//! (`dynamics::point_force`); on a free figure its `q̇`–`q̇` block (`dynamics::rnea_velocity_hessian`), and
//! its translations' columns, which are zero.

use super::Transcription;
use crate::dynamics::kinematics;
use crate::dynamics::point_force::{point_force_hessian, point_force_mixed};
use crate::dynamics::rnea_hessian::rnea_hessian;
use crate::dynamics::rnea_velocity_hessian::rnea_velocity_hessian;
use crate::spatial::{Motion, Vec3};

impl Transcription<'_> {
    /// Whether each node's Hessian takes the engine's exact blocks where they apply
    /// (`dynamics::rnea_velocity_hessian`, `dynamics::rnea_hessian`; the default) or differences the
    /// exact gradient along every `qⱼ` and `q̇ⱼ` (the reference the tests and `benches/second_order.rs`
    /// compare them with).
    pub fn set_exact_node_blocks(&mut self, on: bool) {
        self.hess.exact_blocks = on;
    }

    /// Whether `qⱼ` translates a free figure as a whole (its root's prismatic joints): the node's `φ` does not
    /// depend on it (joint torques, the root rows' forces and momenta about the root's own axes, point forces of
    /// fixed directions and uniform gravity do not change when everything moves by the same offset; a free
    /// figure has no balance rows), so its column of `∇²φ` is zero.
    pub(super) fn moves_the_whole_figure(&self, j: usize) -> bool {
        j < self.layout.nv
            && self.free.dofs.contains(&j)
            && self.spec.model.joints[j + 1].kind == crate::model::JointKind::Prismatic
    }

    /// Whether `∂²φ/∂q̇²` is the engine's exact block ([`rnea_velocity_hessian`]) after the node's base pass:
    /// the weights `ω̂` do not depend on the state (no strength terms), so that `φ = ω̂ᵀτ + ω_W·W` with `τ`'s
    /// other parts (passive torques, loads, contact forces) at most linear in `q̇`; for a free body the
    /// contracted gradient was used (`H_rr` regular: `root_gradient.rs`), whose `q̇` dependence is `ω̃ᵀτ` at
    /// weights `ω̃` of `q` alone (its root rows' momenta `H q̇` are linear).
    pub(super) fn velocity_block_exact(&self) -> bool {
        let contracted = self.free.dofs.is_empty() || self.free.root_factor.is_some();
        self.hess.exact_blocks && contracted && self.spec.strength.is_none() && self.hess.rho.iter().all(|r| *r == 0.0)
    }

    /// Whether the `q` columns are the engine's exact blocks ([`rnea_hessian`], and
    /// [`point_force_hessian`] for the loads and contact forces) too: a fixed-base tree and the velocity block
    /// exact.
    pub(super) fn position_blocks_exact(&self) -> bool {
        self.free.dofs.is_empty() && self.velocity_block_exact()
    }

    /// The node's whole `∇²φ` over `(q, q̇, q̈)` in `hess.s` from [`rnea_hessian`] at the node's base pass (in
    /// `data`), with its weights `ω̂`, `u₀ = ω_W`, and the loads' and contact forces' terms.
    pub(super) fn add_exact_blocks(&mut self) {
        let d = 3 * self.layout.nv + self.layout.n_lambda;
        let u0 = self.hess.root_weight();
        let h = &mut self.hess;
        rnea_hessian(&self.spec.model, &self.data, (&h.omega_hat, &u0), &mut h.velocity, &mut h.s, d);
        self.add_point_force_blocks(&u0);
    }

    /// The loads' and contact forces' part of the `q` columns: `φ_f = −Ψ_b·[p × f; f]` of each
    /// ([`point_force_hessian`]; `Ψ_b = u₀ + Σ_path ω̂ᵢSᵢ`), and each contact force component's `λ` row
    /// ([`point_force_mixed`]), at the base pass's placements.
    fn add_point_force_blocks(&mut self, u0: &Motion) {
        let (spec, nv) = (self.spec, self.layout.nv);
        let d = 3 * nv + self.layout.n_lambda;
        let (data, h, w) = (&self.data, &mut self.hess, &self.work);
        let psi = |path: &[usize]| path.iter().fold(*u0, |u, &i| u.add_scaled(&data.S[i + 1], h.omega_hat[i]));
        for (l, load) in spec.loads.iter().enumerate() {
            let p = kinematics::frame_placement(&spec.model, data, load.frame).translation;
            let path = &self.load_paths[l];
            point_force_hessian(data, path, (&p, &load.force), &psi(path), &mut h.s, d);
        }
        for (c, contact) in spec.contacts.iter().enumerate() {
            let info = &self.contacts[c];
            let p = kinematics::frame_placement(&spec.model, data, contact.frame).translation;
            let f = info.directions.iter().enumerate().fold(Vec3::zeros(), |f, (m, e)| f + e * w.lambda[info.offset + m]);
            let psi_b = psi(&info.path);
            point_force_hessian(data, &info.path, (&p, &f), &psi_b, &mut h.s, d);
            for (m, e) in info.directions.iter().enumerate() {
                let row = 3 * nv + info.offset + m;
                let column = &mut h.row[..nv];
                column.fill(0.0);
                point_force_mixed(data, &info.path, (&p, e), &psi_b, column);
                for (k, v) in column.iter().enumerate() {
                    h.s[row * d + k] += v;
                    h.s[k * d + row] += v;
                }
            }
        }
    }

    /// The `q̇`–`q̇` block of a free figure's `hess.s` from [`rnea_velocity_hessian`] at the placements of the
    /// node's first pass (in `data`), with its weights `ω̃` (plus the root rows' where they are its forces:
    /// `root_gradient.rs`), `u₀ = 0` (a fixed base takes [`Self::add_exact_blocks`]).
    pub(super) fn add_velocity_block(&mut self) {
        let nv = self.layout.nv;
        let d = 3 * nv + self.layout.n_lambda;
        let (f, h) = (&self.free, &mut self.hess);
        h.velocity_weights.copy_from_slice(&f.omega_tilde);
        if !f.conserved {
            f.dofs.iter().zip(&h.root_w).for_each(|(&r, &w)| h.velocity_weights[r] += w);
        }
        let block = &mut h.s[nv * d + nv..];
        rnea_velocity_hessian(&self.spec.model, &self.data, (&h.velocity_weights, &Motion::ZERO), &mut h.velocity, block, d);
    }
}

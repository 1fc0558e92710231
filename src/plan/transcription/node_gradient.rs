//! `∇φₖ` of one node's weighted torques (`hessian.rs`), at the state in `work`, without the node's
//! derivative matrices: one contracted pass of the engine ([`rnea_gradient`], O(nv)) and the contracted
//! derivatives of the loads and contact forces on their paths,
//!
//! ```text
//!   φ = Σ_l ω̂_l τ_l + ω_W · W,    τ = ID(q, q̇, q̈) − τ_passive − Σ Jᵀf,   W = W_ID − Σ [p × f; f],
//!   ω̂_l = ω_l + ρ_l f_l(q_l, q̇_l)                  (the strength residuals' varying factor, `strength.rs`)
//!   ∇φ = ∇(ω̂ᵀτ_ID + ω_W·W_ID) + ω̂ᵢ [kᵢ; dᵢ] − Σ_f ω̂ᵀ ∂(Jᵀf) − ω_W · ∂[p×f; f] + Σ_l ρ_l τ_l ∇f_l − σ± ∇S±
//! ```
//!
//! (`kᵢ`, `dᵢ` the passive stiffness and damping; the `λ̃` columns `∂φ/∂λ̃_m = −(Σᵢ ω̂ᵢ Sᵢ + ω_W) · [p × e_m; e_m]`).

use super::Transcription;
use crate::dynamics::point_force::{add_generalized_force, generalized_force_derivative};
use crate::dynamics::rnea_gradient::{rnea_gradient, rnea_gradient_placed};
use crate::dynamics::rnea_gradient_moved::{keep_as_base, rnea_gradient_moved, Moved};
use crate::dynamics::{kinematics, Data};
use crate::spatial::{Force, Motion, Vec3};

/// How [`Transcription::node_gradient`] runs the engine's pass.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Pass {
    /// The whole tree; `placed`: the engine's placements are those of `work.q` already.
    Full { placed: bool },
    /// The whole tree, kept (with its gradient) as the base of the moved passes that follow (`hess.base`).
    Base,
    /// Only what moving `q_j` or `q̇_j` from the base state changes ([`rnea_gradient_moved`]; a fixed-base
    /// tree). The caller restores `data` afterwards.
    Moved(usize, Moved),
}

impl Transcription<'_> {
    /// `∇φ` at the state in `self.work` into `out`: `[∂/∂q, ∂/∂q̇, ∂/∂q̈, ∂/∂λ̃]`. Leaves the active torque
    /// in `work.tau`.
    pub(super) fn node_gradient(&mut self, out: &mut [f64], pass: Pass) {
        self.effective_weights();
        if !self.free.dofs.is_empty() {
            return self.free_node_gradient(out, pass == Pass::Full { placed: true });
        }
        let u0 = self.hess.root_weight();
        let omega = std::mem::take(&mut self.hess.omega_hat);
        self.contracted_gradient(out, pass, &omega, &u0);
        self.hess.omega_hat = omega;
        if self.spec.strength.is_some() {
            self.add_strength_gradient(out);
        }
    }

    /// `∇(ωᵀτ + u₀·W)` at the state in `self.work` into `out` for given weights `ω` (nv) and `u₀`, `τ` the
    /// torques with the passive ones, loads and contact forces (module docs; no strength terms); `τ` into
    /// `work.tau`; `pass` as in [`Self::node_gradient`].
    pub(super) fn contracted_gradient(&mut self, out: &mut [f64], pass: Pass, omega: &[f64], u0: &Motion) {
        let (spec, nv) = (self.spec, self.layout.nv);
        let (w, data, h) = (&mut self.work, &mut self.data, &mut self.hess);
        out.fill(0.0);
        // ∇(ωᵀτ_ID + u₀·W_ID), and τ = τ_ID
        let z = (&w.q[..], &w.qd[..], &w.qdd[..]);
        if let Pass::Moved(..) = pass {
            out[..3 * nv].copy_from_slice(&h.base_gradient);
        }
        let (g_q, rest) = out.split_at_mut(nv);
        let (g_v, rest) = rest.split_at_mut(nv);
        let (g_a, g_l) = rest.split_at_mut(nv);
        let (model, gravity) = (&spec.model, &spec.gravity);
        match pass {
            Pass::Full { placed: true } => rnea_gradient_placed(model, data, z, gravity, None, omega, u0, (g_q, g_v, g_a)),
            Pass::Full { placed: false } | Pass::Base => rnea_gradient(model, data, z, gravity, None, omega, u0, (g_q, g_v, g_a)),
            Pass::Moved(j, moved) => {
                let engine = (&h.base, &mut *data);
                rnea_gradient_moved(model, engine, z, None, (omega, u0), (j, moved, &h.subtrees), (g_q, g_v, g_a))
            }
        }
        if pass == Pass::Base {
            keep_as_base(data, &mut h.base);
            for (k, g) in [&*g_q, &*g_v, &*g_a].into_iter().enumerate() {
                h.base_gradient[k * nv..(k + 1) * nv].copy_from_slice(g);
            }
        }
        w.tau.copy_from_slice(data.tau.as_slice());
        // τ −= τ_passive(q, q̇) = −k(q − q₀) − d q̇:  ∂φ/∂qᵢ += ωᵢ kᵢ, ∂φ/∂q̇ᵢ += ωᵢ dᵢ
        for i in 0..nv {
            let p = &spec.model.joints[i + 1].passive;
            w.tau[i] -= p.torque(w.q[i], w.qd[i]);
            g_q[i] += omega[i] * p.stiffness;
            g_v[i] += omega[i] * p.damping;
        }
        for (l, load) in spec.loads.iter().enumerate() {
            let p = kinematics::frame_placement(&spec.model, data, load.frame).translation;
            let path = &self.load_paths[l];
            world_force_gradient(data, path, &p, &load.force, (omega, u0), &mut w.scratch, g_q, &mut w.tau);
        }
        for (c, contact) in spec.contacts.iter().enumerate() {
            let info = &self.contacts[c];
            let p = kinematics::frame_placement(&spec.model, data, contact.frame).translation;
            let f = info.directions.iter().enumerate().fold(Vec3::zeros(), |f, (m, e)| f + e * w.lambda[info.offset + m]);
            world_force_gradient(data, &info.path, &p, &f, (omega, u0), &mut w.scratch, g_q, &mut w.tau);
            // ∂φ/∂λ̃_m = −(Σ_{i on the path} ωᵢ Sᵢ + u₀) · [p × e_m; e_m]
            let weight = info.path.iter().fold(*u0, |u, &i| u.add_scaled(&data.S[i + 1], omega[i]));
            for (m, e) in info.directions.iter().enumerate() {
                g_l[info.offset + m] = -weight.dot(&Force::new(p.cross(e), *e));
            }
        }
    }

    /// `∇φ` from the node's torque rows, for a free body (the derivative matrices of `eval_state` projected,
    /// `root.rs`: O(nv²) a pass; [`Self::free_node_gradient`] is the contracted one, and this its reference):
    /// `Σ_l ω̂_l ∇τ_l + Σᵢ w_pᵢ ∇pᵢ` (the root's rows, momenta or forces), plus the strength terms (a free figure has
    /// no balance, `ω_W = 0`).
    pub(super) fn node_gradient_of_rows(&mut self, out: &mut [f64]) {
        let (nv, nl) = (self.layout.nv, self.layout.n_lambda);
        self.eval_state(true);
        out.fill(0.0);
        let (w, h) = (&self.work, &self.hess);
        for l in (0..nv).filter(|&l| h.omega_hat[l] != 0.0) {
            let o = h.omega_hat[l];
            for c in 0..nv {
                out[c] += o * w.dq[l * nv + c];
                out[nv + c] += o * w.dv[l * nv + c];
                out[2 * nv + c] += o * w.da[l * nv + c];
            }
            for m in 0..nl {
                out[3 * nv + m] += o * w.dl[l * nl + m];
            }
        }
        for (m, &wp) in h.root_w.iter().enumerate().filter(|(_, w)| **w != 0.0) {
            let d = self.free.row_derivatives(m, nv, nl);
            for c in 0..nv {
                out[c] += wp * d.q[c];
                out[nv + c] += wp * d.v[c];
                out[2 * nv + c] += wp * d.a[c];
            }
            for (c, v) in d.lambda.into_iter().flatten().enumerate() {
                out[3 * nv + c] += wp * v;
            }
        }
        if self.spec.strength.is_some() {
            self.add_strength_gradient(out);
        }
    }

    /// `ω̂ = ω + ρ f(q, q̇)` at the state in `work` into `hess.omega_hat`.
    fn effective_weights(&mut self) {
        for l in 0..self.layout.nv {
            let rho = self.hess.rho[l];
            let varying = if rho != 0.0 {
                rho * self.torque_factor(l, self.hess.positive[l], self.work.q[l], self.work.qd[l]).value
            } else {
                0.0
            };
            self.hess.omega_hat[l] = self.hess.omega[l] + varying;
        }
    }
}

/// A world-fixed force `f` at the world point `p` of the body whose root path is `path`: `τ −= Jᵀf`, and
/// `g_q −= ω̂ᵀ ∂(Jᵀf)/∂q + ω_W · ∂[p × f; f]/∂q` (`∂p/∂q_k = S_k,ω × p + S_k,v`). `scratch` holds `|path|²`.
#[allow(clippy::too_many_arguments)]
fn world_force_gradient(
    data: &Data,
    path: &[usize],
    p: &Vec3,
    f: &Vec3,
    (omega_hat, u0): (&[f64], &Motion),
    scratch: &mut [f64],
    g_q: &mut [f64],
    tau: &mut [f64],
) {
    let m = path.len();
    add_generalized_force(data, path, p, &(-f), tau);
    generalized_force_derivative(data, path, p, f, &mut scratch[..m * m]);
    for (c, &kc) in path.iter().enumerate() {
        let s = &data.S[kc + 1];
        let p_dot = s.w.cross(p) + s.v;
        let torques: f64 = path.iter().enumerate().map(|(r, &kr)| omega_hat[kr] * scratch[r * m + c]).sum();
        g_q[kc] -= torques + u0.w.dot(&p_dot.cross(f));
    }
}

//! The velocity block `∂²φ/∂q̇²` of the Hessian of one weighted sum of the joint torques and the root wrench,
//!
//! ```text
//!   φ(q, q̇, q̈) = ωᵀτ + u₀ · W,        τ = ID(q, q̇, q̈),  W = F₀ the root reaction wrench,
//! ```
//!
//! exactly and in O(n·depth), for a fixed-base tree with one DOF per joint (world frame, as
//! [`super::rnea_gradient`]). Summing the torques over the bodies, `φ = Σ_b Ψ_b · f_b` with
//! `Ψ_b = u₀ + Σ_{i ⪯ b} ωᵢ Sᵢ` (a motion) and `f_b = I_b a_b + v_b ×* I_b v_b`. At a fixed `q` the only
//! terms of second order in `q̇` are the velocity product of the acceleration,
//! `a_b ∋ Σ_{k ≺ j ⪯ b} (S_k × S_j) q̇_k q̇_j` (from `Ṡⱼ = v_λ(j) × Sⱼ`), and the gyroscopic force with
//! `v_b = Σ_{m ⪯ b} S_m q̇_m`. With the subtree sums
//!
//! ```text
//!   P_n = Σ_{b ⪰ n} I_b Ψ_b  (a force),     K_n = Σ_{b ⪰ n} crm(Ψ_b)ᵀ I_b  (6×6; Ψ · (x ×* I y) = xᵀ crm(Ψ)ᵀ I y)
//! ```
//!
//! the entries for `m ⪯ n` (`m` an ancestor of `n`, or `n` itself) are
//!
//! ```text
//!   ∂²φ/∂q̇_m∂q̇_n = S_m · (K_n + K_nᵀ) S_n  +  [m ≺ n] P_n · (S_m × S_n),
//! ```
//!
//! and zero for joints on different branches. Everything else in `φ` is at most linear in `q̇` (the passive
//! damping, the loads and contact forces do not depend on it). The planner's exact second-order term
//! (`plan/transcription/hessian.rs`) takes this block instead of differencing `∇φ` along each `q̇ⱼ`.

use super::Data;
use crate::model::Model;
use crate::spatial::{motion_cross_matrix, Force, Mat6, Motion};

/// Scratch of [`rnea_velocity_hessian`] and [`super::rnea_hessian`], allocated once per model: each
/// body's `Ψ_b` and the subtree sums `P`, `K` (and `Q` of the position blocks).
#[derive(Clone, Debug)]
pub struct VelocityHessianWork {
    pub(super) psi: Vec<Motion>,
    pub(super) p: Vec<Force>,
    pub(super) q: Vec<Force>,
    pub(super) k: Vec<Mat6>,
}

impl VelocityHessianWork {
    /// Scratch for the bodies of `model`.
    pub fn new(model: &Model) -> Self {
        let nb = model.bodies.len();
        VelocityHessianWork {
            psi: vec![Motion::ZERO; nb],
            p: vec![Force::ZERO; nb],
            q: vec![Force::ZERO; nb],
            k: vec![Mat6::zeros(); nb],
        }
    }
}

/// `Ψ_b = Ψ_λ(b) + ω_b S_b` (`Ψ₀ = u₀`) and the subtree sums `P_n = Σ_{b ⪰ n} I_b Ψ_b`,
/// `K_n = Σ_{b ⪰ n} crm(Ψ_b)ᵀ I_b`, with `velocities` also `Q_n = Σ_{b ⪰ n} B_bᵀ Ψ_b`
/// (`B_bᵀΨ = v_b ×* I_bΨ − Ψ ×* I_b v_b + I_b(Ψ × v_b)`: `Ψ·B_b x = x·B_bᵀΨ`; `data.v` read), leaves first.
pub(super) fn weighted_sums(
    model: &Model,
    data: &Data,
    (omega, u0): (&[f64], &Motion),
    work: &mut VelocityHessianWork,
    velocities: bool,
) {
    let (nv, nb) = (model.nv(), model.bodies.len());
    assert!(nb == nv + 1 && omega.len() == nv && work.psi.len() == nb, "one DOF per body and matching sizes");
    work.p.fill(Force::ZERO);
    work.q.fill(Force::ZERO);
    work.k.fill(Mat6::zeros());
    work.psi[0] = *u0;
    for b in 1..nb {
        work.psi[b] = work.psi[model.joints[b].parent].add_scaled(&data.S[b], omega[b - 1]);
    }
    for b in (1..nb).rev() {
        let (psi, inertia) = (work.psi[b], &data.oI[b]);
        work.p[b] += inertia.mul(&psi);
        work.k[b] += motion_cross_matrix(&psi).transpose() * inertia.matrix();
        if velocities {
            let v = data.v[b];
            work.q[b] += v.cross_force(&inertia.mul(&psi)) - psi.cross_force(&inertia.mul(&v)) + inertia.mul(&psi.cross(&v));
        }
        let parent = model.joints[b].parent;
        if parent > 0 {
            let (p, q, k) = (work.p[b], work.q[b], work.k[b]);
            work.p[parent] += p;
            work.q[parent] += q;
            work.k[parent] += k;
        }
    }
}

/// `∂²φ/∂q̇²` (module docs) at the placements in `data` (by [`super::kinematics::placements`] or any pass at
/// this `q`: `data.S` and `data.oI` are read) into `out[m·stride + n]`, `m, n < nv` (every entry written).
/// Needs a fixed-base tree with one DOF per joint (a free root's six joints count as six).
pub fn rnea_velocity_hessian(
    model: &Model,
    data: &Data,
    weights: (&[f64], &Motion),
    work: &mut VelocityHessianWork,
    out: &mut [f64],
    stride: usize,
) {
    let nv = model.nv();
    assert!(stride >= nv && out.len() >= (nv - 1) * stride + nv, "out holds an nv × nv block with this stride");
    weighted_sums(model, data, weights, work, false);
    velocity_block(model, data, work, out, stride);
}

/// The block of [`rnea_velocity_hessian`] from the sums in `work` ([`weighted_sums`] at these placements).
pub(super) fn velocity_block(model: &Model, data: &Data, work: &VelocityHessianWork, out: &mut [f64], stride: usize) {
    let nv = model.nv();
    for m in 0..nv {
        out[m * stride..m * stride + nv].fill(0.0);
    }
    for n in 1..=nv {
        let s_n = data.S[n];
        // w_n = (K_n + K_nᵀ) S_n
        let (k, s) = (&work.k[n], s_n.to_vec6());
        let w_n = Force::from_vec6(&(k * s + k.transpose() * s));
        let mut m = n;
        while m > 0 {
            let s_m = data.S[m];
            // S_m · (K_n + K_nᵀ) S_n  +  [m ≺ n] P_n · (S_m × S_n)
            let mut h = s_m.dot(&w_n);
            if m != n {
                h += s_m.cross(&s_n).dot(&work.p[n]);
            }
            out[(m - 1) * stride + n - 1] = h;
            out[(n - 1) * stride + m - 1] = h;
            m = model.joints[m].parent;
        }
    }
}

//! The Hessian, by its `q` columns, of one weighted sum of the joint torques and the root wrench,
//! `∂²φ/∂q∂q`, `∂²φ/∂q̇∂q` and `∂²φ/∂q̈∂q` of
//!
//! ```text
//!   φ(q, q̇, q̈) = ωᵀτ + u₀ · W,        τ = ID(q, q̇, q̈) without external forces,
//! ```
//!
//! exactly and in O(n·depth), for a tree with one DOF per joint (world frame, as [`super::rnea_gradient`]).
//! The gradient of that module reads, with `Ψ_b = u₀ + Σ_{i ⪯ b} ωᵢSᵢ`, `U_k = Ψ_λ(k)` and the subtree sums
//! `F_k = Σ f_b`, `P_k = Σ I_bΨ_b`, `Q_k = Σ B_bᵀΨ_b` (`b ⪰ k`; [`super::rnea_velocity_hessian`]),
//!
//! ```text
//!   ∂φ/∂q_k = (U_k × S_k)·F_k + A_k·P_k + Ṡ_k·Q_k,     ∂φ/∂q̇_k = 2Ṡ_k·P_k + S_k·Q_k,     ∂φ/∂q̈_k = S_k·P_k.
//! ```
//!
//! Moving `q_m` turns the subtree of `m` about `S_m`. Every one of these scalars is a product of world-frame
//! vectors, unchanged when all of them turn together, so its derivative is what the turn leaves out: the
//! parts fixed above `m`. For a row `k` in the subtree of `m` (`m ≺ k`) those are, with `ψ_m = U_m × S_m`,
//!
//! ```text
//!   δΨ_b = δU_k = ψ_m,   δv_b = Ṡ_m,   δa_b = A_m + Ṡ_m × v_b,   δṠ_k = Ṡ_m × S_k,   δP_k = Y_k ψ_m,
//!   δQ_k = B_kᵀ ψ_m + Ṡ_m ×* P_k + (K_k + K_kᵀ) Ṡ_m,     (K_k = Σ_{b ⪰ k} crm(Ψ_b)ᵀ I_b)
//! ```
//!
//! and for a row `k ⪯ m` only the sums change, by the derivative of their subtree-of-`m` part,
//!
//! ```text
//!   ∂F = S_m ×* F_m + Y_m A_m + B_m Ṡ_m,   ∂P = S_m ×* P_m + Y_m ψ_m,   ∂Q = S_m ×* Q_m + δQ_m.
//! ```
//!
//! So, `k ⪯ m`: `∂²φ/∂q_k∂q_m = (U_k × S_k)·∂F + A_k·∂P + Ṡ_k·∂Q`, `∂²φ/∂q̇_k∂q_m = 2Ṡ_k·∂P + S_k·∂Q`,
//! `∂²φ/∂q̈_k∂q_m = S_k·∂P`; `m ≺ k`: `∂²φ/∂q̇_k∂q_m = 2(Ṡ_m × S_k)·P_k + 2Ṡ_k·Y_kψ_m + S_k·δQ_k`,
//! `∂²φ/∂q̈_k∂q_m = S_k·Y_kψ_m` (the `q`–`q` entries by symmetry). Joints on different branches give zero.
//! The planner's exact second-order term (`plan/transcription/hessian.rs`) takes these blocks instead of
//! differencing `∇φ` along each `q_m` where the node has a fixed base and no strength terms; the loads and
//! contact forces, which do not turn with the bodies, add their own terms ([`super::point_force::point_force_hessian`]).

use super::rnea_velocity_hessian::{velocity_block, weighted_sums, VelocityHessianWork};
use super::Data;
use crate::model::Model;
use crate::spatial::{Force, Motion};

/// The whole `∇²φ` over `z = (q, q̇, q̈)` at the state of the last [`super::rnea_gradient::rnea_gradient`]
/// pass in `data` (its placements, velocities, `A`, `Ṡ`, `U` and composites `F`, `Y`, `B_ww`, `p` are read;
/// no external forces) with the same `weights`, into the `3nv × 3nv` row-major `out` of row length `stride`
/// (every entry written), the sums formed once: the `q` columns and rows (module docs), the `q̇`–`q̇` block
/// of [`super::rnea_velocity_hessian`], and zero `q̈`–`q̇`, `q̈`–`q̈` blocks (`τ` is linear in `q̈` and
/// `∂τ/∂q̈ = H(q)` does not depend on `q̇`).
pub fn rnea_hessian(
    model: &Model,
    data: &Data,
    weights: (&[f64], &Motion),
    work: &mut VelocityHessianWork,
    out: &mut [f64],
    stride: usize,
) {
    let nv = model.nv();
    assert!(stride >= 3 * nv && out.len() >= (3 * nv - 1) * stride + 3 * nv, "out holds the 3nv × 3nv blocks");
    weighted_sums(model, data, weights, work, true);
    position_blocks(model, data, work, out, stride);
    velocity_block(model, data, work, &mut out[nv * stride + nv..], stride);
    for r in nv..3 * nv {
        let first = if r < 2 * nv { 2 * nv } else { nv };
        out[r * stride + first..r * stride + 3 * nv].fill(0.0);
    }
}

/// The `q` columns and rows of [`rnea_hessian`] from the sums in `work` ([`weighted_sums`] with `Q`).
fn position_blocks(model: &Model, data: &Data, work: &VelocityHessianWork, out: &mut [f64], stride: usize) {
    let nv = model.nv();
    for r in 0..3 * nv {
        out[r * stride..r * stride + nv].fill(0.0);
        if r < nv {
            out[r * stride + nv..r * stride + 3 * nv].fill(0.0);
        }
    }
    let mut put = |row: usize, col: usize, h: f64| {
        out[row * stride + col] = h;
        out[col * stride + row] = h;
    };
    for m in 1..=nv {
        let (d_f, d_p, d_q) = moved_sums(data, work, m);
        // Rows k ⪯ m: only the sums change.
        let mut k = m;
        while k > 0 {
            let (s_k, sdot_k) = (data.S[k], data.Sdot[k]);
            let u_k = data.Uw[k].cross(&s_k);
            put(k - 1, m - 1, u_k.dot(&d_f) + data.A[k].dot(&d_p) + sdot_k.dot(&d_q));
            put(nv + k - 1, m - 1, 2.0 * sdot_k.dot(&d_p) + s_k.dot(&d_q));
            put(2 * nv + k - 1, m - 1, s_k.dot(&d_p));
            k = model.joints[k].parent;
        }
        // Rows k ≻ m of the q̇ and q̈ blocks: what the turn about S_m leaves out.
        let psi_m = data.Uw[m].cross(&data.S[m]);
        let sdot_m = data.Sdot[m];
        for k in (m + 1)..=nv {
            if !model.is_ancestor_or_self(m, k) {
                continue;
            }
            let (s_k, sdot_k) = (data.S[k], data.Sdot[k]);
            let y_psi = data.Y[k].mul(&psi_m);
            let d_q = turned_q(data, work, k, &psi_m, &sdot_m);
            put(nv + k - 1, m - 1, 2.0 * sdot_m.cross(&s_k).dot(&work.p[k]) + 2.0 * sdot_k.dot(&y_psi) + s_k.dot(&d_q));
            put(2 * nv + k - 1, m - 1, s_k.dot(&y_psi));
        }
    }
}

/// The derivatives along `q_m` of the sums of `m`'s subtree: `∂F = S_m ×* F_m + Y_m A_m + B_m Ṡ_m`,
/// `∂P = S_m ×* P_m + Y_m ψ_m`, `∂Q = S_m ×* Q_m + δQ_m`.
fn moved_sums(data: &Data, work: &VelocityHessianWork, m: usize) -> (Force, Force, Force) {
    let (s_m, sdot_m) = (data.S[m], data.Sdot[m]);
    let psi_m = data.Uw[m].cross(&s_m);
    let d_f = s_m.cross_force(&data.f[m]) + data.Y[m].mul(&data.A[m]) + b_times(data, m, &sdot_m);
    let d_p = s_m.cross_force(&work.p[m]) + data.Y[m].mul(&psi_m);
    let d_q = s_m.cross_force(&work.q[m]) + turned_q(data, work, m, &psi_m, &sdot_m);
    (d_f, d_p, d_q)
}

/// `δQ_k = B_kᵀ ψ + Ṡ ×* P_k + (K_k + K_kᵀ) Ṡ` for a turn with `ψ = ψ_m`, `Ṡ = Ṡ_m`.
fn turned_q(data: &Data, work: &VelocityHessianWork, k: usize, psi: &Motion, sdot: &Motion) -> Force {
    let kk = &work.k[k];
    let s = sdot.to_vec6();
    let symmetric = Force::from_vec6(&(kk * s + kk.transpose() * s));
    b_transpose_times(data, k, psi) + sdot.cross_force(&work.p[k]) + symmetric
}

/// `B_kᵀ x = [B_ww,kᵀ x_ω + 2 p_k × x_v; 0]` (`B_k`'s only non-zero columns are its first three).
fn b_transpose_times(data: &Data, k: usize, x: &Motion) -> Force {
    Force::new(data.B_ww[k].transpose() * x.w + 2.0 * data.p[k].cross(&x.v), crate::spatial::Vec3::zeros())
}

/// `B_k x = [B_ww,k x_ω; −2 p_k × x_ω]` of body `k`'s composites.
fn b_times(data: &Data, k: usize, x: &Motion) -> Force {
    Force::new(data.B_ww[k] * x.w, -2.0 * data.p[k].cross(&x.w))
}

//! The gradient of one weighted sum of the joint torques and the root wrench,
//!
//! ```text
//!   φ(q, q̇, q̈) = ωᵀτ + u₀ · W,        τ = ID(q, q̇, q̈),  W = F₀ the root reaction wrench,
//! ```
//!
//! with respect to `q`, `q̇` and `q̈`, in O(n): [`super::rnea_derivatives`] contracted with `ω` and `u₀`
//! before its sums are formed. Its columns (world frame, Carpentier & Mansard 2018) read
//!
//! ```text
//!   ∂τᵢ/∂q_k = Sᵢ · (Yᵢ A_k + Bᵢ Ṡ_k)   (k ⪯ i),     Sᵢ · D_k   (i ≺ k),   D_k = S_k ×* F_k + Y_k A_k + B_k Ṡ_k
//!   ∂τᵢ/∂q̇_k = Sᵢ · (2Yᵢ Ṡ_k + Bᵢ S_k)  (k ⪯ i),     Sᵢ · E_k   (i ≺ k),   E_k = 2 Y_k Ṡ_k + B_k S_k
//!   H_ik     = Sᵢ · Yᵢ S_k             (k ⪯ i),     Sᵢ · Y_k S_k (i ≺ k),  and ∂W/∂(·)_k = D_k, E_k, Y_k S_k,
//! ```
//!
//! so with the subtree sums `G_k = Σ_{i ⪰ k} ωᵢ YᵢSᵢ` (a force), `β_k = Σ_{i ⪰ k} ωᵢ bᵢ` (`Sᵢ · Bᵢx = x_ω · bᵢ`,
//! `bᵢ = B_ww,ᵢᵀ Sᵢ_ω − 2 Sᵢ_v × pᵢ`) and the ancestor sum `U_k = u₀ + Σ_{0 < j ≺ k} ωⱼ Sⱼ` (a motion):
//!
//! ```text
//!   ∂φ/∂q_k = A_k · G_k + Ṡ_k,ω · β_k + U_k · D_k
//!   ∂φ/∂q̇_k = 2 Ṡ_k · G_k + S_k,ω · β_k + U_k · E_k
//!   ∂φ/∂q̈_k = S_k · G_k + U_k · Y_k S_k
//! ```
//!
//! One forward pass for `U`, one backward pass for the composites and `G`, `β`: no `k`-loop over ancestors.
//! This is the reverse-mode (adjoint) gradient that the planner's exact second-order term differences
//! (`plan/transcription/hessian.rs`): `nv` of these per node (`2·nv` where [`super::rnea_velocity_hessian`]
//! does not give the `q̇` block) instead of as many whole derivative matrices,
//! each after the first recomputing only the moved joint's subtree ([`super::rnea_gradient_moved`]).

use super::kinematics::{accelerations, placements, velocities};
use super::rnea::{body_forces, ExternalForces};
use super::rnea_derivatives::{body_seeds, check_sizes};
use super::Data;
use crate::model::Model;
use crate::spatial::{Force, Motion, Vec3};

/// `∇φ` of `φ = ωᵀτ + u₀·W` at `(q, q̇, q̈)` (external forces `fext` as in [`super::rnea::rnea`]) into `g_q`, `g_v`, `g_a` (each `nv`); also `τ` into `data.tau`
/// and `W` into `data.root_wrench`, as [`super::rnea::rnea`] leaves them. `u₀` pairs with the wrench
/// `W = [n; f]` as a twist: `u₀ · W = u₀,ω · n + u₀,v · f`.
#[allow(clippy::too_many_arguments)]
pub fn rnea_gradient(
    model: &Model,
    data: &mut Data,
    (q, v, a): (&[f64], &[f64], &[f64]),
    gravity: &Vec3,
    fext: ExternalForces,
    omega: &[f64],
    u0: &Motion,
    (g_q, g_v, g_a): (&mut [f64], &mut [f64], &mut [f64]),
) {
    placements(model, data, q);
    rnea_gradient_placed(model, data, (q, v, a), gravity, fext, omega, u0, (g_q, g_v, g_a));
}

/// [`rnea_gradient`] with the placements of `q` already in `data` (by [`placements`], or a previous call
/// at the same `q`): for a change of `q̇` or `q̈` alone.
#[allow(clippy::too_many_arguments)]
pub fn rnea_gradient_placed(
    model: &Model,
    data: &mut Data,
    (q, v, a): (&[f64], &[f64], &[f64]),
    gravity: &Vec3,
    fext: ExternalForces,
    omega: &[f64],
    u0: &Motion,
    (g_q, g_v, g_a): (&mut [f64], &mut [f64], &mut [f64]),
) {
    let nv = model.nv();
    check_sizes(model, q, v, a);
    assert!(
        omega.len() == nv && g_q.len() == nv && g_v.len() == nv && g_a.len() == nv,
        "ω and the gradient need {nv} entries each"
    );
    velocities(model, data, v);
    accelerations(model, data, v, a, gravity);
    body_forces(model, data, fext);
    body_seeds(model, data);
    ancestor_weights(model, data, omega, u0);
    for i in (1..model.bodies.len()).rev() {
        backward_step(model, data, omega, i, true, (&mut *g_q, &mut *g_v, &mut *g_a));
    }
    data.root_wrench = data.f[0];
}

/// Body `i`'s step of the backward pass, its children done: its own terms join its subtree sums
/// (`G_i += ωᵢ YᵢSᵢ`, `β_i += ωᵢ bᵢ`), then `τᵢ` and its gradient entries ([`body_gradient`]), and with `carry`
/// its composites and sums flow to the parent.
#[inline]
pub(super) fn backward_step(
    model: &Model,
    data: &mut Data,
    omega: &[f64],
    i: usize,
    carry: bool,
    g: (&mut [f64], &mut [f64], &mut [f64]),
) {
    let w_i = omega[i - 1];
    data.G[i] += data.Y[i].mul(&data.S[i]) * w_i;
    let b_i = own_beta(data, i);
    data.beta[i] += b_i * w_i;
    body_gradient(data, i, g);
    if carry {
        let parent = model.joints[i].parent;
        let (y_i, b_ww, p_i, f_i, g, beta) = (data.Y[i], data.B_ww[i], data.p[i], data.f[i], data.G[i], data.beta[i]);
        data.Y[parent] += y_i;
        data.B_ww[parent] += b_ww;
        data.p[parent] += p_i;
        data.f[parent] += f_i;
        data.G[parent] += g;
        data.beta[parent] += beta;
    }
}

/// `bᵢ = B_ww,ᵢᵀ Sᵢ_ω − 2 Sᵢ_v × pᵢ` of body `i`'s composites.
#[inline]
fn own_beta(data: &Data, i: usize) -> Vec3 {
    let s_i = &data.S[i];
    data.B_ww[i].transpose() * s_i.w - 2.0 * s_i.v.cross(&data.p[i])
}

/// `τᵢ` and body `i`'s entries of `∇φ` from its composites `Yᵢ, B_ww,ᵢ, pᵢ, Fᵢ` and subtree sums `G_i, β_i`
/// (both complete) and `U_i`: `∂φ/∂q_i = Aᵢ·G_i + Ṡᵢ,ω·β_i + U_i·D_i`, `∂φ/∂q̇_i = 2Ṡᵢ·G_i + Sᵢ,ω·β_i + U_i·E_i`,
/// `∂φ/∂q̈_i = Sᵢ·G_i + U_i·YᵢSᵢ` (module docs).
#[inline]
pub(super) fn body_gradient(data: &mut Data, i: usize, (g_q, g_v, g_a): (&mut [f64], &mut [f64], &mut [f64])) {
    let (s_i, sdot_i, a_i, u_i) = (data.S[i], data.Sdot[i], data.A[i], data.Uw[i]);
    let (y_i, b_ww, p_i, f_i) = (data.Y[i], data.B_ww[i], data.p[i], data.f[i]);
    let b_times = |x: &Motion| Force::new(b_ww * x.w, -2.0 * p_i.cross(&x.w));
    // τᵢ = Sᵢ · Fᵢ
    data.tau[i - 1] = s_i.dot(&f_i);
    // D_i = Sᵢ ×* Fᵢ + Yᵢ Aᵢ + Bᵢ Ṡᵢ,  E_i = 2 Yᵢ Ṡᵢ + Bᵢ Sᵢ
    let d_q = s_i.cross_force(&f_i) + y_i.mul(&a_i) + b_times(&sdot_i);
    let d_v = y_i.mul(&sdot_i) * 2.0 + b_times(&s_i);
    let (g, beta) = (data.G[i], data.beta[i]);
    g_q[i - 1] = a_i.dot(&g) + sdot_i.w.dot(&beta) + u_i.dot(&d_q);
    g_v[i - 1] = 2.0 * sdot_i.dot(&g) + s_i.w.dot(&beta) + u_i.dot(&d_v);
    g_a[i - 1] = s_i.dot(&g) + u_i.dot(&y_i.mul(&s_i));
}

/// `U_i = u₀ + Σ_{0 < j ≺ i} ωⱼ Sⱼ` from the root out (`U_i = U_λ(i) + ω_λ(i) S_λ(i)`), and `G`, `β` cleared.
fn ancestor_weights(model: &Model, data: &mut Data, omega: &[f64], u0: &Motion) {
    data.G.iter_mut().for_each(|g| *g = Force::ZERO);
    data.beta.iter_mut().for_each(|b| *b = Vec3::zeros());
    for i in 1..model.bodies.len() {
        let parent = model.joints[i].parent;
        data.Uw[i] = if parent == 0 { *u0 } else { data.Uw[parent].add_scaled(&data.S[parent], omega[parent - 1]) };
    }
}

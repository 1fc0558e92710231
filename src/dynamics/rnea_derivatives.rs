//! The analytical derivatives `∂τ/∂q`, `∂τ/∂q̇` (and `∂τ/∂q̈ = H`) of inverse dynamics (paper section 5.2,
//! eq. 24 and its pseudo-code), sharing the forward pass and the inflow pass of [`super::rnea`].
//!
//! The paper differentiates the local-frame recursion once per joint variable (forward mode, O(n²)).
//! In world coordinates the same derivatives collapse (Carpentier & Mansard 2018): moving `q_k` rotates
//! the whole subtree of `k` about `S_k`, so every quantity attached to it changes by a cross product with
//! `S_k`, plus two corrections because the parent's velocity and acceleration do not rotate:
//!
//! ```text
//! ∂vⱼ/∂q_k = S_k × vⱼ + Ṡ_k                       (j in subtree(k); Ṡ_k = v_λ(k) × S_k)
//! ∂aⱼ/∂q_k = S_k × aⱼ + A_k + Ṡ_k × vⱼ             (A_k = a_λ(k) × S_k + v_λ(k) × Ṡ_k)
//! ∂fⱼ/∂q_k = S_k ×* fⱼ + Iⱼ A_k + Bⱼ Ṡ_k           (Bⱼ x = Iⱼ(x × vⱼ) + x ×* Iⱼvⱼ + vⱼ ×* Iⱼ x)
//! ```
//!
//! Summed over a subtree with composite `Yᵢ = Σ Iⱼ`, `Bᵢ = Σ Bⱼ` and `Fᵢ = Σ fⱼ`, and using
//! `∂Sᵢ/∂q_k = S_k × Sᵢ` (whose term cancels `S_k ×* Fᵢ`):
//!
//! ```text
//! ∂τᵢ/∂q_k = Sᵢ · (Yᵢ A_k + Bᵢ Ṡ_k)                          k ⪯ i
//!          = Sᵢ · (S_k ×* F_k + Y_k A_k + B_k Ṡ_k)           i ≺ k
//! ∂τᵢ/∂q̇_k = Sᵢ · (2 Yᵢ Ṡ_k + Bᵢ S_k)                       k ⪯ i
//!          = Sᵢ · (2 Y_k Ṡ_k + B_k S_k)                       i ≺ k
//! H_ik     = Sᵢ · Yᵢ S_k  (k ⪯ i),   Sᵢ · Y_k S_k  (i ≺ k)
//! ```
//!
//! `Bⱼ` has only its left 6×3 column block non-zero: `Bⱼ x = [B_ww x_ω; −2 pⱼ × x_ω]` with
//! `B_ww = ω̃I_o + (ω̃I_o)ᵀ − ñ − h uᵀ − u hᵀ + 2(u·h)1` and `pⱼ` the body's linear momentum (`vⱼ = [ω; u]`,
//! `Iⱼvⱼ = [n; p]`, `h = m c`). `docs/dynamics.md` has the derivation.

use super::kinematics::{accelerations, placements, velocities};
use super::rnea::{body_forces, ExternalForces};
use super::Data;
use crate::model::Model;
use crate::spatial::{skew, Force, Mat3, Motion, Vec3};

/// `τ`, `∂τ/∂q`, `∂τ/∂q̇` and `H` at `(q, q̇, q̈)` into `data.tau`, `data.dtau_dq`, `data.dtau_dv`,
/// `data.M`. Also the root reaction wrench and its derivatives (`data.dW_dq`, `dW_dv`, `dW_da`): a column
/// `k` is the derivative of every strict ancestor's joint force, the root's included.
pub fn rnea_derivatives(model: &Model, data: &mut Data, q: &[f64], v: &[f64], a: &[f64], gravity: &Vec3, fext: ExternalForces) {
    let nb = model.bodies.len();
    check_sizes(model, q, v, a);
    placements(model, data, q);
    velocities(model, data, v);
    accelerations(model, data, v, a, gravity);
    body_forces(model, data, fext);
    body_seeds(model, data);
    for i in (1..nb).rev() {
        let (s_i, y_i, b_ww, p_i, f_i) = (data.S[i], data.Y[i], data.B_ww[i], data.p[i], data.f[i]);
        let b_times = |x: &Motion| Force::new(b_ww * x.w, -2.0 * p_i.cross(&x.w));
        data.tau[i - 1] = s_i.dot(&f_i);
        // Row i against k ⪯ i: Sᵢ·Yᵢx = (YᵢSᵢ)·x and Sᵢ·Bᵢx = x_ω·(B_wwᵀSᵢ_ω − 2 Sᵢ_v × pᵢ).
        let y_s = y_i.mul(&s_i);
        let b_s = b_ww.transpose() * s_i.w - 2.0 * s_i.v.cross(&p_i);
        let mut k = i;
        while k > 0 {
            let (s_k, sdot_k) = (&data.S[k], &data.Sdot[k]);
            data.dtau_dq[(i - 1, k - 1)] = data.A[k].dot(&y_s) + b_s.dot(&sdot_k.w);
            data.dtau_dv[(i - 1, k - 1)] = 2.0 * sdot_k.dot(&y_s) + b_s.dot(&s_k.w);
            let h = s_k.dot(&y_s);
            data.M[(i - 1, k - 1)] = h;
            data.M[(k - 1, i - 1)] = h;
            k = model.joints[k].parent;
        }
        // Column i against the strict ancestors j ≺ i.
        let (sdot_i, a_i) = (data.Sdot[i], data.A[i]);
        let d_q = s_i.cross_force(&f_i) + y_i.mul(&a_i) + b_times(&sdot_i);
        let d_v = y_i.mul(&sdot_i) * 2.0 + b_times(&s_i);
        data.dW_dq[i - 1] = d_q;
        data.dW_dv[i - 1] = d_v;
        data.dW_da[i - 1] = y_s;
        let mut j = model.joints[i].parent;
        while j > 0 {
            data.dtau_dq[(j - 1, i - 1)] = data.S[j].dot(&d_q);
            data.dtau_dv[(j - 1, i - 1)] = data.S[j].dot(&d_v);
            j = model.joints[j].parent;
        }
        let parent = model.joints[i].parent;
        data.Y[parent] += y_i;
        data.B_ww[parent] += b_ww;
        data.p[parent] += p_i;
        data.f[parent] += f_i;
    }
    data.root_wrench = data.f[0];
}

/// Panics unless `q`, `v`, `a` each have `model.nv()` entries.
pub(super) fn check_sizes(model: &Model, q: &[f64], v: &[f64], a: &[f64]) {
    let nv = model.nv();
    assert!(
        q.len() == nv && v.len() == nv && a.len() == nv,
        "q, q̇, q̈ need {nv} entries each, not {}, {}, {}",
        q.len(),
        v.len(),
        a.len()
    );
}

/// Each body's seeds of the derivative recursions after the forward pass: `Aᵢ = a_λ(i) × Sᵢ + v_λ(i) × Ṡᵢ`,
/// `B_ww,ᵢ`, the linear momentum `pᵢ`, and `Yᵢ = Iᵢ` (made composite by the backward pass).
pub(super) fn body_seeds(model: &Model, data: &mut Data) {
    for i in 0..model.bodies.len() {
        body_seed(model, data, i);
    }
}

/// Body `i`'s step of [`body_seeds`].
#[inline]
pub(super) fn body_seed(model: &Model, data: &mut Data, i: usize) {
    let parent = model.joints[i].parent;
    if i > 0 {
        data.A[i] = data.a[parent].cross(&data.S[i]) + data.v[parent].cross(&data.Sdot[i]);
    }
    let inertia = data.oI[i];
    let momentum = inertia.mul(&data.v[i]);
    let (w, u) = (data.v[i].w, data.v[i].v);
    // B_ww = ω̃I_o + (ω̃I_o)ᵀ − ñ − h uᵀ − u hᵀ + 2(u·h)1
    let t = skew(&w) * inertia.i_o;
    data.B_ww[i] = t + t.transpose() - skew(&momentum.n) - inertia.h * u.transpose() - u * inertia.h.transpose()
        + Mat3::identity() * (2.0 * u.dot(&inertia.h));
    data.p[i] = momentum.f;
    data.Y[i] = inertia;
}
